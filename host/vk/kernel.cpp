// Kernel creation and recording.
#include "host/vk/kernel.h"

#include <string>

namespace lpir::vk {

Result<Kernel> Kernel::Create(const Device& device, const PipelineDesc& desc,
                              const std::vector<const Buffer*>& buffers) {
  LPIR_VK_ASSIGN_OR_RETURN(ComputePipeline pipeline, ComputePipeline::Create(device, desc));
  LPIR_VK_ASSIGN_OR_RETURN(DescriptorSet set, DescriptorSet::Create(device, pipeline, buffers));
  return Kernel(std::move(pipeline), std::move(set), device.limits().maxComputeWorkGroupCount[0]);
}

Status Kernel::CheckGroups(uint64_t invocations) const {
  const uint32_t local = pipeline_.local_size_x();
  const uint64_t groups = (invocations + local - 1) / local;
  if (groups <= max_groups_) return Status();
  Error e;
  e.result = VK_ERROR_UNKNOWN;
  e.message = pipeline_.name() + ": " + std::to_string(invocations) + " invocations need " +
              std::to_string(groups) + " workgroups, the device dispatches at most " +
              std::to_string(max_groups_);
  return e;
}

Status Kernel::Record(CommandBuffer& cmd, uint32_t invocations, const void* push) const {
  LPIR_VK_RETURN_IF_ERROR(CheckGroups(invocations));
  const uint32_t local = pipeline_.local_size_x();
  const uint32_t groups = uint32_t((uint64_t(invocations) + local - 1) / local);
  if (groups == 0) return Status();
  Bind(cmd, push);
  cmd.Dispatch(groups);
  return Status();
}

void Kernel::RecordIndirect(CommandBuffer& cmd, const Buffer& args, VkDeviceSize offset,
                            const void* push) const {
  Bind(cmd, push);
  cmd.DispatchIndirect(args, offset);
}

void Kernel::Bind(CommandBuffer& cmd, const void* push) const {
  cmd.BindPipeline(pipeline_);
  cmd.BindDescriptorSet(pipeline_, set_);
  if (pipeline_.push_constant_bytes())
    cmd.PushConstants(pipeline_, push, pipeline_.push_constant_bytes());
}

}  // namespace lpir::vk
