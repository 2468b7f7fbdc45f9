// Physical device choice, feature checks and the logical device with its compute queue.
#include "host/vk/device.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <utility>

namespace lpir::vk {
namespace {

struct Candidate {
  uint32_t index = 0;
  VkPhysicalDevice physical = VK_NULL_HANDLE;
  VkPhysicalDeviceProperties properties{};
  std::string why_not;  // "" when usable
  uint32_t queue_family = 0;
  uint32_t timestamp_valid_bits = 0;
};

const char* TypeName(VkPhysicalDeviceType type) {
  switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU:
      return "discrete GPU";
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU:
      return "integrated GPU";
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU:
      return "virtual GPU";
    case VK_PHYSICAL_DEVICE_TYPE_CPU:
      return "CPU";
    default:
      return "other";
  }
}

// Discrete GPUs first (docs/spec.md: any Vulkan 1.2 device; lavapipe last but allowed).
int TypeRank(VkPhysicalDeviceType type) {
  switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU:
      return 0;
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU:
      return 1;
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU:
      return 2;
    case VK_PHYSICAL_DEVICE_TYPE_CPU:
      return 3;
    default:
      return 4;
  }
}

std::string VersionString(uint32_t v) {
  return std::to_string(VK_API_VERSION_MAJOR(v)) + "." + std::to_string(VK_API_VERSION_MINOR(v)) +
         "." + std::to_string(VK_API_VERSION_PATCH(v));
}

std::string Lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(),
                 [](unsigned char c) { return char(std::tolower(c)); });
  return s;
}

Candidate Inspect(uint32_t index, VkPhysicalDevice physical) {
  Candidate c;
  c.index = index;
  c.physical = physical;
  vkGetPhysicalDeviceProperties(physical, &c.properties);
  VkPhysicalDeviceFeatures features{};
  vkGetPhysicalDeviceFeatures(physical, &features);
  uint32_t family_count = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(physical, &family_count, nullptr);
  std::vector<VkQueueFamilyProperties> families(family_count);
  vkGetPhysicalDeviceQueueFamilyProperties(physical, &family_count, families.data());
  // A compute queue: with timestamps before without, compute-only before compute + graphics.
  int best = -1, best_rank = 99;
  for (uint32_t f = 0; f < family_count; ++f) {
    if (!(families[f].queueFlags & VK_QUEUE_COMPUTE_BIT) || families[f].queueCount == 0) continue;
    const int rank = (families[f].timestampValidBits ? 0 : 2) +
                     ((families[f].queueFlags & VK_QUEUE_GRAPHICS_BIT) ? 1 : 0);
    if (rank < best_rank) best = int(f), best_rank = rank;
  }
  if (c.properties.apiVersion < VK_API_VERSION_1_2) {
    c.why_not = "supports Vulkan " + VersionString(c.properties.apiVersion) + ", 1.2 needed";
  } else if (!features.shaderInt64) {
    c.why_not = "no shaderInt64 (the exact division and square root need 64-bit integers)";
  } else if (best < 0) {
    c.why_not = "no compute queue";
  } else {
    c.queue_family = uint32_t(best);
    c.timestamp_valid_bits = families[best].timestampValidBits;
  }
  return c;
}

std::string Line(const Candidate& c) {
  return "#" + std::to_string(c.index) + " " + c.properties.deviceName + " (" +
         TypeName(c.properties.deviceType) + ", Vulkan " + VersionString(c.properties.apiVersion) +
         "): " + (c.why_not.empty() ? std::string("usable") : c.why_not);
}

Result<std::vector<Candidate>> Enumerate(const Instance& instance) {
  uint32_t count = 0;
  LPIR_VK_CHECK(vkEnumeratePhysicalDevices(instance.handle(), &count, nullptr),
                "vkEnumeratePhysicalDevices", "");
  std::vector<VkPhysicalDevice> physical(count);
  LPIR_VK_CHECK(vkEnumeratePhysicalDevices(instance.handle(), &count, physical.data()),
                "vkEnumeratePhysicalDevices", "");
  std::vector<Candidate> candidates;
  for (uint32_t i = 0; i < count; ++i) candidates.push_back(Inspect(i, physical[i]));
  return candidates;
}

std::string AllLines(const std::vector<Candidate>& candidates) {
  std::string s;
  for (const Candidate& c : candidates) s += "\n  " + Line(c);
  return s;
}

Error SelectionError(const std::string& what, const std::vector<Candidate>& candidates) {
  Error e;
  e.result = VK_ERROR_FEATURE_NOT_PRESENT;
  e.message = what + "; the devices:" + AllLines(candidates);
  return e;
}

}  // namespace

Result<std::vector<std::string>> Device::Describe(const Instance& instance) {
  Result<std::vector<Candidate>> candidates = Enumerate(instance);
  if (!candidates.ok()) return candidates.error();
  std::vector<std::string> lines;
  for (const Candidate& c : candidates.value()) lines.push_back(Line(c));
  return lines;
}

Result<Device> Device::Create(const Instance& instance, const std::string& selector,
                              bool gpu_only) {
  LPIR_VK_ASSIGN_OR_RETURN(std::vector<Candidate> candidates, Enumerate(instance));
  if (candidates.empty()) {
    Error e;
    e.result = VK_ERROR_INITIALIZATION_FAILED;
    e.no_device = true;
    e.message = "no Vulkan physical device found (vkEnumeratePhysicalDevices returned none)";
    return e;
  }

  const Candidate* chosen = nullptr;
  const bool by_index =
      !selector.empty() && std::all_of(selector.begin(), selector.end(),
                                       [](unsigned char ch) { return std::isdigit(ch) != 0; });
  if (by_index) {
    const unsigned long index = std::stoul(selector);
    if (index >= candidates.size())
      return SelectionError("no Vulkan device #" + selector, candidates);
    chosen = &candidates[index];
    if (!chosen->why_not.empty())
      return SelectionError("Vulkan device #" + selector + " is not usable", candidates);
  } else {
    std::vector<const Candidate*> order;
    for (const Candidate& c : candidates)
      if (selector.empty() ||
          Lower(c.properties.deviceName).find(Lower(selector)) != std::string::npos)
        order.push_back(&c);
    if (order.empty())
      return SelectionError("no Vulkan device name contains \"" + selector + "\"", candidates);
    std::stable_sort(order.begin(), order.end(), [](const Candidate* a, const Candidate* b) {
      return TypeRank(a->properties.deviceType) < TypeRank(b->properties.deviceType);
    });
    std::vector<const Candidate*> cpu_drivers;  // usable, left out by gpu_only
    for (const Candidate* c : order) {
      if (!c->why_not.empty()) continue;
      if (gpu_only && selector.empty() && c->properties.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU) {
        cpu_drivers.push_back(c);
        continue;
      }
      chosen = c;
      break;
    }
    if (!chosen && !cpu_drivers.empty()) {
      std::string names;
      // the driver's name without its details ("llvmpipe", not "llvmpipe (LLVM 15.0.6, 256
      // bits)"): the note stays one line of a 120-column terminal
      for (const Candidate* c : cpu_drivers) {
        const std::string name = c->properties.deviceName;
        names += (names.empty() ? "" : ", ") + name.substr(0, name.find(" ("));
      }
      const bool alone = cpu_drivers.size() == candidates.size();
      Error e;
      e.result = VK_ERROR_FEATURE_NOT_PRESENT;
      e.cpu_driver_only = true;
      e.message = std::string(alone ? "the only" : "the only usable") + " Vulkan device" +
                  (cpu_drivers.size() > 1 ? "s are CPU drivers (" : " is a CPU driver (") + names +
                  "); --backend vulkan uses " + (cpu_drivers.size() > 1 ? "them" : "it");
      return e;
    }
    if (!chosen)
      return SelectionError(selector.empty()
                                ? std::string("no usable Vulkan device")
                                : "no usable Vulkan device named like \"" + selector + "\"",
                            candidates);
  }

  Device device;
  device.physical_ = chosen->physical;
  device.properties_ = chosen->properties;
  device.queue_family_ = chosen->queue_family;
  device.timestamp_valid_bits_ = chosen->timestamp_valid_bits;
  vkGetPhysicalDeviceMemoryProperties(device.physical_, &device.memory_);

  const float priority = 1.0f;
  VkDeviceQueueCreateInfo queue_info{};
  queue_info.sType = VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO;
  queue_info.queueFamilyIndex = device.queue_family_;
  queue_info.queueCount = 1;
  queue_info.pQueuePriorities = &priority;

  VkPhysicalDeviceFeatures features{};
  features.shaderInt64 = VK_TRUE;

  VkDeviceCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO;
  info.queueCreateInfoCount = 1;
  info.pQueueCreateInfos = &queue_info;
  info.pEnabledFeatures = &features;
  LPIR_VK_CHECK(vkCreateDevice(device.physical_, &info, nullptr, &device.device_), "vkCreateDevice",
                device.name());
  vkGetDeviceQueue(device.device_, device.queue_family_, 0, &device.queue_);
  return device;
}

Device::Device(Device&& other) noexcept
    : physical_(std::exchange(other.physical_, VK_NULL_HANDLE)),
      device_(std::exchange(other.device_, VK_NULL_HANDLE)),
      queue_(std::exchange(other.queue_, VK_NULL_HANDLE)),
      queue_family_(other.queue_family_),
      timestamp_valid_bits_(other.timestamp_valid_bits_),
      properties_(other.properties_),
      memory_(other.memory_) {}

Device& Device::operator=(Device&& other) noexcept {
  if (this != &other) {
    Release();
    physical_ = std::exchange(other.physical_, VK_NULL_HANDLE);
    device_ = std::exchange(other.device_, VK_NULL_HANDLE);
    queue_ = std::exchange(other.queue_, VK_NULL_HANDLE);
    queue_family_ = other.queue_family_;
    timestamp_valid_bits_ = other.timestamp_valid_bits_;
    properties_ = other.properties_;
    memory_ = other.memory_;
  }
  return *this;
}

Device::~Device() { Release(); }

void Device::Release() {
  if (device_ != VK_NULL_HANDLE) {
    vkDeviceWaitIdle(device_);
    vkDestroyDevice(device_, nullptr);
  }
  device_ = VK_NULL_HANDLE;
}

Result<uint32_t> Device::FindMemoryType(uint32_t type_bits, VkMemoryPropertyFlags required,
                                        VkMemoryPropertyFlags preferred) const {
  int fallback = -1;
  for (uint32_t i = 0; i < memory_.memoryTypeCount; ++i) {
    if (!(type_bits & (1u << i))) continue;
    const VkMemoryPropertyFlags flags = memory_.memoryTypes[i].propertyFlags;
    if ((flags & required) != required) continue;
    if ((flags & preferred) == preferred) return i;
    if (fallback < 0) fallback = int(i);
  }
  if (fallback >= 0) return uint32_t(fallback);
  Error e;
  e.result = VK_ERROR_FEATURE_NOT_PRESENT;
  char flags[16];
  std::snprintf(flags, sizeof(flags), "0x%x", unsigned(required));
  e.message = std::string("no memory type with property flags ") + flags + " on " + name();
  return e;
}

}  // namespace lpir::vk
