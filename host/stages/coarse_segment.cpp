// Stage 4, coarse segment, on Vulkan: the kernel's bindings and the one-shot runner.
#include "host/stages/coarse_segment.h"

#include <cstdint>
#include <string>

#include "host/vk/run_once.h"
#include "host/vk/transfer.h"

namespace lpir::vk {
namespace {
#include "shaders/coarse_segment.spv.h"  // kCoarseSegmentSpv, from shaders/coarse_segment.comp

struct Push {
  uint32_t count;  // cells (passes 0, 2, 4) or points (passes 1, 3, 5)
};

Error Invalid(const std::string& message) {
  Error e;
  e.result = VK_ERROR_UNKNOWN;
  e.message = "coarse_segment: " + message;
  return e;
}
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

Status RunCoarseSegment(const Context& context, const Cloud& cloud, const Params& p,
                        const Tables& t, Frame& f, double* gpu_ns) {
  const Device& device = context.device();
  const uint64_t n = f.n;
  const uint32_t cells = CellCount(p), rings = p.rings_near + p.rings_far;
  if (cloud.xyzi.size() != 4 * n || f.zt.size() != n || f.point_cell.size() != n)
    return Invalid("the cloud and the frame's stage 1-3 point buffers do not hold " +
                   std::to_string(n) + " points");
  if (f.cell_zmin.size() != cells || f.cell_zmax.size() != cells || f.cell_count.size() != cells)
    return Invalid("the frame's stage 3 cell buffers do not hold " + std::to_string(cells) +
                   " cells");
  if (t.ring_inner.size() != rings)
    return Invalid("ring_inner has " + std::to_string(t.ring_inner.size()) + " entries, not " +
                   std::to_string(rings));
  if (cells == 0 || p.sectors_near == 0 || p.sectors_far == 0)
    return Invalid("the grid must have cells");

  const VkDeviceSize per_point = 4 * n, per_cell = 4 * VkDeviceSize(cells);
  const MemoryKind kind = MemoryKind::kDeviceLocal;
  LPIR_VK_ASSIGN_OR_RETURN(Buffer params_buffer, Buffer::Create(device, sizeof(Params), kind));
  LPIR_VK_ASSIGN_OR_RETURN(Buffer xyzi, Buffer::Create(device, 4 * per_point, kind));
  LPIR_VK_ASSIGN_OR_RETURN(Buffer zt, Buffer::Create(device, per_point, kind));
  LPIR_VK_ASSIGN_OR_RETURN(Buffer point_cell, Buffer::Create(device, per_point, kind));
  LPIR_VK_ASSIGN_OR_RETURN(Buffer cell_zmin, Buffer::Create(device, per_cell, kind));
  LPIR_VK_ASSIGN_OR_RETURN(Buffer cell_zmax, Buffer::Create(device, per_cell, kind));
  LPIR_VK_ASSIGN_OR_RETURN(Buffer cell_count, Buffer::Create(device, per_cell, kind));
  LPIR_VK_ASSIGN_OR_RETURN(Buffer ring_inner, Buffer::Create(device, 4 * rings, kind));
  LPIR_VK_ASSIGN_OR_RETURN(Buffer cell_seed_mode, Buffer::Create(device, per_cell, kind));
  LPIR_VK_ASSIGN_OR_RETURN(Buffer cell_plane, Buffer::Create(device, 8 * per_cell, kind));
  LPIR_VK_ASSIGN_OR_RETURN(Buffer coarse, Buffer::Create(device, per_point, kind));
  LPIR_VK_ASSIGN_OR_RETURN(Buffer coarse_scratch,
                           Buffer::Create(device, CoarseSegmentStage::ScratchBytes(cells), kind));

  LPIR_VK_ASSIGN_OR_RETURN(Transfer transfer, Transfer::Create(device));
  LPIR_VK_RETURN_IF_ERROR(transfer.Upload(params_buffer, &p, sizeof(Params)));
  if (n) {
    LPIR_VK_RETURN_IF_ERROR(transfer.Upload(xyzi, cloud.xyzi.data(), 4 * per_point));
    LPIR_VK_RETURN_IF_ERROR(transfer.Upload(zt, f.zt.data(), per_point));
    LPIR_VK_RETURN_IF_ERROR(transfer.Upload(point_cell, f.point_cell.data(), per_point));
  }
  LPIR_VK_RETURN_IF_ERROR(transfer.Upload(cell_zmin, f.cell_zmin.data(), per_cell));
  LPIR_VK_RETURN_IF_ERROR(transfer.Upload(cell_zmax, f.cell_zmax.data(), per_cell));
  LPIR_VK_RETURN_IF_ERROR(transfer.Upload(cell_count, f.cell_count.data(), per_cell));
  LPIR_VK_RETURN_IF_ERROR(transfer.Upload(ring_inner, t.ring_inner.data(), 4 * rings));

  CoarseSegmentBuffers bindings;
  bindings.params = &params_buffer;
  bindings.xyzi = &xyzi;
  bindings.zt = &zt;
  bindings.point_cell = &point_cell;
  bindings.cell_zmin = &cell_zmin;
  bindings.cell_zmax = &cell_zmax;
  bindings.cell_count = &cell_count;
  bindings.ring_inner = &ring_inner;
  bindings.cell_seed_mode = &cell_seed_mode;
  bindings.cell_plane = &cell_plane;
  bindings.coarse = &coarse;
  bindings.coarse_scratch = &coarse_scratch;
  LPIR_VK_ASSIGN_OR_RETURN(CoarseSegmentStage stage, CoarseSegmentStage::Create(device, bindings));
  LPIR_VK_RETURN_IF_ERROR(RunOnce(
      device, [&](CommandBuffer& cmd) { return stage.Record(cmd, uint32_t(n), cells); }, gpu_ns));

  f.cell_seed_mode.resize(cells);
  f.cell_plane.resize(size_t(cells) * 8);
  f.coarse.resize(n);
  LPIR_VK_RETURN_IF_ERROR(transfer.Download(cell_seed_mode, f.cell_seed_mode.data(), per_cell));
  LPIR_VK_RETURN_IF_ERROR(transfer.Download(cell_plane, f.cell_plane.data(), 8 * per_cell));
  if (n) LPIR_VK_RETURN_IF_ERROR(transfer.Download(coarse, f.coarse.data(), per_point));
  return Status();
}

}  // namespace lpir::vk
