// coarse_segment, on Vulkan: shaders/coarse_segment.comp behind the generic dispatcher.
// CoarseSegmentStage is bound once to the frame's buffers and recorded every frame: six passes
// with a compute -> compute barrier between each two.
#pragma once
#include <cstdint>

#include "host/gpu/frame_buffers.h"
#include "host/vk/buffer.h"
#include "host/vk/command_buffer.h"
#include "host/vk/device.h"
#include "host/vk/kernel.h"
#include "host/vk/result.h"

namespace lpir::vk {

// The bindings of shaders/coarse_segment.comp: per-point buffers of at least n elements, per-cell
// buffers of at least CellCount(p) elements (any buffer when there are no points).
struct CoarseSegmentBuffers {
  const Buffer* params = nullptr;          // one Params (uniform)
  const Buffer* xyzi = nullptr;            // float x, y, z, intensity per point (the cloud)
  const Buffer* zt = nullptr;              // float corrected height (prepare)
  const Buffer* point_cell = nullptr;      // uint32 cell per point, kNone without one (grid_reduce)
  const Buffer* cell_zmin = nullptr;       // uint32 ordered key of min z_t (grid_reduce)
  const Buffer* cell_zmax = nullptr;       // uint32 ordered key of max z_t (grid_reduce)
  const Buffer* cell_count = nullptr;      // uint32 points per cell (grid_reduce)
  const Buffer* ring_inner = nullptr;      // Tables::ring_inner, rings_near + rings_far floats
  const Buffer* cell_seed_mode = nullptr;  // out: uint32 per cell, 0 / 1 / 2
  const Buffer* cell_plane = nullptr;      // out: int32, 8 per cell
  const Buffer* coarse = nullptr;          // out: uint32 per point, 1 ground
  const Buffer* coarse_scratch = nullptr;  // ScratchBytes(cells): per-cell sums, the stage's own
};

class CoarseSegmentStage {
 public:
  static constexpr uint32_t kLocalSize = 64;
  static constexpr uint32_t kScratchWords = 24;  // per cell, shaders/coarse_segment.comp
  // Points per invocation of passes 1, 3, 5 in the CPU shape (host/vk/shape.h; the GPU's is 1).
  static constexpr uint32_t kCpuItems = 32;

  static VkDeviceSize ScratchBytes(uint32_t cells) {
    return 4 * VkDeviceSize(kScratchWords) * cells;
  }

  static Result<CoarseSegmentStage> Create(const Device& device,
                                           const CoarseSegmentBuffers& buffers);
  // Bound to one frame of a frame pipeline (host/gpu/frame_buffers.h).
  static Result<CoarseSegmentStage> Create(const Device& device, const FrameBuffers& b) {
    const TableBuffers& t = *b.tables;
    return Create(
        device, CoarseSegmentBuffers{&b.params, &b.points, &b.zt, &b.point_cell, &b.cell_zmin,
                                     &b.cell_zmax, &b.cell_count, &t.ring_inner, &b.cell_seed_mode,
                                     &b.cell_plane, &b.coarse, &b.coarse_scratch});
  }

  // Records the six passes over `cells` cells and n points with a compute -> compute barrier
  // between each two (none before or after: the caller orders it with the stages around).
  Status Record(CommandBuffer& cmd, uint32_t n, uint32_t cells) const;
  // The same over a frame of `size` (the frame pipeline's call).
  Status Record(CommandBuffer& cmd, const FrameSize& size) const {
    return Record(cmd, size.n, size.cells);
  }

  // The kernel's shape (host/vk/shape.h), read from LPIR_VK_SHAPE or the device at Create.
  Shape shape() const { return kernel_.shape(); }

 private:
  explicit CoarseSegmentStage(Kernel kernel) : kernel_(std::move(kernel)) {}

  Kernel kernel_;
};

}  // namespace lpir::vk
