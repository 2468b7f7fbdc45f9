// Device: the physical device lpir-gseg runs on and its logical device with one compute queue.
// Choice: a selector of digits is an index into vkEnumeratePhysicalDevices; any other non-empty
// selector is a case-insensitive substring of the device name; an empty one takes the first
// usable device, discrete GPUs first, then integrated, virtual, CPU (lavapipe), other; with
// gpu_only, the same without CPU drivers (Backend::kAuto: the CPU reference beats lavapipe on the
// same cores, docs/speed.md). Usable: Vulkan 1.2, shaderInt64 (the exact helpers of
// shaders/common/exact.glsl), a compute queue.
#pragma once
#include <vulkan/vulkan.h>

#include <cstdint>
#include <string>
#include <vector>

#include "host/vk/instance.h"
#include "host/vk/result.h"

namespace lpir::vk {

class Device {
 public:
  // Errors name every device seen and why it was not taken; Error::no_device when the instance
  // has no physical device at all. `gpu_only` (only with an empty selector) leaves out
  // VK_PHYSICAL_DEVICE_TYPE_CPU devices; when one of those is all there is to take, the error is
  // Error::cpu_driver_only, one line: "the only Vulkan device is a CPU driver (<name>); --backend
  // vulkan uses it", <name> without its parenthesised details ("llvmpipe").
  static Result<Device> Create(const Instance& instance, const std::string& selector = "",
                               bool gpu_only = false);
  // One line per physical device: index, name, type, API version, and "usable" or why not.
  static Result<std::vector<std::string>> Describe(const Instance& instance);

  Device(Device&& other) noexcept;
  Device& operator=(Device&& other) noexcept;
  Device(const Device&) = delete;
  Device& operator=(const Device&) = delete;
  ~Device();  // waits for the device to be idle, then destroys it

  VkDevice handle() const { return device_; }
  VkPhysicalDevice physical() const { return physical_; }
  VkQueue queue() const { return queue_; }
  uint32_t queue_family() const { return queue_family_; }
  const VkPhysicalDeviceProperties& properties() const { return properties_; }
  const VkPhysicalDeviceLimits& limits() const { return properties_.limits; }
  const VkPhysicalDeviceMemoryProperties& memory_properties() const { return memory_; }
  std::string name() const { return properties_.deviceName; }
  // Valid bits of the queue's timestamps (0: no timestamps on this queue).
  uint32_t timestamp_valid_bits() const { return timestamp_valid_bits_; }

  // The first memory type allowed by `type_bits` with every `required` flag, preferring one that
  // also has every `preferred` flag.
  Result<uint32_t> FindMemoryType(uint32_t type_bits, VkMemoryPropertyFlags required,
                                  VkMemoryPropertyFlags preferred) const;

 private:
  Device() = default;
  void Release();

  VkPhysicalDevice physical_ = VK_NULL_HANDLE;
  VkDevice device_ = VK_NULL_HANDLE;
  VkQueue queue_ = VK_NULL_HANDLE;
  uint32_t queue_family_ = 0;
  uint32_t timestamp_valid_bits_ = 0;
  VkPhysicalDeviceProperties properties_{};
  VkPhysicalDeviceMemoryProperties memory_{};
};

}  // namespace lpir::vk
