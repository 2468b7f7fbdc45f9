// Kernel: the generic dispatcher. One compute shader ready to run over a 1-D range: its pipeline
// and one descriptor set bound to buffers fixed at creation (allocated once for the largest
// cloud, SPEC section 5). Recording binds, pushes the constants and dispatches
// ceil(invocations / local size) workgroups; the shader skips invocations past its count.
#pragma once
#include <cstdint>
#include <vector>

#include "host/vk/buffer.h"
#include "host/vk/command_buffer.h"
#include "host/vk/compute_pipeline.h"
#include "host/vk/descriptor_set.h"
#include "host/vk/device.h"
#include "host/vk/result.h"

namespace lpir::vk {

class Kernel {
 public:
  static Result<Kernel> Create(const Device& device, const PipelineDesc& desc,
                               const std::vector<const Buffer*>& buffers);

  // `push` holds desc.push_constant_bytes bytes (nullptr when none). No barrier is recorded.
  // An error when the range needs more workgroups than the device dispatches along x.
  Status Record(CommandBuffer& cmd, uint32_t invocations, const void* push) const;

  // An error when `invocations` need more workgroups than the device dispatches along x.
  Status CheckGroups(uint64_t invocations) const;

  // The same with the workgroup counts read on the GPU from `args` at `offset` (see
  // CommandBuffer::DispatchIndirect): the shader decides whether its successor runs.
  void RecordIndirect(CommandBuffer& cmd, const Buffer& args, VkDeviceSize offset,
                      const void* push) const;

  const ComputePipeline& pipeline() const { return pipeline_; }

 private:
  Kernel(ComputePipeline pipeline, DescriptorSet set, uint32_t max_groups)
      : pipeline_(std::move(pipeline)), set_(std::move(set)), max_groups_(max_groups) {}
  void Bind(CommandBuffer& cmd, const void* push) const;

  ComputePipeline pipeline_;
  DescriptorSet set_;
  uint32_t max_groups_ = 0;
};

}  // namespace lpir::vk
