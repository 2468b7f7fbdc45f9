// CommandBuffer: one primary command buffer in a pool of its own on the device's compute queue,
// with the few commands the stages record (bind, push, dispatch, barriers, copies, timestamps),
// so stage code never touches raw Vulkan calls. Re-recorded each frame: Begin resets it.
#pragma once
#include <vulkan/vulkan.h>

#include <cstdint>
#include <functional>
#include <utility>
#include <vector>

#include "host/vk/buffer.h"
#include "host/vk/compute_pipeline.h"
#include "host/vk/descriptor_set.h"
#include "host/vk/device.h"
#include "host/vk/fence.h"
#include "host/vk/handle.h"
#include "host/vk/result.h"
#include "host/vk/timestamp_queries.h"

namespace lpir::vk {

// What one recording holds, counted as the commands are recorded (Begin resets it). Indirect
// dispatches read their workgroup counts on the GPU, unknown at record time: they are counted in
// `dispatches` and `indirect_dispatches`, and their workgroups are not in `workgroups`.
struct RecordCounts {
  uint32_t dispatches = 0;           // direct and indirect
  uint32_t indirect_dispatches = 0;  // of which indirect
  uint32_t barriers = 0;             // vkCmdPipelineBarrier calls
  uint64_t workgroups = 0;           // x * y * z summed over the direct dispatches
  uint64_t upload_bytes = 0;         // host -> device: copies from kHostVisible into kDeviceLocal
                                     // buffers, and UpdateBuffer's inline data
  uint64_t download_bytes = 0;       // device -> host: copies from kDeviceLocal into kHostVisible

  RecordCounts& operator+=(const RecordCounts& o) {
    dispatches += o.dispatches, indirect_dispatches += o.indirect_dispatches;
    barriers += o.barriers, workgroups += o.workgroups;
    upload_bytes += o.upload_bytes, download_bytes += o.download_bytes;
    return *this;
  }
};

// One recorded command, kept on a tape instead of in the command buffer: what it records, what it
// counts, and for a barrier its scopes (Barrier's arguments; all zero for every other command).
struct Command {
  Command(std::function<void(VkCommandBuffer)> r) : record(std::move(r)) {}  // NOLINT: implicit
  std::function<void(VkCommandBuffer)> record;
  RecordCounts counts{};
  struct Scopes {
    VkPipelineStageFlags src_stage = 0;
    VkAccessFlags src_access = 0;
    VkPipelineStageFlags dst_stage = 0;
    VkAccessFlags dst_access = 0;
    bool operator==(const Scopes& o) const {
      return src_stage == o.src_stage && src_access == o.src_access && dst_stage == o.dst_stage &&
             dst_access == o.dst_access;
    }
  } barrier;
};
using Tape = std::vector<Command>;

class CommandBuffer {
 public:
  static Result<CommandBuffer> Create(const Device& device);

  CommandBuffer(CommandBuffer&&) noexcept = default;
  CommandBuffer& operator=(CommandBuffer&&) noexcept = default;

  Status Begin();  // resets; one-time submit
  Status End();
  // Submits to the device's queue; `fence` signals when the work is done.
  Status Submit(const Fence& fence) const;
  // Submit, then wait for `fence` and reset it.
  Status SubmitAndWait(Fence& fence) const;

  void BindPipeline(const ComputePipeline& pipeline);
  void BindDescriptorSet(const ComputePipeline& pipeline, const DescriptorSet& set);
  void PushConstants(const ComputePipeline& pipeline, const void* data, uint32_t bytes);
  void Dispatch(uint32_t groups_x, uint32_t groups_y = 1, uint32_t groups_z = 1);
  // Workgroup counts read on the GPU from three uint32 at `offset` in `args` (x = 0: nothing runs).
  void DispatchIndirect(const Buffer& args, VkDeviceSize offset);

  // A global memory barrier (every buffer: the stages share big buffers, so there is nothing to
  // gain from per-buffer ranges).
  void Barrier(VkPipelineStageFlags src_stage, VkAccessFlags src_access,
               VkPipelineStageFlags dst_stage, VkAccessFlags dst_access);
  void ComputeToCompute();   // a dispatch's writes -> the next dispatch's reads and writes
  void ComputeToIndirect();  // ComputeToCompute, and the writes -> indirect dispatch counts
  void ComputeToTransfer();  // a dispatch's writes -> copies from them; reads -> copies over them
  void TransferToCompute();  // copies and fills -> dispatches
  void ComputeToHost();      // a dispatch's writes -> host reads of a mapped buffer
  void TransferToHost();     // copies -> host reads of a mapped buffer

  void CopyBuffer(const Buffer& src, const Buffer& dst, VkDeviceSize bytes,
                  VkDeviceSize src_offset = 0, VkDeviceSize dst_offset = 0);
  void FillBuffer(const Buffer& dst, uint32_t value);  // the whole buffer
  // Writes `bytes` (a multiple of 4, at most 65536) from host memory into `dst`, in order with
  // the commands around it (vkCmdUpdateBuffer: a transfer write).
  void UpdateBuffer(const Buffer& dst, const void* data, VkDeviceSize bytes);

  void ResetQueries(const TimestampQueries& queries);
  // Timestamp `index`, written once every earlier command has completed.
  void WriteTimestamp(const TimestampQueries& queries, uint32_t index);

  // Batches: between BeginTape and EndTape every command above goes on `tape` (cleared first)
  // instead of into the command buffer. PlayInterleaved records several tapes of the same
  // barrier sequence (frames of one batch: the same passes, other buffers) as one: the commands
  // of every tape up to its first barrier, tape after tape, then that barrier once, and so on;
  // so the B frames' dispatches between two barriers run side by side, and a batch costs the
  // barriers of one frame. An error (nothing recorded) when the tapes' barriers differ.
  void BeginTape(Tape* tape);
  void EndTape();
  Status PlayInterleaved(const std::vector<Tape>& tapes);

  VkCommandBuffer handle() const { return cmd_.get(); }
  // The commands recorded since the last Begin.
  const RecordCounts& counts() const { return counts_; }

 private:
  CommandBuffer() = default;

  DeviceHandle<VkCommandPool, vkDestroyCommandPool> pool_;  // frees the command buffer with it
  ResetOnMove<VkCommandBuffer> cmd_;
  ResetOnMove<VkQueue> queue_;
  RecordCounts counts_;
  Tape* tape_ = nullptr;  // where commands go between BeginTape and EndTape

  void Emit(Command command);         // onto the tape, or recorded and counted
  void Play(const Command& command);  // recorded and counted
};

}  // namespace lpir::vk
