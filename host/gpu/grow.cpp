// grow, on Vulkan: the kernel's bindings and its five passes.
#include "host/gpu/grow.h"

#include <cstdint>
#include <utility>

namespace lpir::vk {
namespace {
#include "shaders/grow.spv.h"  // kGrowSpv, compiled from shaders/grow.comp at build time

struct Push {
  uint32_t count;  // pixels
};
}  // namespace

Result<GrowStage> GrowStage::Create(const Device& device, const GrowBuffers& b) {
  PipelineDesc desc;
  desc.name = "grow";
  desc.code = SpirvOf(kGrowSpv);
  desc.bindings.assign(9, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER);
  desc.bindings[0] = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
  desc.push_constant_bytes = sizeof(Push);
  desc.local_size_x = kLocalSize;
  desc.passes = kPasses;
  LPIR_VK_ASSIGN_OR_RETURN(
      Kernel kernel, Kernel::Create(device, desc,
                                    {b.params, b.pixel_fused, b.f_height, b.f_range, b.pixel_grown,
                                     b.pixel_comp, b.pixel_label, b.grow_reach, b.grow_sizes}));
  return GrowStage(std::move(kernel));
}

Status GrowStage::Record(CommandBuffer& cmd, uint32_t width, uint32_t beams) const {
  const Push push{width * beams};
  for (uint32_t pass = 0; pass < kPasses; ++pass) {
    if (pass > 0) cmd.ComputeToCompute();
    LPIR_VK_RETURN_IF_ERROR(kernel_.Record(cmd, push.count, &push, pass));
  }
  return Status();
}

}  // namespace lpir::vk
