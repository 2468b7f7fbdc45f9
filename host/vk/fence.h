// Fence: signalled by a queue submission, waited for by the host.
#pragma once
#include <vulkan/vulkan.h>

#include <cstdint>

#include "host/vk/device.h"
#include "host/vk/handle.h"
#include "host/vk/result.h"

namespace lpir::vk {

class Fence {
 public:
  static constexpr uint64_t kDefaultTimeoutNs = 120'000'000'000ull;  // 2 min: lavapipe, big clouds

  static Result<Fence> Create(const Device& device);

  // Waits until signalled (VK_TIMEOUT after `timeout_ns` is an error), then resets the fence for
  // the next submission.
  Status WaitAndReset(uint64_t timeout_ns = kDefaultTimeoutNs);

  VkFence handle() const { return fence_.get(); }

 private:
  Fence() = default;

  DeviceHandle<VkFence, vkDestroyFence> fence_;
};

}  // namespace lpir::vk
