// Kernel creation and recording.
#include "host/vk/kernel.h"

#include <algorithm>
#include <map>
#include <mutex>
#include <string>
#include <tuple>

namespace lpir::vk {
namespace {

// Everything that makes a kernel's pipelines what they are: the device, the SPIR-V and every
// field of PipelineDesc but the name and the pass.
using PipelineKey = std::tuple<VkDevice, const uint32_t*, size_t, std::vector<VkDescriptorType>,
                               uint32_t, uint32_t, uint32_t, uint32_t>;

// The pipelines of the kernels alive, by key (an entry expires with its last kernel).
std::mutex g_cache_mutex;
std::map<PipelineKey, std::weak_ptr<const Kernel::Pipelines>> g_cache;

}  // namespace

Result<Kernel> Kernel::Create(const Device& device, const PipelineDesc& desc,
                              const std::vector<const Buffer*>& buffers) {
  LPIR_VK_ASSIGN_OR_RETURN(const Shape shape, ShapeFor(device));
  const uint32_t items = shape == Shape::kCpu ? desc.cpu_items : 1;
  const PipelineKey key{
      device.handle(),          desc.code.words,   desc.code.bytes,           desc.bindings,
      desc.push_constant_bytes, desc.local_size_x, std::max(desc.passes, 1u), items};
  std::lock_guard<std::mutex> lock(g_cache_mutex);
  std::shared_ptr<const Pipelines> pipelines = g_cache[key].lock();
  if (!pipelines) {
    auto made = std::make_shared<Pipelines>();
    for (uint32_t pass = 0; pass < std::max(desc.passes, 1u); ++pass) {
      PipelineDesc one = desc;
      one.pass = pass;
      one.items = items;
      LPIR_VK_ASSIGN_OR_RETURN(ComputePipeline pipeline, ComputePipeline::Create(device, one));
      made->push_back(std::move(pipeline));
    }
    pipelines = std::move(made);
    g_cache[key] = pipelines;
  }
  LPIR_VK_ASSIGN_OR_RETURN(DescriptorSet set,
                           DescriptorSet::Create(device, pipelines->front(), buffers));
  return Kernel(std::move(pipelines), std::move(set), device.limits().maxComputeWorkGroupCount[0],
                shape);
}

Status Kernel::CheckGroups(uint64_t invocations) const {
  const uint32_t local = pipelines_->front().local_size_x();
  const uint64_t groups = (invocations + local - 1) / local;
  if (groups <= max_groups_) return Status();
  Error e;
  e.result = VK_ERROR_UNKNOWN;
  e.message = pipelines_->front().name() + ": " + std::to_string(invocations) +
              " invocations need " + std::to_string(groups) + " workgroups of " +
              std::to_string(local) + "; this device's maxComputeWorkGroupCount[0] is " +
              std::to_string(max_groups_);
  return e;
}

Status Kernel::Record(CommandBuffer& cmd, uint32_t invocations, const void* push,
                      uint32_t pass) const {
  LPIR_VK_RETURN_IF_ERROR(CheckGroups(invocations));
  const uint32_t local = pipelines_->front().local_size_x();
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
  const ComputePipeline& pipeline = pipelines_->at(pass);
  cmd.BindPipeline(pipeline);
  cmd.BindDescriptorSet(pipeline, set_);
  if (pipeline.push_constant_bytes())
    cmd.PushConstants(pipeline, push, pipeline.push_constant_bytes());
}

}  // namespace lpir::vk
