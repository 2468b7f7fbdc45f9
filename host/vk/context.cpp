// Context creation from options or the environment.
#include "host/vk/context.h"

#include <cstdlib>
#include <cstring>
#include <utility>

namespace lpir::vk {

ContextOptions ContextOptions::FromEnvironment() {
  ContextOptions options;
  const char* validation = std::getenv("LPIR_VK_VALIDATION");
  options.validation = validation && std::strcmp(validation, "0") != 0 && *validation != '\0';
  const char* device = std::getenv("LPIR_VK_DEVICE");
  if (device) options.device = device;
  return options;
}

Result<Context> Context::Create(const ContextOptions& options) {
  InstanceOptions instance_options;
  instance_options.validation = options.validation;
  LPIR_VK_ASSIGN_OR_RETURN(Instance instance, Instance::Create(instance_options));
  LPIR_VK_ASSIGN_OR_RETURN(Device device,
                           Device::Create(instance, options.device, options.gpu_only));
  return Context(std::move(instance), std::move(device));
}

}  // namespace lpir::vk
