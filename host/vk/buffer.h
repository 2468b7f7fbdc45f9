// Buffer: one VkBuffer with its own memory, usable as storage buffer, uniform buffer and transfer
// source and destination. kDeviceLocal buffers are never mapped (Transfer moves data through a
// staging buffer, the path a discrete GPU needs); kHostVisible buffers are host-coherent and
// mapped for their whole life (staging, readback, small per-frame inputs).
#pragma once
#include <vulkan/vulkan.h>

#include <cstddef>

#include "host/vk/device.h"
#include "host/vk/handle.h"
#include "host/vk/result.h"

namespace lpir::vk {

enum class MemoryKind { kDeviceLocal, kHostVisible };

class Buffer {
 public:
  // `bytes` == 0 allocates 16 bytes, so an empty cloud still has something to bind.
  static Result<Buffer> Create(const Device& device, VkDeviceSize bytes, MemoryKind kind);

  Buffer() = default;  // owns nothing (as after a move), until a created buffer is moved in
  Buffer(Buffer&&) noexcept = default;
  Buffer& operator=(Buffer&&) noexcept = default;

  VkBuffer handle() const { return buffer_.get(); }
  VkDeviceSize size() const { return size_.get(); }
  MemoryKind kind() const { return kind_; }
  // The mapping of a kHostVisible buffer (coherent: no flush needed), nullptr otherwise.
  void* mapped() const { return mapped_.get(); }

 private:
  DeviceHandle<VkDeviceMemory, vkFreeMemory> memory_;  // freed after the buffer (and unmapped)
  DeviceHandle<VkBuffer, vkDestroyBuffer> buffer_;
  ResetOnMove<VkDeviceSize> size_;
  MemoryKind kind_ = MemoryKind::kDeviceLocal;
  ResetOnMove<void*> mapped_;
};

}  // namespace lpir::vk
