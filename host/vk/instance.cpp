// Instance creation: API version check, the validation layer and the counting debug messenger.
#include "host/vk/instance.h"

#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <utility>
#include <vector>

namespace lpir::vk {
namespace {

constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";

std::atomic<uint64_t> g_total_messages{0};

std::string VersionString(uint32_t v) {
  return std::to_string(VK_API_VERSION_MAJOR(v)) + "." + std::to_string(VK_API_VERSION_MINOR(v)) +
         "." + std::to_string(VK_API_VERSION_PATCH(v));
}

}  // namespace

struct Instance::Log {
  std::atomic<uint64_t> count{0};
};

namespace {

VKAPI_ATTR VkBool32 VKAPI_CALL OnMessage(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                         VkDebugUtilsMessageTypeFlagsEXT /*types*/,
                                         const VkDebugUtilsMessengerCallbackDataEXT* data,
                                         void* user) {
  ++static_cast<Instance::Log*>(user)->count;
  ++g_total_messages;
  const char* level =
      (severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT) ? "error" : "warning";
  std::fprintf(stderr, "[vulkan %s] %s\n", level,
               data && data->pMessage ? data->pMessage : "(no message)");
  return VK_FALSE;  // never abort the call
}

bool HasLayer(const char* name) {
  uint32_t count = 0;
  if (vkEnumerateInstanceLayerProperties(&count, nullptr) != VK_SUCCESS) return false;
  std::vector<VkLayerProperties> layers(count);
  if (vkEnumerateInstanceLayerProperties(&count, layers.data()) != VK_SUCCESS) return false;
  for (const VkLayerProperties& layer : layers)
    if (std::strcmp(layer.layerName, name) == 0) return true;
  return false;
}

bool HasExtension(const char* layer, const char* name) {
  uint32_t count = 0;
  if (vkEnumerateInstanceExtensionProperties(layer, &count, nullptr) != VK_SUCCESS) return false;
  std::vector<VkExtensionProperties> extensions(count);
  if (vkEnumerateInstanceExtensionProperties(layer, &count, extensions.data()) != VK_SUCCESS)
    return false;
  for (const VkExtensionProperties& e : extensions)
    if (std::strcmp(e.extensionName, name) == 0) return true;
  return false;
}

}  // namespace

Result<Instance> Instance::Create(const InstanceOptions& options) {
  uint32_t loader_version = VK_API_VERSION_1_0;
  LPIR_VK_CHECK(vkEnumerateInstanceVersion(&loader_version), "vkEnumerateInstanceVersion", "");
  if (loader_version < VK_API_VERSION_1_2) {
    Error e;
    e.result = VK_ERROR_INCOMPATIBLE_DRIVER;
    e.message = "the Vulkan loader supports Vulkan " + VersionString(loader_version) +
                "; lpir-gseg needs 1.2 (update libvulkan1)";
    return e;
  }

  std::vector<const char*> layers, extensions;
  bool sync_validation = false;
  if (options.validation) {
    if (!HasLayer(kValidationLayer)) {
      Error e;
      e.result = VK_ERROR_LAYER_NOT_PRESENT;
      e.message = std::string("validation was asked for but ") + kValidationLayer +
                  " is not installed (Debian package vulkan-validationlayers)";
      return e;
    }
    if (!HasExtension(nullptr, VK_EXT_DEBUG_UTILS_EXTENSION_NAME) &&
        !HasExtension(kValidationLayer, VK_EXT_DEBUG_UTILS_EXTENSION_NAME)) {
      Error e;
      e.result = VK_ERROR_EXTENSION_NOT_PRESENT;
      e.message = std::string("validation was asked for but ") + VK_EXT_DEBUG_UTILS_EXTENSION_NAME +
                  " is not available";
      return e;
    }
    layers.push_back(kValidationLayer);
    extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
    sync_validation = HasExtension(kValidationLayer, VK_EXT_VALIDATION_FEATURES_EXTENSION_NAME);
    if (sync_validation) extensions.push_back(VK_EXT_VALIDATION_FEATURES_EXTENSION_NAME);
  }

  Instance instance;
  instance.log_ = std::make_unique<Log>();

  VkDebugUtilsMessengerCreateInfoEXT messenger_info{};
  messenger_info.sType = VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT;
  messenger_info.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT |
                                   VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
  messenger_info.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT |
                               VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                               VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
  messenger_info.pfnUserCallback = OnMessage;
  messenger_info.pUserData = instance.log_.get();

  VkApplicationInfo app{};
  app.sType = VK_STRUCTURE_TYPE_APPLICATION_INFO;
  app.pApplicationName = "lpir-gseg";
  app.applicationVersion = 1;
  app.pEngineName = "lpir-gseg";
  app.engineVersion = 1;
  app.apiVersion = VK_API_VERSION_1_2;

  VkInstanceCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO;
  // Chained, the messenger also hears vkCreateInstance and vkDestroyInstance.
  info.pNext = options.validation ? &messenger_info : nullptr;
  // Synchronization validation too: a missing barrier between stages is a race that byte
  // comparisons on one device may never catch.
  const VkValidationFeatureEnableEXT enables[] = {
      VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT};
  VkValidationFeaturesEXT features{};
  features.sType = VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT;
  features.enabledValidationFeatureCount = 1;
  features.pEnabledValidationFeatures = enables;
  features.pNext = &messenger_info;
  if (sync_validation) info.pNext = &features;
  info.pApplicationInfo = &app;
  info.enabledLayerCount = uint32_t(layers.size());
  info.ppEnabledLayerNames = layers.data();
  info.enabledExtensionCount = uint32_t(extensions.size());
  info.ppEnabledExtensionNames = extensions.data();

  const VkResult r = vkCreateInstance(&info, nullptr, &instance.instance_);
  if (r != VK_SUCCESS) {
    instance.instance_ = VK_NULL_HANDLE;
    const char* icds = std::getenv("VK_ICD_FILENAMES");
    Error e = CallError("vkCreateInstance", r,
                        icds ? std::string("VK_ICD_FILENAMES=") + icds : std::string());
    if (r == VK_ERROR_INCOMPATIBLE_DRIVER) {
      e.no_device = true;
      e.message = "no Vulkan driver found: " + e.message;
    }
    return e;
  }

  if (options.validation) {
    auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance.instance_, "vkCreateDebugUtilsMessengerEXT"));
    instance.destroy_messenger_ = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance.instance_, "vkDestroyDebugUtilsMessengerEXT"));
    if (!create || !instance.destroy_messenger_) {
      Error e;
      e.result = VK_ERROR_EXTENSION_NOT_PRESENT;
      e.message = "vkGetInstanceProcAddr: no vkCreateDebugUtilsMessengerEXT";
      return e;
    }
    LPIR_VK_CHECK(create(instance.instance_, &messenger_info, nullptr, &instance.messenger_),
                  "vkCreateDebugUtilsMessengerEXT", "");
  }
  return instance;
}

Instance::Instance(Instance&& other) noexcept
    : instance_(std::exchange(other.instance_, VK_NULL_HANDLE)),
      messenger_(std::exchange(other.messenger_, VK_NULL_HANDLE)),
      destroy_messenger_(std::exchange(other.destroy_messenger_, nullptr)),
      log_(std::move(other.log_)) {}

Instance& Instance::operator=(Instance&& other) noexcept {
  if (this != &other) {
    Release();
    instance_ = std::exchange(other.instance_, VK_NULL_HANDLE);
    messenger_ = std::exchange(other.messenger_, VK_NULL_HANDLE);
    destroy_messenger_ = std::exchange(other.destroy_messenger_, nullptr);
    log_ = std::move(other.log_);
  }
  return *this;
}

Instance::~Instance() { Release(); }

void Instance::Release() {
  if (messenger_ != VK_NULL_HANDLE) destroy_messenger_(instance_, messenger_, nullptr);
  messenger_ = VK_NULL_HANDLE;
  if (instance_ != VK_NULL_HANDLE) vkDestroyInstance(instance_, nullptr);
  instance_ = VK_NULL_HANDLE;
  log_.reset();  // after vkDestroyInstance: the chained messenger may still report during it
}

uint64_t Instance::messages() const { return log_ ? log_->count.load() : 0; }

uint64_t Instance::TotalMessages() { return g_total_messages.load(); }

}  // namespace lpir::vk
