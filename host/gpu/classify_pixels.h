// classify_pixels, on Vulkan: shaders/classify_pixels.comp behind the generic
// dispatcher. ClassifyPixelsStage is bound once to the frame's buffers and recorded every
// frame.
#pragma once
#include <cstdint>

#include "host/gpu/frame_buffers.h"
#include "host/vk/buffer.h"
#include "host/vk/command_buffer.h"
#include "host/vk/device.h"
#include "host/vk/kernel.h"
#include "host/vk/result.h"

namespace lpir::vk {

// The bindings of shaders/classify_pixels.comp, each per-pixel buffer holding at least
// width * beams elements.
struct ClassifyPixelsBuffers {
  const Buffer* params = nullptr;        // one Params (uniform): t_edge, t_slope_*, t_stdz_*
  const Buffer* pixel_filled = nullptr;  // uint32 (feature_maps): 0 empty
  const Buffer* f_edge_l = nullptr;      // floats (feature_maps)
  const Buffer* f_edge_r = nullptr;
  const Buffer* f_slope = nullptr;
  const Buffer* f_varz = nullptr;
  const Buffer* pixel_class = nullptr;  // out: uint32 kPix*
};

class ClassifyPixelsStage {
 public:
  static constexpr uint32_t kLocalSize = 64;

  static Result<ClassifyPixelsStage> Create(const Device& device,
                                            const ClassifyPixelsBuffers& buffers);
  // Bound to one frame of a frame pipeline (host/gpu/frame_buffers.h).
  static Result<ClassifyPixelsStage> Create(const Device& device, const FrameBuffers& b) {
    return Create(device,
                  ClassifyPixelsBuffers{&b.params, &b.pixel_filled, &b.f_edge_l, &b.f_edge_r,
                                        &b.f_slope, &b.f_varz, &b.pixel_class});
  }

  // Records the dispatches over `pixels` pixels (no barrier: the caller orders it with the stages
  // around).
  Status Record(CommandBuffer& cmd, uint32_t pixels) const;
  // The same over a frame of `size` (the frame pipeline's call).
  Status Record(CommandBuffer& cmd, const FrameSize& size) const {
    return Record(cmd, size.pixels);
  }

 private:
  explicit ClassifyPixelsStage(Kernel kernel) : kernel_(std::move(kernel)) {}

  Kernel kernel_;
};

}  // namespace lpir::vk
