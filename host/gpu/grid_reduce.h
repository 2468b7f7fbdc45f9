// grid_reduce, on Vulkan: shaders/grid_reduce.comp behind the generic dispatcher.
// GridReduceStage is bound once to the frame's buffers and recorded every frame: the cell clear,
// a barrier, the per-point reduction.
#pragma once
#include <cstdint>

#include "host/gpu/frame_buffers.h"
#include "host/vk/buffer.h"
#include "host/vk/command_buffer.h"
#include "host/vk/device.h"
#include "host/vk/kernel.h"
#include "host/vk/result.h"

namespace lpir::vk {

// The bindings of shaders/grid_reduce.comp: per-point buffers of at least n elements, per-cell
// buffers of at least CellCount(p) elements.
struct GridReduceBuffers {
  const Buffer* params = nullptr;       // one Params (uniform)
  const Buffer* flags = nullptr;        // uint32 kPoint* bits (prepare)
  const Buffer* r2 = nullptr;           // float squared planar range (prepare)
  const Buffer* zt = nullptr;           // float corrected height (prepare)
  const Buffer* point_pixel = nullptr;  // uint32 pixel per point (project)
  const Buffer* ring_bound2 = nullptr;  // Tables::ring_bound2, rings_near + rings_far floats
  const Buffer* point_cell = nullptr;   // out: uint32 cell per point, kNone without one
  const Buffer* cell_zmin = nullptr;    // out: uint32 ordered key of min z_t, kNone when empty
  const Buffer* cell_zmax = nullptr;    // out: uint32 ordered key of max z_t, 0 when empty
  const Buffer* cell_count = nullptr;   // out: uint32 points per cell
};

class GridReduceStage {
 public:
  static constexpr uint32_t kLocalSize = 64;
  // Points per invocation of the reduction in the CPU shape (host/vk/shape.h; the GPU's is 1).
  static constexpr uint32_t kCpuItems = 32;

  static Result<GridReduceStage> Create(const Device& device, const GridReduceBuffers& buffers);
  // Bound to one frame of a frame pipeline (host/gpu/frame_buffers.h).
  static Result<GridReduceStage> Create(const Device& device, const FrameBuffers& b) {
    const TableBuffers& t = *b.tables;
    return Create(
        device, GridReduceBuffers{&b.params, &b.flags, &b.r2, &b.zt, &b.point_pixel, &t.ring_bound2,
                                  &b.point_cell, &b.cell_zmin, &b.cell_zmax, &b.cell_count});
  }

  // Records the clear of `cells` cells, a compute -> compute barrier and the reduction over n
  // points (no barrier before or after: the caller orders it with the stages around).
  Status Record(CommandBuffer& cmd, uint32_t n, uint32_t cells) const;
  // The same over a frame of `size` (the frame pipeline's call).
  Status Record(CommandBuffer& cmd, const FrameSize& size) const {
    return Record(cmd, size.n, size.cells);
  }

  // The kernel's shape (host/vk/shape.h), read from LPIR_VK_SHAPE or the device at Create.
  Shape shape() const { return kernel_.shape(); }

 private:
  explicit GridReduceStage(Kernel kernel) : kernel_(std::move(kernel)) {}

  Kernel kernel_;
};

}  // namespace lpir::vk
