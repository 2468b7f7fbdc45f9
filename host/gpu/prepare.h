// prepare, on Vulkan: shaders/prepare.comp behind the generic dispatcher. PrepareStage
// is bound once to the frame's buffers and recorded every frame.
#pragma once
#include <cstdint>

#include "host/gpu/frame_buffers.h"
#include "host/vk/buffer.h"
#include "host/vk/command_buffer.h"
#include "host/vk/device.h"
#include "host/vk/kernel.h"
#include "host/vk/result.h"

namespace lpir::vk {

// The bindings of shaders/prepare.comp, each buffer holding at least n elements.
struct PrepareBuffers {
  const Buffer* params = nullptr;  // one Params (uniform); has_ring says whether ring is read
  const Buffer* points = nullptr;  // vec4 x, y, z, raw intensity per point
  const Buffer* ring = nullptr;    // int32 per point; any buffer when has_ring is 0
  const Buffer* flags = nullptr;   // out: uint32 kPoint* bits
  const Buffer* zt = nullptr;      // out: float corrected height, eq. 3
  const Buffer* r2 = nullptr;      // out: float squared planar range
};

class PrepareStage {
 public:
  static constexpr uint32_t kLocalSize = 64;

  static Result<PrepareStage> Create(const Device& device, const PrepareBuffers& buffers);
  // Bound to one frame of a frame pipeline (host/gpu/frame_buffers.h).
  static Result<PrepareStage> Create(const Device& device, const FrameBuffers& b) {
    return Create(device, PrepareBuffers{&b.params, &b.points, &b.ring, &b.flags, &b.zt, &b.r2});
  }

  // Records the dispatch over n points (no barrier: the caller orders it with the stages around).
  Status Record(CommandBuffer& cmd, uint32_t n) const;
  // The same over a frame of `size` (the frame pipeline's call).
  Status Record(CommandBuffer& cmd, const FrameSize& size) const { return Record(cmd, size.n); }

 private:
  explicit PrepareStage(Kernel kernel) : kernel_(std::move(kernel)) {}

  Kernel kernel_;
};

}  // namespace lpir::vk
