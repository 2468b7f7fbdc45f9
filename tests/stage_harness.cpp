#include "tests/stage_harness.h"

#include <utility>

namespace lpir::test {

StageHarness::StageHarness(const vk::Device& device, std::string stage)
    : device_(device), stage_(std::move(stage)) {
  vk::Result<vk::Transfer> transfer = vk::Transfer::Create(device_);
  if (transfer.ok()) {
    transfer_.emplace(std::move(transfer).value());
  } else {
    status_ = transfer.error();
  }
}

const vk::Buffer* StageHarness::Make(VkDeviceSize bytes) {
  if (!status_.ok()) return nullptr;
  vk::Result<vk::Buffer> buffer = vk::Buffer::Create(device_, bytes, vk::MemoryKind::kDeviceLocal);
  if (!buffer.ok()) {
    status_ = buffer.error();
    return nullptr;
  }
  buffers_.push_back(std::move(buffer).value());
  return &buffers_.back();
}

const vk::Buffer* StageHarness::Input(const char* name, const void* data, size_t bytes) {
  const vk::Buffer* buffer = Make(bytes);
  if (!buffer || bytes == 0) return buffer;
  const vk::Status uploaded = transfer_->Upload(*buffer, data, bytes);
  if (uploaded.ok()) return buffer;
  status_ = vk::UsageError(stage_, std::string("uploading ") + name + ": " + uploaded.message());
  return nullptr;
}

vk::Status StageHarness::DownloadOutputs() {
  for (const Output& out : outputs_)
    LPIR_VK_RETURN_IF_ERROR(transfer_->Download(*out.buffer, out.data, out.bytes));
  return vk::Status();
}

}  // namespace lpir::test
