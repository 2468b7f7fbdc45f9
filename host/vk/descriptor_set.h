// DescriptorSet: one descriptor set of a pipeline's layout, in a pool of its own, with one buffer
// bound (whole) at every binding. Bound once when the frame's buffers are allocated, never
// updated on the per-frame path.
#pragma once
#include <vulkan/vulkan.h>

#include <vector>

#include "host/vk/buffer.h"
#include "host/vk/compute_pipeline.h"
#include "host/vk/device.h"
#include "host/vk/handle.h"
#include "host/vk/result.h"

namespace lpir::vk {

class DescriptorSet {
 public:
  // buffers[i] is bound at binding i; as many buffers as the pipeline has bindings.
  static Result<DescriptorSet> Create(const Device& device, const ComputePipeline& pipeline,
                                      const std::vector<const Buffer*>& buffers);

  DescriptorSet(DescriptorSet&&) noexcept = default;
  DescriptorSet& operator=(DescriptorSet&&) noexcept = default;

  VkDescriptorSet handle() const { return set_.get(); }

 private:
  DescriptorSet() = default;

  DeviceHandle<VkDescriptorPool, vkDestroyDescriptorPool> pool_;  // frees the set with it
  ResetOnMove<VkDescriptorSet> set_;
};

}  // namespace lpir::vk
