// Fence creation, wait and reset.
#include "host/vk/fence.h"

#include <string>

namespace lpir::vk {

Result<Fence> Fence::Create(const Device& device) {
  VkFenceCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO;
  VkFence handle = VK_NULL_HANDLE;
  LPIR_VK_CHECK(vkCreateFence(device.handle(), &info, nullptr, &handle), "vkCreateFence", "");
  Fence fence;
  fence.fence_ = DeviceHandle<VkFence, vkDestroyFence>(device.handle(), handle);
  return fence;
}

Status Fence::WaitAndReset(uint64_t timeout_ns) {
  const VkFence handle = fence_.get();
  LPIR_VK_CHECK(vkWaitForFences(fence_.device(), 1, &handle, VK_TRUE, timeout_ns),
                "vkWaitForFences", "waited " + std::to_string(timeout_ns / 1000000) + " ms");
  LPIR_VK_CHECK(vkResetFences(fence_.device(), 1, &handle), "vkResetFences", "");
  return Status();
}

}  // namespace lpir::vk
