// DeviceHandle: the move-only owner of one Vulkan object that a VkDevice destroys (buffer,
// memory, pipeline, pool, fence, ...), and ResetOnMove for the plain values beside it. The classes
// of host/vk/ hold their objects in these, so their own moves are the defaults and their
// destructors release everything in reverse order of declaration. Only the factories of host/vk/
// construct them.
#pragma once
#include <vulkan/vulkan.h>

#include <utility>

namespace lpir::vk {

template <class H, void (*Destroy)(VkDevice, H, const VkAllocationCallbacks*)>
class DeviceHandle {
 public:
  DeviceHandle() = default;
  DeviceHandle(VkDevice device, H handle) : device_(device), handle_(handle) {}
  DeviceHandle(DeviceHandle&& other) noexcept
      : device_(std::exchange(other.device_, VK_NULL_HANDLE)),
        handle_(std::exchange(other.handle_, VK_NULL_HANDLE)) {}
  DeviceHandle& operator=(DeviceHandle&& other) noexcept {
    if (this != &other) {
      Release();
      device_ = std::exchange(other.device_, VK_NULL_HANDLE);
      handle_ = std::exchange(other.handle_, VK_NULL_HANDLE);
    }
    return *this;
  }
  DeviceHandle(const DeviceHandle&) = delete;
  DeviceHandle& operator=(const DeviceHandle&) = delete;
  ~DeviceHandle() { Release(); }

  H get() const { return handle_; }
  VkDevice device() const { return device_; }

 private:
  void Release() {
    if (handle_ != VK_NULL_HANDLE) Destroy(device_, handle_, nullptr);
    handle_ = VK_NULL_HANDLE;
  }

  VkDevice device_ = VK_NULL_HANDLE;
  H handle_ = VK_NULL_HANDLE;
};

// A plain value (a handle owned by something else, a mapping) that a move leaves at its zero, so
// a moved-from owner never points at what it gave away.
template <class T>
class ResetOnMove {
 public:
  ResetOnMove() = default;
  ResetOnMove(T value) : value_(value) {}  // NOLINT: implicit, for assignments
  ResetOnMove(ResetOnMove&& other) noexcept : value_(std::exchange(other.value_, T{})) {}
  ResetOnMove& operator=(ResetOnMove&& other) noexcept {
    value_ = std::exchange(other.value_, T{});
    return *this;
  }
  ResetOnMove(const ResetOnMove&) = delete;
  ResetOnMove& operator=(const ResetOnMove&) = delete;

  T get() const { return value_; }
  T* out() { return &value_; }  // for vkAllocate*/vkMapMemory outputs

 private:
  T value_{};
};

}  // namespace lpir::vk
