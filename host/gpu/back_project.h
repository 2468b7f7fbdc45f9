// back_project, on Vulkan: shaders/back_project.comp behind the generic dispatcher.
// BackProjectStage is bound once to the frame's buffers and recorded every frame.
// The output is one byte per point, label | why << 1 (Frame::label_why), four points a uint32
// word (the device is created without the 8-bit storage feature): a frame downloads n bytes
// rounded up to a word and unpacks label and why on the host.
#pragma once
#include <cstdint>

#include "host/gpu/frame_buffers.h"
#include "host/vk/buffer.h"
#include "host/vk/command_buffer.h"
#include "host/vk/device.h"
#include "host/vk/kernel.h"
#include "host/vk/result.h"

namespace lpir::vk {

// The bindings of shaders/back_project.comp; per-point buffers hold at least n elements,
// per-pixel ones width * beams.
struct BackProjectBuffers {
  const Buffer* params = nullptr;       // one Params (uniform)
  const Buffer* flags = nullptr;        // uint32 kPoint* bits per point
  const Buffer* point_pixel = nullptr;  // uint32 pixel per point, kNone when invalid
  const Buffer* pixel_point = nullptr;  // uint32 winning point per pixel
  const Buffer* pixel_label = nullptr;  // uint32 kPix* per pixel (grow)
  const Buffer* f_range = nullptr;      // float per pixel
  const Buffer* f_height = nullptr;     // float per pixel
  const Buffer* r2 = nullptr;           // float per point
  const Buffer* zt = nullptr;           // float per point
  const Buffer* coarse = nullptr;       // uint32 per point
  const Buffer* label_why = nullptr;    // out: a byte per point (PackLabelWhy), at least
                                        // LabelWhyBytes(n) bytes
};

class BackProjectStage {
 public:
  static constexpr uint32_t kLocalSize = 64;

  // Bytes of the label_why output for n points: n rounded up to a whole word.
  static constexpr uint64_t LabelWhyBytes(uint64_t n) { return (n + 3) / 4 * 4; }

  static Result<BackProjectStage> Create(const Device& device, const BackProjectBuffers& buffers);
  // Bound to one frame of a frame pipeline (host/gpu/frame_buffers.h).
  static Result<BackProjectStage> Create(const Device& device, const FrameBuffers& b) {
    return Create(device, BackProjectBuffers{&b.params, &b.flags, &b.point_pixel, &b.pixel_point,
                                             &b.pixel_label, &b.f_range, &b.f_height, &b.r2, &b.zt,
                                             &b.coarse, &b.label_why});
  }

  // Records the dispatch over n points (no barrier: the caller orders it with the stages around).
  Status Record(CommandBuffer& cmd, uint32_t n) const;
  // The same over a frame of `size` (the frame pipeline's call).
  Status Record(CommandBuffer& cmd, const FrameSize& size) const { return Record(cmd, size.n); }

 private:
  explicit BackProjectStage(Kernel kernel) : kernel_(std::move(kernel)) {}

  Kernel kernel_;
};

}  // namespace lpir::vk
