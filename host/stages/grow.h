// Stage 8, grow, on Vulkan: shaders/grow.comp behind the generic dispatcher. GrowStage is the
// per-frame piece (bound once to the frame's buffers, recorded every frame: a fixed-point loop of
// `max_iters` gated sweeps, then a union-find for the components, no CPU round trip); RunGrow is
// the one-shot twin of lpir::Grow for tests and tools.
#pragma once
#include <cstdint>

#include "host/vk/buffer.h"
#include "host/vk/command_buffer.h"
#include "host/vk/context.h"
#include "host/vk/device.h"
#include "host/vk/kernel.h"
#include "host/vk/result.h"
#include "reference_cpu/frame.h"
#include "reference_cpu/params.h"

namespace lpir::vk {

// The bindings of shaders/grow.comp; per-pixel buffers hold at least width * beams elements.
struct GrowBuffers {
  const Buffer* params = nullptr;       // one Params (uniform)
  const Buffer* pixel_fused = nullptr;  // uint32 kPix* per pixel (stage 7)
  const Buffer* f_inten = nullptr;      // float per pixel
  const Buffer* f_height = nullptr;     // float per pixel
  const Buffer* f_range = nullptr;      // float per pixel
  const Buffer* pixel_grown = nullptr;  // out: uint32 kPix* per pixel (also the growing state)
  const Buffer* pixel_comp = nullptr;   // out: uint32 component label per pixel, kNone off ground
  const Buffer* pixel_label = nullptr;  // out: uint32 kPix* per pixel (step masks before that)
  const Buffer* scratch = nullptr;      // uint32 per pixel: the unknown pixels, then the roots
  const Buffer* sizes = nullptr;        // uint32 per pixel: component sizes
  const Buffer* flags = nullptr;        // GrowStage::FlagWords(max_iters) uint32 (see below)
};

// What the flags buffer says after a frame (GrowStage::ReadReport).
struct GrowReport {
  uint32_t grow_sweeps = 0;  // sweeps run, the last one proving the fixed point; 0: not reached
  bool converged() const { return grow_sweeps != 0; }
};

class GrowStage {
 public:
  static constexpr uint32_t kLocalSize = 64;

  // The flags buffer: three words of the list, max_iters + 1 indirect dispatch arguments
  // (shaders/grow.comp says how the sweeps set them), then the summary word
  // flags[3 (max_iters + 2)] (grow sweeps, 0 = not converged).
  static uint32_t FlagWords(uint32_t max_iters) { return 3 * (max_iters + 2) + 1; }
  static GrowReport ReadReport(const uint32_t* flags, uint32_t max_iters) {
    return {flags[3 * (max_iters + 2)]};
  }

  // `max_iters` (Params::grow_max_iters, at least 1): the growing sweeps recorded; the sweeps
  // after the first one that changes nothing launch no workgroup.
  static Result<GrowStage> Create(const Device& device, const GrowBuffers& buffers,
                                  uint32_t max_iters);

  // Records the whole stage over a width x beams image (the Params uploaded to buffers.params
  // must say the same), with compute-to-compute barriers between its passes but none before the
  // first or after the last (the caller orders it with the stages around). The production
  // pipeline must check the summary word (ReadReport) and reject a frame whose growing loop did
  // not converge.
  Status Record(CommandBuffer& cmd, uint32_t width, uint32_t beams) const;

  uint32_t max_iters() const { return max_iters_; }

 private:
  GrowStage(Kernel kernel, const Buffer* flags, uint32_t max_iters)
      : kernel_(std::move(kernel)), flags_(flags), max_iters_(max_iters) {}

  Kernel kernel_;
  const Buffer* flags_;  // also the sweeps' indirect dispatch arguments
  uint32_t max_iters_ = 0;
};

// Stage 8 on the GPU, the twin of lpir::Grow(p, f): allocates device-local buffers, uploads
// f.pixel_fused, f.f_inten, f.f_height and f.f_range, runs, and fills f.pixel_grown,
// f.pixel_comp and f.pixel_label (nothing else of f is touched). An error when a per-pixel input
// does not hold width * beams elements, or when the growing loop's fixed point was not reached
// within p.grow_max_iters sweeps (outputs then still downloaded). `report`, when given, gets the
// sweep count; `gpu_ns` the stage's GPU time in nanoseconds (-1 without timestamps). Waits for the GPU.
Status RunGrow(const Context& context, const Params& p, Frame& f, GrowReport* report = nullptr,
               double* gpu_ns = nullptr);

}  // namespace lpir::vk
