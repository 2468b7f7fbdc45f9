// Uploads and downloads through mappings or a staging buffer.
#include "host/vk/transfer.h"

#include <algorithm>
#include <cstring>
#include <string>

namespace lpir::vk {
namespace {

Status CheckRange(const Buffer& buffer, VkDeviceSize bytes, VkDeviceSize offset, const char* op) {
  if (offset <= buffer.size() && bytes <= buffer.size() - offset) return Status();
  Error e;
  e.result = VK_ERROR_UNKNOWN;
  e.message = std::string(op) + " of " + std::to_string(bytes) + " bytes at offset " +
              std::to_string(offset) + " of a buffer of " + std::to_string(buffer.size());
  return e;
}

}  // namespace

Result<Transfer> Transfer::Create(const Device& device, VkDeviceSize staging_bytes) {
  LPIR_VK_ASSIGN_OR_RETURN(Buffer staging,
                           Buffer::Create(device, staging_bytes, MemoryKind::kHostVisible));
  LPIR_VK_ASSIGN_OR_RETURN(CommandBuffer cmd, CommandBuffer::Create(device));
  LPIR_VK_ASSIGN_OR_RETURN(Fence fence, Fence::Create(device));
  return Transfer(std::move(staging), std::move(cmd), std::move(fence));
}

Status Transfer::Upload(const Buffer& dst, const void* src, VkDeviceSize bytes,
                        VkDeviceSize offset) {
  LPIR_VK_RETURN_IF_ERROR(CheckRange(dst, bytes, offset, "upload"));
  if (dst.mapped()) {
    std::memcpy(static_cast<char*>(dst.mapped()) + offset, src, bytes);
    return Status();
  }
  const char* from = static_cast<const char*>(src);
  for (VkDeviceSize done = 0; done < bytes;) {
    const VkDeviceSize chunk = std::min(bytes - done, staging_.size());
    std::memcpy(staging_.mapped(), from + done, chunk);
    LPIR_VK_RETURN_IF_ERROR(cmd_.Begin());
    // Earlier dispatches and copies touching dst finish before the copy overwrites it.
    cmd_.Barrier(VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
                 VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_WRITE_BIT,
                 VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT);
    cmd_.CopyBuffer(staging_, dst, chunk, 0, offset + done);
    cmd_.TransferToCompute();
    LPIR_VK_RETURN_IF_ERROR(cmd_.End());
    LPIR_VK_RETURN_IF_ERROR(cmd_.SubmitAndWait(fence_));
    done += chunk;
  }
  return Status();
}

Status Transfer::Download(const Buffer& src, void* dst, VkDeviceSize bytes, VkDeviceSize offset) {
  LPIR_VK_RETURN_IF_ERROR(CheckRange(src, bytes, offset, "download"));
  if (src.mapped()) {
    std::memcpy(dst, static_cast<const char*>(src.mapped()) + offset, bytes);
    return Status();
  }
  char* to = static_cast<char*>(dst);
  for (VkDeviceSize done = 0; done < bytes;) {
    const VkDeviceSize chunk = std::min(bytes - done, staging_.size());
    LPIR_VK_RETURN_IF_ERROR(cmd_.Begin());
    cmd_.Barrier(VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
                 VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_WRITE_BIT,
                 VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_READ_BIT);
    cmd_.CopyBuffer(src, staging_, chunk, offset + done, 0);
    cmd_.TransferToHost();
    LPIR_VK_RETURN_IF_ERROR(cmd_.End());
    LPIR_VK_RETURN_IF_ERROR(cmd_.SubmitAndWait(fence_));
    std::memcpy(to + done, staging_.mapped(), chunk);
    done += chunk;
  }
  return Status();
}

}  // namespace lpir::vk
