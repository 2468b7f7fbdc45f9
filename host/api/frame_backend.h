// FrameBackend: what a Segmenter runs its frames on, one shape for both backends. The twins are
// CpuPipeline (the CPU reference, host/api/cpu_pipeline.h) and VulkanPipeline (a vk::FramePipeline
// on its own device, host/api/vulkan_pipeline.h). A backend holds a fixed number of slots, each one
// frame from Stage to Collect. The Segmenter chooses the slots (its blocks and batches) and checks
// every cloud once before it is staged; a backend trusts both. Errors are std::runtime_error.
#pragma once
#include <cstdint>

#include "reference_cpu/cloud.h"
#include "reference_cpu/frame.h"
#include "reference_cpu/params.h"
#include "reference_cpu/pipeline.h"

namespace lpir {

class FrameBackend {
 public:
  virtual ~FrameBackend() = default;

  // Stages `cloud` in the free slot `slot`; its frame runs with the backend's Params seen from
  // `mount` (WithMount). The cloud is checked: at most the backend's max_points points, a ring
  // field empty or one entry a point. `borrowed`: the caller keeps the cloud alive and unchanged
  // until the slot's frame is collected, so a backend may read it in place (the CPU does) rather
  // than copy it; otherwise it is copied before Stage returns.
  virtual void Stage(uint32_t slot, const Cloud& cloud, const Mount& mount, bool borrowed) = 0;
  // Starts the frames staged in slots first .. first + count - 1 as one batch
  // (1 <= count <= batch()).
  virtual void SubmitStaged(uint32_t first, uint32_t count) = 0;
  // Waits for slot `slot`'s frame and frees the slot. Fills out.n, out.label, out.why and
  // out.label_why, and every other buffer of the frame with `all_buffers` (the CPU fills them
  // always); `times` (optional) gets the frame's times.
  virtual void Collect(uint32_t slot, Frame& out, bool all_buffers, FrameTimes* times) = 0;

  // The most frames one SubmitStaged takes.
  virtual uint32_t batch() const = 0;
  // Device memory held for the frames, in bytes (0 on the CPU).
  virtual uint64_t device_bytes() const = 0;
  // The device is a CPU driver such as lavapipe (false on the CPU reference).
  virtual bool on_cpu_driver() const = 0;
};

}  // namespace lpir
