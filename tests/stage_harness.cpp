#include "tests/stage_harness.h"

#include <algorithm>
#include <cstring>
#include <string>
#include <utility>

namespace lpir::test {
namespace {

constexpr VkDeviceSize kMinBytes = 16;  // an empty frame's buffers still bind
constexpr uint8_t kPoison = 0xEE;

VkDeviceSize WordBytes(uint64_t elements, size_t size) {
  return (VkDeviceSize(elements) * size + 3) / 4 * 4;
}

uint64_t LimitOf(Per per, const FrameLimits& l) {
  return per == Per::kPoint ? l.points : per == Per::kPixel ? l.pixels : l.cells;
}

uint64_t ItemsOfSize(Per per, const vk::FrameSize& s) {
  return per == Per::kPoint ? s.n : per == Per::kPixel ? s.pixels : s.cells;
}

bool IsStage(const char* a, const char* b) { return std::strcmp(a, b) == 0; }

// The index of `stage` in the table's run order (kStageCount when it is none).
int StageIndex(const char* stage) {
  int i = 0;
#define LPIR_STAGE(name, Type, parameters) \
  if (IsStage(#name, stage)) return i;     \
  ++i;
#define LPIR_BUFFER LPIR_IGNORE
#define LPIR_HOST_BUFFER LPIR_IGNORE
#define LPIR_SCRATCH LPIR_IGNORE
#include "reference_cpu/stage_table.def"
  return i;
}

}  // namespace

FrameBench::FrameBench(const vk::Device& device, const FrameLimits& limits, const Tables* tables)
    : device_(device), limits_(limits) {
  auto make = [&](vk::Buffer& buffer, VkDeviceSize bytes) {
    if (!status_.ok()) return;
    vk::Result<vk::Buffer> made =
        vk::Buffer::Create(device_, std::max(bytes, kMinBytes), vk::MemoryKind::kDeviceLocal);
    if (made.ok())
      buffer = std::move(made).value();
    else
      status_ = made.error();
  };
  vk::Result<vk::Transfer> transfer = vk::Transfer::Create(device_);
  if (!transfer.ok()) {
    status_ = transfer.error();
    return;
  }
  transfer_.emplace(std::move(transfer).value());
  const std::pair<vk::Buffer*, const std::vector<float>*> table_values[] = {
      {&tables_.column_dir, tables ? &tables->column_dir : nullptr},
      {&tables_.beam_bound, tables ? &tables->beam_bound : nullptr},
      {&tables_.beam_origin, tables ? &tables->beam_origin : nullptr},
      {&tables_.ring_bound2, tables ? &tables->ring_bound2 : nullptr},
      {&tables_.ring_inner, tables ? &tables->ring_inner : nullptr}};
  for (const auto& [buffer, values] : table_values) {
    make(*buffer, values ? 4 * values->size() : 0);
    if (status_.ok() && values && !values->empty())
      status_ = transfer_->Upload(*buffer, values->data(), 4 * values->size());
  }
  buffers_.tables = &tables_;
  make(buffers_.params, sizeof(Params));
  make(buffers_.points, WordBytes(limits.points, 16));
  make(buffers_.ring, WordBytes(limits.points, 4));
#define LPIR_STAGE LPIR_IGNORE
#define LPIR_BUFFER(stage, name, type, per, stride) \
  make(buffers_.name, WordBytes(LimitOf(Per::per, limits) * stride, sizeof(type)));
#define LPIR_HOST_BUFFER LPIR_IGNORE
#define LPIR_SCRATCH(stage, name, type, per, stride, extra) \
  make(buffers_.name, WordBytes(LimitOf(Per::per, limits) * stride + extra, sizeof(type)));
#include "reference_cpu/stage_table.def"
}

vk::Result<vk::FrameSize> FrameBench::Fill(const char* stage, const Params& p, const Cloud* cloud,
                                           const Frame& in) {
  LPIR_VK_RETURN_IF_ERROR(status_);
  const uint32_t n = cloud ? uint32_t(cloud->size()) : in.n;
  const vk::FrameSize size{n, p.width, p.beams, p.width * p.beams, CellCount(p)};
  if (n > limits_.points || size.pixels > limits_.pixels || size.cells > limits_.cells)
    return vk::UsageError(stage, "a frame of " + std::to_string(n) + " points, " +
                                     std::to_string(size.pixels) + " pixels and " +
                                     std::to_string(size.cells) + " cells is beyond the bench's");
  if (cloud && in.n && in.n != n)
    return vk::UsageError(stage, "the frame holds " + std::to_string(in.n) + " points, the cloud " +
                                     std::to_string(n));
  Params params = p;
  if (cloud) params.has_ring = cloud->ring.empty() ? 0u : 1u;
  LPIR_VK_RETURN_IF_ERROR(transfer_->Upload(buffers_.params, &params, sizeof(Params)));
  if (cloud && n)
    LPIR_VK_RETURN_IF_ERROR(
        transfer_->Upload(buffers_.points, cloud->xyzi.data(), 16 * VkDeviceSize(n)));
  if (cloud && n && params.has_ring)
    LPIR_VK_RETURN_IF_ERROR(
        transfer_->Upload(buffers_.ring, cloud->ring.data(), 4 * VkDeviceSize(n)));
  const int index = StageIndex(stage);
  std::vector<uint8_t> poison;
  auto fill = [&](const char* writer, const char* name, const vk::Buffer& buffer, const auto& v,
                  uint64_t elements) -> vk::Status {
    const VkDeviceSize bytes = WordBytes(elements, sizeof(v[0]));
    if (StageIndex(writer) < index && !v.empty()) {
      if (v.size() != elements)
        return vk::UsageError(stage, std::string(name) + " holds " + std::to_string(v.size()) +
                                         " elements, not " + std::to_string(elements));
      return transfer_->Upload(buffer, v.data(), elements * sizeof(v[0]));
    }
    if (bytes == 0) return vk::Status();
    poison.assign(bytes, kPoison);
    return transfer_->Upload(buffer, poison.data(), bytes);
  };
  vk::Status filled;
#define LPIR_STAGE LPIR_IGNORE
#define LPIR_BUFFER(writer, name, type, per, stride) \
  if (filled.ok())                                   \
    filled = fill(#writer, #name, buffers_.name, in.name, ItemsOfSize(Per::per, size) * stride);
#define LPIR_HOST_BUFFER LPIR_IGNORE
#define LPIR_SCRATCH LPIR_IGNORE
#include "reference_cpu/stage_table.def"
  LPIR_VK_RETURN_IF_ERROR(filled);
  return size;
}

vk::Status FrameBench::Read(const char* stage, const vk::FrameSize& size, Frame* out) {
  out->n = size.n;
  vk::Status read;
  auto get = [&](const vk::Buffer& buffer, auto& v, uint64_t elements) {
    v.assign(elements, {});
    if (read.ok() && elements)
      read = transfer_->Download(buffer, v.data(), elements * sizeof(v[0]));
  };
#define LPIR_STAGE LPIR_IGNORE
#define LPIR_BUFFER(writer, name, type, per, stride) \
  if (IsStage(#writer, stage)) get(buffers_.name, out->name, ItemsOfSize(Per::per, size) * stride);
#define LPIR_HOST_BUFFER(writer, name, type, per, stride) \
  if (IsStage(#writer, stage)) out->name.clear();
#define LPIR_SCRATCH LPIR_IGNORE
#include "reference_cpu/stage_table.def"
  return read;
}

vk::Status FrameBench::Bytes(const char* name, size_t count, std::vector<uint8_t>* bytes) {
  const vk::Buffer* buffer = nullptr;
#define LPIR_STAGE LPIR_IGNORE
#define LPIR_BUFFER(writer, buffer_name, type, per, stride) \
  if (IsStage(#buffer_name, name)) buffer = &buffers_.buffer_name;
#define LPIR_HOST_BUFFER LPIR_IGNORE
#define LPIR_SCRATCH LPIR_IGNORE
#include "reference_cpu/stage_table.def"
  if (!buffer) return vk::UsageError("harness", std::string("no device buffer ") + name);
  if (count > buffer->size()) return vk::UsageError("harness", std::string(name) + " is smaller");
  bytes->resize(count);
  if (!count) return vk::Status();
  return transfer_->Download(*buffer, bytes->data(), bytes->size());
}

}  // namespace lpir::test
