// Context: what every Vulkan stage runs on, the instance and the chosen device with its compute
// queue, made once per process (or per Segmenter) and shared by the stages by reference.
#pragma once
#include <cstdint>
#include <string>

#include "host/vk/device.h"
#include "host/vk/instance.h"
#include "host/vk/result.h"

namespace lpir::vk {

struct ContextOptions {
  bool validation = false;  // the Khronos validation layer, messages printed and counted
  std::string device;       // "": first usable, discrete first; digits: index; else name part
  bool gpu_only = false;    // with device "": no CPU driver (Device::Create, cpu_driver_only)

  // LPIR_VK_VALIDATION=1 turns validation on, LPIR_VK_DEVICE=<selector> picks the device.
  static ContextOptions FromEnvironment();
};

class Context {
 public:
  // Error::no_device when the machine has no Vulkan driver or device (callers may fall back to
  // the CPU reference, tests skip).
  static Result<Context> Create(const ContextOptions& options);

  const Instance& instance() const { return instance_; }
  const Device& device() const { return device_; }
  // Validation messages received so far (0 without validation).
  uint64_t validation_messages() const { return instance_.messages(); }

 private:
  Context(Instance instance, Device device)
      : instance_(std::move(instance)), device_(std::move(device)) {}

  Instance instance_;  // declared first: destroyed after the device
  Device device_;
};

}  // namespace lpir::vk
