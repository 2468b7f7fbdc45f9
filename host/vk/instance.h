// Instance: the VkInstance (Vulkan 1.2), optionally with the Khronos validation layer (its
// synchronization validation on too, where the layer offers VK_EXT_validation_features) and a
// debug messenger that prints every warning and error to stderr and counts them, so tests can
// assert that a run produced none.
#pragma once
#include <vulkan/vulkan.h>

#include <cstdint>
#include <memory>

#include "host/vk/result.h"

namespace lpir::vk {

struct InstanceOptions {
  bool validation = false;  // VK_LAYER_KHRONOS_validation + VK_EXT_debug_utils messenger
};

class Instance {
 public:
  // Errors: the loader older than 1.2; validation asked for but the layer is not installed;
  // vkCreateInstance failing (no driver at all: Error::no_device).
  static Result<Instance> Create(const InstanceOptions& options);

  Instance(Instance&& other) noexcept;
  Instance& operator=(Instance&& other) noexcept;
  Instance(const Instance&) = delete;
  Instance& operator=(const Instance&) = delete;
  ~Instance();

  VkInstance handle() const { return instance_; }
  bool validation() const { return messenger_ != VK_NULL_HANDLE; }
  // Validation warnings and errors this instance's messenger received so far.
  uint64_t messages() const;
  // Every one the process received, including those of instances already destroyed (leaks are
  // reported while vkDestroyDevice and vkDestroyInstance run).
  static uint64_t TotalMessages();

  struct Log;  // the messenger's count, on the heap: the messenger points at it across moves

 private:
  Instance() = default;
  void Release();

  VkInstance instance_ = VK_NULL_HANDLE;
  VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
  PFN_vkDestroyDebugUtilsMessengerEXT destroy_messenger_ = nullptr;
  std::unique_ptr<Log> log_;
};

}  // namespace lpir::vk
