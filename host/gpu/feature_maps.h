// feature_maps, on Vulkan: shaders/feature_maps.comp behind the generic dispatcher.
// FeatureMapsStage is bound once to the frame's buffers and recorded every frame: measure and
// fill, a barrier, slope, edges and variances.
#pragma once
#include <cstdint>

#include "host/gpu/frame_buffers.h"
#include "host/vk/buffer.h"
#include "host/vk/command_buffer.h"
#include "host/vk/device.h"
#include "host/vk/kernel.h"
#include "host/vk/result.h"

namespace lpir::vk {

// The bindings of shaders/feature_maps.comp: per-point buffers of at least n elements, per-pixel
// buffers of at least width * beams elements.
struct FeatureMapsBuffers {
  const Buffer* params = nullptr;        // one Params (uniform): width, beams, hole_gap
  const Buffer* pixel_point = nullptr;   // uint32 winning point per pixel, kNone empty (project)
  const Buffer* r2 = nullptr;            // float squared planar range per point (prepare)
  const Buffer* zt = nullptr;            // float corrected height per point (prepare)
  const Buffer* pixel_filled = nullptr;  // out: uint32 0 empty, 1 measured, 2 filled
  const Buffer* f_range = nullptr;       // out: floats per pixel
  const Buffer* f_height = nullptr;
  const Buffer* f_slope = nullptr;
  const Buffer* f_edge_l = nullptr;
  const Buffer* f_edge_r = nullptr;
  const Buffer* f_varz = nullptr;
  const Buffer* feature_pack = nullptr;  // scratch: PackBytes(pixels), pass 0 or 1 -> pass 2
};

class FeatureMapsStage {
 public:
  static constexpr uint32_t kLocalSize = 64;
  // Pixels of a row per invocation of pass 2 in the CPU shape (host/vk/shape.h; the GPU's is 1).
  static constexpr uint32_t kCpuItems = 32;

  // The scratch buffer's size: a uvec4 per pixel (filled, the bits of range and height, and 0), so
  // that pass 2 reads a pixel with one load (docs/decisions/feature_maps.md).
  static VkDeviceSize PackBytes(uint64_t pixels) { return 16 * (pixels == 0 ? 1 : pixels); }

  static Result<FeatureMapsStage> Create(const Device& device, const FeatureMapsBuffers& buffers);
  // Bound to one frame of a frame pipeline (host/gpu/frame_buffers.h).
  static Result<FeatureMapsStage> Create(const Device& device, const FrameBuffers& b) {
    return Create(device, FeatureMapsBuffers{&b.params, &b.pixel_point, &b.r2, &b.zt,
                                             &b.pixel_filled, &b.f_range, &b.f_height, &b.f_slope,
                                             &b.f_edge_l, &b.f_edge_r, &b.f_varz, &b.feature_pack});
  }

  // Records the measure-and-fill pass over the width x beams image (pass 1, one invocation per
  // four pixels, when the width is a multiple of 4, else pass 0, one per pixel), a compute ->
  // compute barrier and the features pass 2 (one invocation per run of the shape's items,
  // kCpuItems or 1, pixels of a row), with no barrier before or after (the caller orders it with
  // the stages around).
  Status Record(CommandBuffer& cmd, uint32_t width, uint32_t beams) const;
  // The same over a frame of `size` (the frame pipeline's call).
  Status Record(CommandBuffer& cmd, const FrameSize& size) const {
    return Record(cmd, size.width, size.beams);
  }

  // The kernel's shape (host/vk/shape.h), read from LPIR_VK_SHAPE or the device at Create.
  Shape shape() const { return kernel_.shape(); }

 private:
  explicit FeatureMapsStage(Kernel kernel) : kernel_(std::move(kernel)) {}

  Kernel kernel_;
};

}  // namespace lpir::vk
