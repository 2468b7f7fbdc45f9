// grow, on Vulkan: shaders/grow.comp behind the generic dispatcher. GrowStage is bound
// once to the frame's buffers and recorded every frame: five passes, one pixel an invocation,
// whatever the data.
#pragma once
#include <cstdint>

#include "host/gpu/frame_buffers.h"
#include "host/vk/buffer.h"
#include "host/vk/command_buffer.h"
#include "host/vk/device.h"
#include "host/vk/kernel.h"
#include "host/vk/result.h"

namespace lpir::vk {

// The bindings of shaders/grow.comp; per-pixel buffers hold at least width * beams elements.
struct GrowBuffers {
  const Buffer* params = nullptr;       // one Params (uniform)
  const Buffer* pixel_fused = nullptr;  // uint32 kPix* per pixel (fuse)
  const Buffer* f_height = nullptr;     // float per pixel
  const Buffer* f_range = nullptr;      // float per pixel
  const Buffer* pixel_grown = nullptr;  // out: uint32 kPix* per pixel
  const Buffer* pixel_comp = nullptr;   // out: uint32 component label per pixel, kNone off ground
  const Buffer* pixel_label = nullptr;  // out: uint32 kPix* per pixel
  const Buffer* grow_reach = nullptr;   // uint32 per pixel + 1 (ReachBytes): growing's union-find
  const Buffer* grow_sizes = nullptr;   // 2 uint32 per pixel (SizesBytes): sizes, seed counts
};

class GrowStage {
 public:
  static constexpr uint32_t kLocalSize = 64;
  static constexpr uint32_t kPasses = 5;  // dispatches a frame

  // The grow_reach buffer's size for an image of `pixels` pixels.
  static VkDeviceSize ReachBytes(uint64_t pixels) { return 4 * (VkDeviceSize(pixels) + 1); }
  // The grow_sizes buffer's size: each component's size, then its seed count, by root pixel.
  static VkDeviceSize SizesBytes(uint64_t pixels) { return 8 * VkDeviceSize(pixels); }

  static Result<GrowStage> Create(const Device& device, const GrowBuffers& buffers);
  // Bound to one frame of a frame pipeline (host/gpu/frame_buffers.h).
  static Result<GrowStage> Create(const Device& device, const FrameBuffers& b) {
    return Create(device,
                  GrowBuffers{&b.params, &b.pixel_fused, &b.f_height, &b.f_range, &b.pixel_grown,
                              &b.pixel_comp, &b.pixel_label, &b.grow_reach, &b.grow_sizes});
  }

  // Records the whole stage over a width x beams image (the Params uploaded to buffers.params
  // must say the same), with compute-to-compute barriers between its passes but none before the
  // first or after the last (the caller orders it with the stages around).
  Status Record(CommandBuffer& cmd, uint32_t width, uint32_t beams) const;
  // The same over a frame of `size` (the frame pipeline's call).
  Status Record(CommandBuffer& cmd, const FrameSize& size) const {
    return Record(cmd, size.width, size.beams);
  }

 private:
  explicit GrowStage(Kernel kernel) : kernel_(std::move(kernel)) {}

  Kernel kernel_;
};

}  // namespace lpir::vk
