// FramePipeline: the whole method (stages 1-9) on one Vulkan device. A frame is one command
// buffer: the cloud's upload, the nine stages back to back with barriers, the labels' download;
// the growing loop ends on the GPU (indirect sweeps, host/stages/grow.h). Every device buffer is
// allocated once, for `max_points` points and the sensor's image and grid; a frame allocates
// nothing. Several frames in flight: each slot owns its command buffer, fence, staging buffers
// and timestamps, and the slots share the device buffers, ordered by a barrier at the head of
// every frame (one queue runs the frames in submission order, each overlapping the host's work
// on the others: reading files, writing labels).
#pragma once
#include <cstdint>
#include <memory>
#include <vector>

#include "host/stages/grow.h"
#include "host/vk/buffer.h"
#include "host/vk/command_buffer.h"
#include "host/vk/context.h"
#include "host/vk/fence.h"
#include "host/vk/result.h"
#include "host/vk/timestamp_queries.h"
#include "reference_cpu/cloud.h"
#include "reference_cpu/frame.h"
#include "reference_cpu/params.h"
#include "reference_cpu/pipeline.h"

namespace lpir::vk {

class FramePipeline {
 public:
  // Builds the nine stages over buffers for clouds of up to `max_points` points (at least 1) and
  // uploads the tables. `slots`: frames that may be in flight at once (at least 1).
  static Result<FramePipeline> Create(const Context& context, const Params& params,
                                      const Tables& tables, uint32_t max_points, uint32_t slots);

  // Copies `cloud` into slot `slot`'s staging buffer, records its frame and submits it. The slot
  // must be free: never submitted, or collected since. An error (nothing submitted) for a cloud
  // over max_points or with a ring field of another length.
  Status Submit(uint32_t slot, const Cloud& cloud);

  // Waits for slot `slot`'s frame and frees the slot. Fills out.n, out.label and out.why; with
  // `all_buffers`, every other buffer of the frame too (read back after the wait, so only for
  // the frame submitted last: the slots share the device buffers; asked of an earlier frame, an
  // error that leaves the slot as it was). `times` (optional) gets the
  // frame's GPU times (timestamps), `grow` (optional) the growing loops' report, written once the
  // frame has finished. An error when the growing loop did not reach its fixed point within
  // Params::grow_max_iters sweeps (out.label is then not valid; StagedCloud gives the cloud back
  // for the reference to label).
  Status Collect(uint32_t slot, Frame& out, bool all_buffers = false, FrameTimes* times = nullptr,
                 GrowReport* grow = nullptr);

  // The cloud last submitted to slot `slot`, read back from its staging buffer (valid until the
  // slot's next Submit).
  Cloud StagedCloud(uint32_t slot) const;

  uint32_t slots() const { return uint32_t(slots_.size()); }
  uint32_t max_points() const { return max_points_; }
  // Vulkan memory allocated, in bytes: the device buffers and the slots' staging buffers (all
  // made by Create: constant for the pipeline's life).
  uint64_t device_bytes() const { return device_bytes_; }
  // The commands of the frame recorded last (by the latest Submit), counted at record time.
  const RecordCounts& last_counts() const { return last_counts_; }

  ~FramePipeline();  // waits for the frames in flight
  FramePipeline(FramePipeline&&) noexcept;
  FramePipeline& operator=(FramePipeline&&) noexcept;

 private:
  struct Buffers;  // every device buffer, at stable addresses (the stages keep pointers)
  struct Stages;   // the nine recorded stages
  struct Slot {
    CommandBuffer cmd;
    Fence fence;
    Buffer upload;    // host-visible: points (16 bytes each), then rings (4 bytes each)
    Buffer download;  // host-visible: label words, why words, the grow summary word
    std::vector<TimestampQueries> queries;  // one pool of kQueries, or none without timestamps
    bool busy = false, has_ring = false;
    uint32_t n = 0;
    uint64_t serial = 0;  // submission order
  };
  static constexpr uint32_t kQueries = 12;  // start, after upload, after each stage, after download

  FramePipeline() = default;
  Status Record(Slot& slot, bool has_ring);
  void WaitForAll();

  const Context* context_ = nullptr;
  Params params_{};
  uint32_t max_points_ = 0, cells_ = 0, pixels_ = 0;
  uint64_t device_bytes_ = 0, submitted_ = 0;
  RecordCounts last_counts_;
  std::unique_ptr<Buffers> buffers_;
  std::unique_ptr<Stages> stages_;
  std::vector<Slot> slots_;
};

}  // namespace lpir::vk
