// grid_reduce, on Vulkan: the kernel's bindings and its recording.
#include "host/gpu/grid_reduce.h"

#include <cstdint>

namespace lpir::vk {
namespace {
#include "shaders/grid_reduce.spv.h"  // kGridReduceSpv, compiled from shaders/grid_reduce.comp

struct Push {
  uint32_t count;  // cells (pass 0) or points (pass 1)
};
}  // namespace

Result<GridReduceStage> GridReduceStage::Create(const Device& device, const GridReduceBuffers& b) {
  PipelineDesc desc;
  desc.name = "grid_reduce";
  desc.code = SpirvOf(kGridReduceSpv);
  desc.bindings.assign(10, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER);
  desc.bindings[0] = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
  desc.push_constant_bytes = sizeof(Push);
  desc.local_size_x = kLocalSize;
  desc.passes = 2;
  desc.cpu_items = kCpuItems;
  LPIR_VK_ASSIGN_OR_RETURN(
      Kernel kernel, Kernel::Create(device, desc,
                                    {b.params, b.flags, b.r2, b.zt, b.point_pixel, b.ring_bound2,
                                     b.point_cell, b.cell_zmin, b.cell_zmax, b.cell_count}));
  return GridReduceStage(std::move(kernel));
}

Status GridReduceStage::Record(CommandBuffer& cmd, uint32_t n, uint32_t cells) const {
  const Push clear{cells}, reduce{n};
  LPIR_VK_RETURN_IF_ERROR(kernel_.Record(cmd, cells, &clear, 0));
  cmd.ComputeToCompute();
  return kernel_.Record(cmd, kernel_.Chunks(n), &reduce, 1);  // kernel_.items() points each
}

}  // namespace lpir::vk
