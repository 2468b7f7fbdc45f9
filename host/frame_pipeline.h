// FramePipeline: the whole method (stages 1-9) on one Vulkan device. A frame is one command
// buffer: the cloud's upload, the nine stages back to back with barriers, the labels' download;
// the number of dispatches is the same for every frame. Every device buffer is
// allocated once, for `max_points` points and the sensor's image and grid; a frame allocates
// nothing. Several frames in flight: each slot owns its command buffer, fence, staging buffers
// and timestamps, and the slots share the device buffers, ordered by a barrier at the head of
// every frame (one queue runs the frames in submission order, each overlapping the host's work
// on the others: reading files, writing labels).
#pragma once
#include <cstdint>
#include <memory>
#include <vector>

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

// What FramePipeline::Create checks its buffers and dispatches against, before allocating.
struct DeviceLimits {
  uint64_t max_storage_buffer_range = 0;  // VkPhysicalDeviceLimits::maxStorageBufferRange
  uint64_t max_uniform_buffer_range = 0;  // VkPhysicalDeviceLimits::maxUniformBufferRange
  uint64_t device_local_heap = 0;         // bytes of the heap device-local buffers come from
  bool staging_in_device_heap = false;    // the host-visible staging buffers come from it too
  // The device's own. maxComputeWorkGroupCount[0] is not here: every kernel checks its
  // dispatches against the device's (Kernel::CheckGroups), and Create records a frame of
  // max_points points to see them.
  static DeviceLimits Of(const Device& device);
};

class FramePipeline {
 public:
  // Builds the nine stages over buffers for clouds of up to `max_points` points (at least 1) and
  // uploads the tables. `slots`: frames that may be in flight at once (at least 1). Before
  // allocating, checks every storage buffer against maxStorageBufferRange, Params against
  // maxUniformBufferRange and the sum of the buffers against the device-local heap (`limits`:
  // nullptr for the device's own, DeviceLimits::Of); after building the stages, records a frame
  // of max_points points, so that a dispatch over more workgroups than
  // maxComputeWorkGroupCount[0] is an error here and not at a later Submit. Each error names the
  // limit, what needs more and the device's value: "max_points 100000000 needs a 1.6 GB points
  // buffer; this device's maxStorageBufferRange is 134217728".
  static Result<FramePipeline> Create(const Context& context, const Params& params,
                                      const Tables& tables, uint32_t max_points, uint32_t slots,
                                      const DeviceLimits* limits = nullptr);

  // Copies `cloud` into slot `slot`'s staging buffer, records its frame and submits it. The slot
  // must be free: never submitted, or collected since. An error (nothing submitted) for a cloud
  // over max_points or with a ring field of another length.
  Status Submit(uint32_t slot, const Cloud& cloud);

  // Waits for slot `slot`'s frame and frees the slot. Fills out.n, out.label_why (downloaded)
  // and out.label, out.why (unpacked from it); with `all_buffers`, every other buffer of the
  // frame too (read back after the wait, so only for the frame submitted last: the slots share
  // the device buffers; asked of an earlier frame, an error that leaves the slot as it was).
  // `times` (optional) gets the frame's GPU times (timestamps).
  Status Collect(uint32_t slot, Frame& out, bool all_buffers = false, FrameTimes* times = nullptr);

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
    Buffer download;  // host-visible: label_why bytes (four points a word)
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
