// VkResult names for the set-up error messages.
#include "host/vk/result.h"

namespace lpir::vk {

std::string VkResultName(VkResult result) {
  const char* name = nullptr;
  switch (result) {
#define LPIR_VK_NAME(r) \
  case r:               \
    name = #r;          \
    break;
    LPIR_VK_NAME(VK_SUCCESS)
    LPIR_VK_NAME(VK_NOT_READY)
    LPIR_VK_NAME(VK_TIMEOUT)
    LPIR_VK_NAME(VK_EVENT_SET)
    LPIR_VK_NAME(VK_EVENT_RESET)
    LPIR_VK_NAME(VK_INCOMPLETE)
    LPIR_VK_NAME(VK_ERROR_OUT_OF_HOST_MEMORY)
    LPIR_VK_NAME(VK_ERROR_OUT_OF_DEVICE_MEMORY)
    LPIR_VK_NAME(VK_ERROR_INITIALIZATION_FAILED)
    LPIR_VK_NAME(VK_ERROR_DEVICE_LOST)
    LPIR_VK_NAME(VK_ERROR_MEMORY_MAP_FAILED)
    LPIR_VK_NAME(VK_ERROR_LAYER_NOT_PRESENT)
    LPIR_VK_NAME(VK_ERROR_EXTENSION_NOT_PRESENT)
    LPIR_VK_NAME(VK_ERROR_FEATURE_NOT_PRESENT)
    LPIR_VK_NAME(VK_ERROR_INCOMPATIBLE_DRIVER)
    LPIR_VK_NAME(VK_ERROR_TOO_MANY_OBJECTS)
    LPIR_VK_NAME(VK_ERROR_FORMAT_NOT_SUPPORTED)
    LPIR_VK_NAME(VK_ERROR_FRAGMENTED_POOL)
    LPIR_VK_NAME(VK_ERROR_UNKNOWN)
    LPIR_VK_NAME(VK_ERROR_OUT_OF_POOL_MEMORY)
    LPIR_VK_NAME(VK_ERROR_INVALID_EXTERNAL_HANDLE)
    LPIR_VK_NAME(VK_ERROR_FRAGMENTATION)
    LPIR_VK_NAME(VK_ERROR_INVALID_OPAQUE_CAPTURE_ADDRESS)
    LPIR_VK_NAME(VK_ERROR_VALIDATION_FAILED_EXT)
#undef LPIR_VK_NAME
    default:
      break;
  }
  const std::string code = std::to_string(static_cast<int>(result));
  return name ? std::string(name) + " (" + code + ")" : "VkResult " + code;
}

Error CallError(const char* call, VkResult result, const std::string& what) {
  Error error;
  error.result = result;
  error.message = std::string(call) + ": " + VkResultName(result);
  if (!what.empty()) error.message += " (" + what + ")";
  return error;
}

}  // namespace lpir::vk
