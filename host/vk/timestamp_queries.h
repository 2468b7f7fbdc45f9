// TimestampQueries: a pool of GPU timestamps for per-stage timing (docs/spec.md, Performance
// shape). Record CommandBuffer::ResetQueries first, CommandBuffer::WriteTimestamp(k) after each
// stage, then read them once the submission's fence has signalled.
#pragma once
#include <vulkan/vulkan.h>

#include <cstdint>
#include <vector>

#include "host/vk/device.h"
#include "host/vk/handle.h"
#include "host/vk/result.h"

namespace lpir::vk {

class TimestampQueries {
 public:
  // An error when the device's compute queue has no timestamps (timestampValidBits == 0).
  static Result<TimestampQueries> Create(const Device& device, uint32_t count);

  TimestampQueries(TimestampQueries&&) noexcept = default;
  TimestampQueries& operator=(TimestampQueries&&) noexcept = default;

  VkQueryPool handle() const { return pool_.get(); }
  uint32_t count() const { return count_; }

  // All `count` timestamps in nanoseconds from an arbitrary origin (subtract two for a duration),
  // waiting for them if needed. `nanoseconds` holds count() values. Allocates nothing.
  Status Read(double* nanoseconds) const;

 private:
  TimestampQueries() = default;

  DeviceHandle<VkQueryPool, vkDestroyQueryPool> pool_;
  uint32_t count_ = 0;
  double period_ns_ = 1.0;
  uint64_t valid_mask_ = ~uint64_t(0);
  mutable std::vector<uint64_t> ticks_;
};

}  // namespace lpir::vk
