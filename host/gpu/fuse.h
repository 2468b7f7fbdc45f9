// fuse, on Vulkan: shaders/fuse.comp behind the generic dispatcher. FuseStage is bound
// once to the frame's buffers and recorded every frame.
#pragma once
#include <cstdint>

#include "host/gpu/frame_buffers.h"
#include "host/vk/buffer.h"
#include "host/vk/command_buffer.h"
#include "host/vk/device.h"
#include "host/vk/kernel.h"
#include "host/vk/result.h"

namespace lpir::vk {

// The bindings of shaders/fuse.comp; per-pixel buffers hold at least width * beams elements.
struct FuseBuffers {
  const Buffer* params = nullptr;        // one Params (uniform)
  const Buffer* pixel_class = nullptr;   // uint32 kPix* per pixel (classify_pixels)
  const Buffer* pixel_point = nullptr;   // uint32 winning point per pixel, kNone when none
  const Buffer* coarse = nullptr;        // uint32 per point (any buffer when there are no points)
  const Buffer* pixel_filled = nullptr;  // uint32 0 empty, 1 measured, 2 hole filled
  const Buffer* f_range = nullptr;       // float per pixel
  const Buffer* f_height = nullptr;      // float per pixel
  const Buffer* pixel_fused = nullptr;   // out: uint32 kPix* per pixel
};

class FuseStage {
 public:
  static constexpr uint32_t kLocalSize = 64;

  static Result<FuseStage> Create(const Device& device, const FuseBuffers& buffers);
  // Bound to one frame of a frame pipeline (host/gpu/frame_buffers.h).
  static Result<FuseStage> Create(const Device& device, const FrameBuffers& b) {
    return Create(device, FuseBuffers{&b.params, &b.pixel_class, &b.pixel_point, &b.coarse,
                                      &b.pixel_filled, &b.f_range, &b.f_height, &b.pixel_fused});
  }

  // Records the dispatch over a width x beams image (the Params uploaded must say the same; four
  // pixels an invocation when the width is a multiple of 4). No barrier: the caller orders it
  // with the stages around.
  Status Record(CommandBuffer& cmd, uint32_t width, uint32_t beams) const;
  // The same over a frame of `size` (the frame pipeline's call).
  Status Record(CommandBuffer& cmd, const FrameSize& size) const {
    return Record(cmd, size.width, size.beams);
  }

 private:
  explicit FuseStage(Kernel kernel) : kernel_(std::move(kernel)) {}

  Kernel kernel_;
};

}  // namespace lpir::vk
