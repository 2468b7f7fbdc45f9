// FramePipeline: the whole method (every stage of reference_cpu/stage_table.def) on one Vulkan
// device. A frame is one command buffer: the cloud's upload, the stages back to back with
// barriers, the labels' download;
// the number of dispatches is the same for every frame. Every device buffer is
// allocated once, for `max_points` points and the sensor's image and grid; a frame allocates
// nothing. Several frames in flight: each slot owns its command buffer, fence, staging buffers,
// timestamps and frame buffers (the tables and the pipelines are shared), so any frame's buffers
// can be read back and the host reads files and writes labels while the device works. A batch
// records the frames of several slots in one command buffer, interleaved pass by pass
// (CommandBuffer::PlayInterleaved): their dispatches between two barriers run side by side, and
// the batch pays for one frame's barriers.
#pragma once
#include <cstdint>
#include <memory>
#include <vector>

#include "host/gpu/frame_buffers.h"
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
  // Builds every stage over buffers for clouds of up to `max_points` points (at least 1) and
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

  // Copies `cloud` into slot `slot`'s staging buffer (Stage), records its frame and submits it
  // (SubmitStaged of one frame).
  Status Submit(uint32_t slot, const Cloud& cloud);
  // Copies `cloud` into slot `slot`'s staging buffer. The slot must be free: never used, or
  // collected since, and not the first of a batch with frames still to collect (an error,
  // nothing staged, otherwise). The cloud must fit, as the caller checks (Segmenter::Submit
  // does): at most max_points points, a ring field empty or one entry a point. The frame runs
  // with Create's Params seen from `mount` (WithMount), or as they are without one.
  Status Stage(uint32_t slot, const Cloud& cloud, const Mount& mount);
  Status Stage(uint32_t slot, const Cloud& cloud) { return Stage(slot, cloud, MountOf(params_)); }
  // Records the frames staged in slots first .. first + count - 1 into one command buffer
  // (slot first's; interleaved pass by pass when count > 1) and submits it. Each frame is
  // collected from its own slot.
  Status SubmitStaged(uint32_t first, uint32_t count);

  // Waits for slot `slot`'s frame and frees the slot. Fills out.n, out.label_why (downloaded)
  // and out.label, out.why (unpacked from it); with `all_buffers`, every other buffer of the
  // frame too. `times` (optional) gets the frame's GPU times (timestamps; in a batch, each stamp
  // is written when the batch's interleaved commands reach it, so stages overlap frames).
  Status Collect(uint32_t slot, Frame& out, bool all_buffers = false, FrameTimes* times = nullptr);

  uint32_t slots() const { return uint32_t(slots_.size()); }
  uint32_t max_points() const { return max_points_; }
  // Vulkan memory allocated, in bytes: the device buffers and the slots' staging buffers (all
  // made by Create: constant for the pipeline's life).
  uint64_t device_bytes() const { return device_bytes_; }
  // The commands of the latest Submit (one frame, or a batch), counted at record time.
  const RecordCounts& last_counts() const { return last_counts_; }

  ~FramePipeline();  // waits for the frames in flight
  FramePipeline(FramePipeline&&) noexcept;
  FramePipeline& operator=(FramePipeline&&) noexcept;

 private:
  struct Stages;  // every stage bound to one slot's buffers
  struct Slot {
    CommandBuffer cmd;
    Fence fence;
    Buffer upload;    // host-visible: points (16 bytes each), then rings (4 bytes each)
    Buffer download;  // host-visible: label_why bytes (four points a word)
    std::vector<TimestampQueries> queries;  // one pool of kQueries, or none without timestamps
    std::unique_ptr<FrameBuffers> buffers;  // at a stable address: the stages keep pointers
    std::unique_ptr<Stages> stages;         // after buffers: destroyed first
    bool busy = false, staged = false, has_ring = false;
    uint32_t n = 0;
    Mount mount{};      // the staged frame's
    uint32_t lead = 0;  // the slot whose command buffer and fence carry this frame
    // As a lead: its fence signals a submission not yet waited for; frames of that submission
    // not yet collected (the slot takes no new frame before they are).
    bool fence_pending = false;
    uint32_t frames = 0;
  };
  // Timestamps: start, after the upload, after each stage, after the download.
  static constexpr uint32_t kQueries = kStageCount + 3;

  FramePipeline() = default;
  // Create's steps, each on a pipeline whose context_, params_ and sizes are set: a
  // device-local (or `kind`) buffer counted in device_bytes_; the tables' buffers, uploaded;
  // one slot more; the check of the largest frame's dispatches.
  Status Allocate(Buffer& buffer, VkDeviceSize bytes, MemoryKind kind = MemoryKind::kDeviceLocal);
  Status MakeTables(const Tables& tables);
  Status AddSlot();
  Status RecordLargestFrame();
  static Result<std::unique_ptr<Stages>> MakeStages(const Device& device, const FrameBuffers& b);
  template <typename Fn>
  static Status ForEachStage(const Stages& s, Fn&& fn);
  // Records slot's frame (slot.n points, slot.has_ring, slot.mount) into cmd, begun by the
  // caller.
  Status RecordFrame(Slot& slot, CommandBuffer& cmd);
  // Collect's parts: the slot's GPU times, and every buffer of its frame.
  Status ReadTimes(const Slot& slot, FrameTimes& times) const;
  Status ReadBuffers(const Slot& slot, Frame& out) const;
  void WaitForAll();

  const Context* context_ = nullptr;
  Params params_{};
  uint32_t max_points_ = 0, cells_ = 0, pixels_ = 0;
  uint64_t device_bytes_ = 0;
  RecordCounts last_counts_;
  std::unique_ptr<TableBuffers> tables_;
  std::vector<Slot> slots_;  // after tables_: destroyed first
};

}  // namespace lpir::vk
