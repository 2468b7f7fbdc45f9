// Transfer: moves bytes between the host and buffers. A kHostVisible buffer is read and written
// through its mapping; a kDeviceLocal one through a staging buffer, a copy command and a wait,
// in chunks of the staging size. Each call waits for its copy, so it is for set-up, tests and
// tools; a frame records its uploads and downloads into its own command buffer instead.
#pragma once
#include <vulkan/vulkan.h>

#include "host/vk/buffer.h"
#include "host/vk/command_buffer.h"
#include "host/vk/device.h"
#include "host/vk/fence.h"
#include "host/vk/result.h"

namespace lpir::vk {

class Transfer {
 public:
  static constexpr VkDeviceSize kDefaultStagingBytes = VkDeviceSize(8) << 20;

  static Result<Transfer> Create(const Device& device,
                                 VkDeviceSize staging_bytes = kDefaultStagingBytes);

  // Writes `bytes` at `offset` of `dst`; later submitted dispatches see the data. For a
  // kDeviceLocal buffer, earlier submitted work on `dst` is ordered before the copy; a kHostVisible
  // one is written at once, so the caller must have waited for the work that uses it.
  Status Upload(const Buffer& dst, const void* src, VkDeviceSize bytes, VkDeviceSize offset = 0);
  // Reads `bytes` at `offset` of `src`, after the earlier submitted work that wrote it. For a
  // kHostVisible buffer the caller must have waited for that work (and recorded ComputeToHost).
  Status Download(const Buffer& src, void* dst, VkDeviceSize bytes, VkDeviceSize offset = 0);

 private:
  Transfer(Buffer staging, CommandBuffer cmd, Fence fence)
      : staging_(std::move(staging)), cmd_(std::move(cmd)), fence_(std::move(fence)) {}

  Buffer staging_;
  CommandBuffer cmd_;
  Fence fence_;
};

}  // namespace lpir::vk
