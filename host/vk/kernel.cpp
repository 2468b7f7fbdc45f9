// Kernel creation and recording.
#include "host/vk/kernel.h"

#include <algorithm>
#include <string>

namespace lpir::vk {

Result<Kernel> Kernel::Create(const Device& device, const PipelineDesc& desc,
                              const std::vector<const Buffer*>& buffers) {
  LPIR_VK_ASSIGN_OR_RETURN(const Shape shape, ShapeFor(device));
  std::vector<ComputePipeline> pipelines;
  for (uint32_t pass = 0; pass < std::max(desc.passes, 1u); ++pass) {
    PipelineDesc one = desc;
    one.pass = pass;
    one.items = shape == Shape::kCpu ? desc.cpu_items : 1;
    LPIR_VK_ASSIGN_OR_RETURN(ComputePipeline pipeline, ComputePipeline::Create(device, one));
    pipelines.push_back(std::move(pipeline));
  }
  LPIR_VK_ASSIGN_OR_RETURN(DescriptorSet set,
                           DescriptorSet::Create(device, pipelines.front(), buffers));
  return Kernel(std::move(pipelines), std::move(set), device.limits().maxComputeWorkGroupCount[0],
                shape);
}

Status Kernel::CheckGroups(uint64_t invocations) const {
  const uint32_t local = pipelines_.front().local_size_x();
  const uint64_t groups = (invocations + local - 1) / local;
  if (groups <= max_groups_) return Status();
  Error e;
  e.result = VK_ERROR_UNKNOWN;
  e.message = pipelines_.front().name() + ": " + std::to_string(invocations) +
              " invocations need " + std::to_string(groups) +
              " workgroups, the device dispatches at most " + std::to_string(max_groups_);
  return e;
}

Status Kernel::Record(CommandBuffer& cmd, uint32_t invocations, const void* push,
                      uint32_t pass) const {
  LPIR_VK_RETURN_IF_ERROR(CheckGroups(invocations));
  const uint32_t local = pipelines_.front().local_size_x();
  const uint32_t groups = uint32_t((uint64_t(invocations) + local - 1) / local);
  if (groups == 0) return Status();
  Bind(cmd, push, pass);
  cmd.Dispatch(groups);
  return Status();
}

void Kernel::RecordIndirect(CommandBuffer& cmd, const Buffer& args, VkDeviceSize offset,
                            const void* push, uint32_t pass) const {
  Bind(cmd, push, pass);
  cmd.DispatchIndirect(args, offset);
}

void Kernel::Bind(CommandBuffer& cmd, const void* push, uint32_t pass) const {
  const ComputePipeline& pipeline = pipelines_.at(pass);
  cmd.BindPipeline(pipeline);
  cmd.BindDescriptorSet(pipeline, set_);
  if (pipeline.push_constant_bytes())
    cmd.PushConstants(pipeline, push, pipeline.push_constant_bytes());
}

}  // namespace lpir::vk
