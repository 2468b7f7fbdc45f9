// Stage 3, grid reduce, on Vulkan: the kernel's bindings and the one-shot runner.
#include "host/stages/grid_reduce.h"

#include <cstdint>
#include <string>

#include "host/vk/run_once.h"
#include "host/vk/transfer.h"

namespace lpir::vk {
namespace {
#include "shaders/grid_reduce.spv.h"  // kGridReduceSpv, compiled from shaders/grid_reduce.comp

struct Push {
  uint32_t count;  // cells (pass 0) or points (pass 1)
};

Error Invalid(const std::string& message) {
  Error e;
  e.result = VK_ERROR_UNKNOWN;
  e.message = "grid_reduce: " + message;
  return e;
}
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

Status RunGridReduce(const Context& context, const Params& p, const Tables& t, Frame& f,
                     double* gpu_ns) {
  const Device& device = context.device();
  const uint64_t n = f.n;
  const uint32_t cells = CellCount(p), rings = p.rings_near + p.rings_far;
  if (f.flags.size() != n || f.r2.size() != n || f.zt.size() != n || f.point_pixel.size() != n)
    return Invalid("the frame's stage 1-2 buffers do not hold " + std::to_string(n) + " points");
  if (t.ring_bound2.size() != rings)
    return Invalid("ring_bound2 has " + std::to_string(t.ring_bound2.size()) + " entries, not " +
                   std::to_string(rings));
  if (cells == 0 || p.sectors_near == 0 || p.sectors_far == 0 || p.width % p.sectors_near ||
      p.width % p.sectors_far)
    return Invalid("the sectors must divide the image width and the grid must have cells");

  const VkDeviceSize per_point = 4 * n, per_cell = 4 * VkDeviceSize(cells);
  const MemoryKind kind = MemoryKind::kDeviceLocal;
  LPIR_VK_ASSIGN_OR_RETURN(Buffer params_buffer, Buffer::Create(device, sizeof(Params), kind));
  LPIR_VK_ASSIGN_OR_RETURN(Buffer flags, Buffer::Create(device, per_point, kind));
  LPIR_VK_ASSIGN_OR_RETURN(Buffer r2, Buffer::Create(device, per_point, kind));
  LPIR_VK_ASSIGN_OR_RETURN(Buffer zt, Buffer::Create(device, per_point, kind));
  LPIR_VK_ASSIGN_OR_RETURN(Buffer point_pixel, Buffer::Create(device, per_point, kind));
  LPIR_VK_ASSIGN_OR_RETURN(Buffer ring_bound2, Buffer::Create(device, 4 * rings, kind));
  LPIR_VK_ASSIGN_OR_RETURN(Buffer point_cell, Buffer::Create(device, per_point, kind));
  LPIR_VK_ASSIGN_OR_RETURN(Buffer cell_zmin, Buffer::Create(device, per_cell, kind));
  LPIR_VK_ASSIGN_OR_RETURN(Buffer cell_zmax, Buffer::Create(device, per_cell, kind));
  LPIR_VK_ASSIGN_OR_RETURN(Buffer cell_count, Buffer::Create(device, per_cell, kind));

  LPIR_VK_ASSIGN_OR_RETURN(Transfer transfer, Transfer::Create(device));
  LPIR_VK_RETURN_IF_ERROR(transfer.Upload(params_buffer, &p, sizeof(Params)));
  if (n) {
    LPIR_VK_RETURN_IF_ERROR(transfer.Upload(flags, f.flags.data(), per_point));
    LPIR_VK_RETURN_IF_ERROR(transfer.Upload(r2, f.r2.data(), per_point));
    LPIR_VK_RETURN_IF_ERROR(transfer.Upload(zt, f.zt.data(), per_point));
    LPIR_VK_RETURN_IF_ERROR(transfer.Upload(point_pixel, f.point_pixel.data(), per_point));
  }
  LPIR_VK_RETURN_IF_ERROR(transfer.Upload(ring_bound2, t.ring_bound2.data(), 4 * rings));

  GridReduceBuffers bindings;
  bindings.params = &params_buffer;
  bindings.flags = &flags;
  bindings.r2 = &r2;
  bindings.zt = &zt;
  bindings.point_pixel = &point_pixel;
  bindings.ring_bound2 = &ring_bound2;
  bindings.point_cell = &point_cell;
  bindings.cell_zmin = &cell_zmin;
  bindings.cell_zmax = &cell_zmax;
  bindings.cell_count = &cell_count;
  LPIR_VK_ASSIGN_OR_RETURN(GridReduceStage stage, GridReduceStage::Create(device, bindings));
  LPIR_VK_RETURN_IF_ERROR(RunOnce(
      device, [&](CommandBuffer& cmd) { return stage.Record(cmd, uint32_t(n), cells); }, gpu_ns));

  f.point_cell.resize(n);
  f.cell_zmin.resize(cells);
  f.cell_zmax.resize(cells);
  f.cell_count.resize(cells);
  if (n) LPIR_VK_RETURN_IF_ERROR(transfer.Download(point_cell, f.point_cell.data(), per_point));
  LPIR_VK_RETURN_IF_ERROR(transfer.Download(cell_zmin, f.cell_zmin.data(), per_cell));
  LPIR_VK_RETURN_IF_ERROR(transfer.Download(cell_zmax, f.cell_zmax.data(), per_cell));
  LPIR_VK_RETURN_IF_ERROR(transfer.Download(cell_count, f.cell_count.data(), per_cell));
  return Status();
}

}  // namespace lpir::vk
