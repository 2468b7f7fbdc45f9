// coarse_segment, on Vulkan: the kernel's bindings and its recording.
#include "host/gpu/coarse_segment.h"

#include <cstdint>

namespace lpir::vk {
namespace {
#include "shaders/coarse_segment.spv.h"  // kCoarseSegmentSpv, from shaders/coarse_segment.comp

struct Push {
  uint32_t count;  // cells (passes 0, 2, 4) or points (passes 1, 3, 5)
};
}  // namespace

Result<CoarseSegmentStage> CoarseSegmentStage::Create(const Device& device,
                                                      const CoarseSegmentBuffers& b) {
  PipelineDesc desc;
  desc.name = "coarse_segment";
  desc.code = SpirvOf(kCoarseSegmentSpv);
  desc.bindings.assign(12, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER);
  desc.bindings[0] = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
  desc.push_constant_bytes = sizeof(Push);
  desc.local_size_x = kLocalSize;
  desc.passes = 6;
  desc.cpu_items = kCpuItems;
  LPIR_VK_ASSIGN_OR_RETURN(
      Kernel kernel,
      Kernel::Create(device, desc,
                     {b.params, b.xyzi, b.zt, b.point_cell, b.cell_zmin, b.cell_zmax, b.cell_count,
                      b.ring_inner, b.cell_seed_mode, b.cell_plane, b.coarse, b.coarse_scratch}));
  return CoarseSegmentStage(std::move(kernel));
}

Status CoarseSegmentStage::Record(CommandBuffer& cmd, uint32_t n, uint32_t cells) const {
  for (uint32_t pass = 0; pass < 6; ++pass) {
    if (pass) cmd.ComputeToCompute();
    const Push push{pass % 2 == 0 ? cells : n};
    // Passes 1, 3 and 5: one invocation per kernel_.items() points (shaders/coarse_segment.comp).
    const uint32_t invocations = pass % 2 == 1 ? kernel_.Chunks(n) : push.count;
    LPIR_VK_RETURN_IF_ERROR(kernel_.Record(cmd, invocations, &push, pass));
  }
  return Status();
}

}  // namespace lpir::vk
