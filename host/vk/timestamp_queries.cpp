// Timestamp query pool creation and read-back.
#include "host/vk/timestamp_queries.h"

#include <string>

namespace lpir::vk {

Result<TimestampQueries> TimestampQueries::Create(const Device& device, uint32_t count) {
  if (device.timestamp_valid_bits() == 0 || count == 0) {
    Error e;
    e.result = VK_ERROR_FEATURE_NOT_PRESENT;
    e.message = count == 0 ? std::string("zero timestamps asked for")
                           : device.name() + "'s compute queue has no timestamps";
    return e;
  }
  VkQueryPoolCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO;
  info.queryType = VK_QUERY_TYPE_TIMESTAMP;
  info.queryCount = count;
  VkQueryPool pool = VK_NULL_HANDLE;
  LPIR_VK_CHECK(vkCreateQueryPool(device.handle(), &info, nullptr, &pool), "vkCreateQueryPool",
                std::to_string(count) + " timestamps");
  TimestampQueries queries;
  queries.pool_ = DeviceHandle<VkQueryPool, vkDestroyQueryPool>(device.handle(), pool);
  queries.count_ = count;
  queries.period_ns_ = device.limits().timestampPeriod;
  const uint32_t bits = device.timestamp_valid_bits();
  queries.valid_mask_ = bits >= 64 ? ~uint64_t(0) : (uint64_t(1) << bits) - 1;
  queries.ticks_.resize(count);
  return queries;
}

Status TimestampQueries::Read(double* nanoseconds) const {
  LPIR_VK_CHECK(
      vkGetQueryPoolResults(pool_.device(), pool_.get(), 0, count_,
                            ticks_.size() * sizeof(uint64_t), ticks_.data(), sizeof(uint64_t),
                            VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT),
      "vkGetQueryPoolResults", "");
  for (uint32_t i = 0; i < count_; ++i)
    nanoseconds[i] = double(ticks_[i] & valid_mask_) * period_ns_;
  return Status();
}

}  // namespace lpir::vk
