// Buffer creation: the buffer, a memory type of the asked kind, binding and mapping.
#include "host/vk/buffer.h"

#include <algorithm>
#include <string>

namespace lpir::vk {

Result<Buffer> Buffer::Create(const Device& device, VkDeviceSize bytes, MemoryKind kind) {
  Buffer buffer;
  buffer.size_ = std::max<VkDeviceSize>(bytes, 16);
  const VkDeviceSize size = buffer.size();
  buffer.kind_ = kind;
  const std::string what = std::to_string(size) + " bytes";

  VkBufferCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO;
  info.size = size;
  info.usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT |
               VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT |
               VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT;
  info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  VkBuffer handle = VK_NULL_HANDLE;
  LPIR_VK_CHECK(vkCreateBuffer(device.handle(), &info, nullptr, &handle), "vkCreateBuffer", what);
  buffer.buffer_ = DeviceHandle<VkBuffer, vkDestroyBuffer>(device.handle(), handle);

  VkMemoryRequirements needs{};
  vkGetBufferMemoryRequirements(device.handle(), handle, &needs);
  const bool host = kind == MemoryKind::kHostVisible;
  // Readback wants cached host memory; device buffers want device-local memory only.
  LPIR_VK_ASSIGN_OR_RETURN(const uint32_t type,
                           device.FindMemoryType(needs.memoryTypeBits,
                                                 host ? VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT |
                                                            VK_MEMORY_PROPERTY_HOST_COHERENT_BIT
                                                      : VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT,
                                                 host ? VK_MEMORY_PROPERTY_HOST_CACHED_BIT : 0));

  VkMemoryAllocateInfo alloc{};
  alloc.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO;
  alloc.allocationSize = needs.size;
  alloc.memoryTypeIndex = type;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  LPIR_VK_CHECK(vkAllocateMemory(device.handle(), &alloc, nullptr, &memory), "vkAllocateMemory",
                what);
  buffer.memory_ = DeviceHandle<VkDeviceMemory, vkFreeMemory>(device.handle(), memory);
  LPIR_VK_CHECK(vkBindBufferMemory(device.handle(), handle, memory, 0), "vkBindBufferMemory", what);
  if (host)
    LPIR_VK_CHECK(vkMapMemory(device.handle(), memory, 0, VK_WHOLE_SIZE, 0, buffer.mapped_.out()),
                  "vkMapMemory", what);
  return buffer;
}

}  // namespace lpir::vk
