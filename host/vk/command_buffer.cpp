// Command pool and buffer creation, recording helpers, submission.
#include "host/vk/command_buffer.h"

#include <utility>
#include <vector>

namespace lpir::vk {

Result<CommandBuffer> CommandBuffer::Create(const Device& device) {
  VkCommandPoolCreateInfo pool_info{};
  pool_info.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO;
  pool_info.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
  pool_info.queueFamilyIndex = device.queue_family();
  VkCommandPool pool = VK_NULL_HANDLE;
  LPIR_VK_CHECK(vkCreateCommandPool(device.handle(), &pool_info, nullptr, &pool),
                "vkCreateCommandPool", "");
  CommandBuffer cmd;
  cmd.pool_ = DeviceHandle<VkCommandPool, vkDestroyCommandPool>(device.handle(), pool);
  cmd.queue_ = device.queue();

  VkCommandBufferAllocateInfo alloc{};
  alloc.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO;
  alloc.commandPool = pool;
  alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  alloc.commandBufferCount = 1;
  LPIR_VK_CHECK(vkAllocateCommandBuffers(device.handle(), &alloc, cmd.cmd_.out()),
                "vkAllocateCommandBuffers", "");
  return cmd;
}

Status CommandBuffer::Begin() {
  counts_ = RecordCounts{};
  LPIR_VK_CHECK(vkResetCommandBuffer(cmd_.get(), 0), "vkResetCommandBuffer", "");
  VkCommandBufferBeginInfo info{};
  info.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO;
  info.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  LPIR_VK_CHECK(vkBeginCommandBuffer(cmd_.get(), &info), "vkBeginCommandBuffer", "");
  return Status();
}

Status CommandBuffer::End() {
  LPIR_VK_CHECK(vkEndCommandBuffer(cmd_.get()), "vkEndCommandBuffer", "");
  return Status();
}

Status CommandBuffer::Submit(const Fence& fence) const {
  const VkCommandBuffer cmd = cmd_.get();
  VkSubmitInfo info{};
  info.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO;
  info.commandBufferCount = 1;
  info.pCommandBuffers = &cmd;
  LPIR_VK_CHECK(vkQueueSubmit(queue_.get(), 1, &info, fence.handle()), "vkQueueSubmit", "");
  return Status();
}

Status CommandBuffer::SubmitAndWait(Fence& fence) const {
  LPIR_VK_RETURN_IF_ERROR(Submit(fence));
  return fence.WaitAndReset();
}

void CommandBuffer::Emit(Command command) {
  if (tape_) {
    tape_->push_back(std::move(command));
    return;
  }
  Play(command);
}

void CommandBuffer::Play(const Command& command) {
  command.record(cmd_.get());
  counts_ += command.counts;
}

void CommandBuffer::BeginTape(Tape* tape) {
  tape->clear();
  tape_ = tape;
}

void CommandBuffer::EndTape() { tape_ = nullptr; }

Status CommandBuffer::PlayInterleaved(const std::vector<Tape>& tapes) {
  if (tapes.empty()) return Status();
  auto barriers = [](const Tape& tape) {
    std::vector<const Command*> out;
    for (const Command& c : tape)
      if (c.counts.barriers) out.push_back(&c);
    return out;
  };
  const std::vector<const Command*> first = barriers(tapes.front());
  for (const Tape& tape : tapes) {
    const std::vector<const Command*> other = barriers(tape);
    bool same = other.size() == first.size();
    for (size_t k = 0; same && k < first.size(); ++k) same = other[k]->barrier == first[k]->barrier;
    if (!same) {
      Error e;
      e.result = VK_ERROR_UNKNOWN;
      e.message = "interleaved frames record different barriers";
      return e;
    }
  }
  std::vector<size_t> at(tapes.size(), 0);  // each tape's next command
  for (size_t k = 0; k <= first.size(); ++k) {
    for (size_t t = 0; t < tapes.size(); ++t)
      for (; at[t] < tapes[t].size() && !tapes[t][at[t]].counts.barriers; ++at[t])
        Play(tapes[t][at[t]]);
    if (k == first.size()) break;
    Play(*first[k]);
    for (size_t& a : at) ++a;  // past barrier k
  }
  return Status();
}

void CommandBuffer::BindPipeline(const ComputePipeline& pipeline) {
  const VkPipeline handle = pipeline.handle();
  Emit({[=](VkCommandBuffer c) { vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_COMPUTE, handle); }});
}

void CommandBuffer::BindDescriptorSet(const ComputePipeline& pipeline, const DescriptorSet& set) {
  const VkDescriptorSet handle = set.handle();
  const VkPipelineLayout layout = pipeline.layout();
  Emit({[=](VkCommandBuffer c) {
    vkCmdBindDescriptorSets(c, VK_PIPELINE_BIND_POINT_COMPUTE, layout, 0, 1, &handle, 0, nullptr);
  }});
}

void CommandBuffer::PushConstants(const ComputePipeline& pipeline, const void* data,
                                  uint32_t bytes) {
  const VkPipelineLayout layout = pipeline.layout();
  const auto* p = static_cast<const uint8_t*>(data);
  std::vector<uint8_t> copy(p, p + bytes);  // vkCmdPushConstants copies at record time
  Emit({[=](VkCommandBuffer c) {
    vkCmdPushConstants(c, layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, bytes, copy.data());
  }});
}

void CommandBuffer::Dispatch(uint32_t groups_x, uint32_t groups_y, uint32_t groups_z) {
  Command command{[=](VkCommandBuffer c) { vkCmdDispatch(c, groups_x, groups_y, groups_z); }};
  command.counts.dispatches = 1;
  command.counts.workgroups = uint64_t(groups_x) * groups_y * groups_z;
  Emit(std::move(command));
}

void CommandBuffer::DispatchIndirect(const Buffer& args, VkDeviceSize offset) {
  const VkBuffer handle = args.handle();
  Command command{[=](VkCommandBuffer c) { vkCmdDispatchIndirect(c, handle, offset); }};
  command.counts.dispatches = 1;
  command.counts.indirect_dispatches = 1;
  Emit(std::move(command));
}

void CommandBuffer::Barrier(VkPipelineStageFlags src_stage, VkAccessFlags src_access,
                            VkPipelineStageFlags dst_stage, VkAccessFlags dst_access) {
  Command command{[=](VkCommandBuffer c) {
    VkMemoryBarrier barrier{};
    barrier.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER;
    barrier.srcAccessMask = src_access;
    barrier.dstAccessMask = dst_access;
    vkCmdPipelineBarrier(c, src_stage, dst_stage, 0, 1, &barrier, 0, nullptr, 0, nullptr);
  }};
  command.counts.barriers = 1;
  command.barrier = {src_stage, src_access, dst_stage, dst_access};
  Emit(std::move(command));
}

void CommandBuffer::ComputeToCompute() {
  Barrier(VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
          VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
          VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT);
}

void CommandBuffer::ComputeToIndirect() {
  Barrier(
      VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
      VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_DRAW_INDIRECT_BIT,
      VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_INDIRECT_COMMAND_READ_BIT);
}

void CommandBuffer::ComputeToTransfer() {
  Barrier(VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
          VK_PIPELINE_STAGE_TRANSFER_BIT,
          VK_ACCESS_TRANSFER_READ_BIT | VK_ACCESS_TRANSFER_WRITE_BIT);
}

void CommandBuffer::TransferToCompute() {
  Barrier(VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
          VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
          VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_UNIFORM_READ_BIT);
}

void CommandBuffer::ComputeToHost() {
  Barrier(VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
          VK_PIPELINE_STAGE_HOST_BIT, VK_ACCESS_HOST_READ_BIT);
}

void CommandBuffer::TransferToHost() {
  Barrier(VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_HOST_BIT,
          VK_ACCESS_HOST_READ_BIT);
}

void CommandBuffer::CopyBuffer(const Buffer& src, const Buffer& dst, VkDeviceSize bytes,
                               VkDeviceSize src_offset, VkDeviceSize dst_offset) {
  const VkBuffer from = src.handle(), to = dst.handle();
  Command command{[=](VkCommandBuffer c) {
    const VkBufferCopy region{src_offset, dst_offset, bytes};
    vkCmdCopyBuffer(c, from, to, 1, &region);
  }};
  const bool src_host = src.kind() == MemoryKind::kHostVisible;
  const bool dst_host = dst.kind() == MemoryKind::kHostVisible;
  if (src_host && !dst_host) command.counts.upload_bytes = bytes;
  if (!src_host && dst_host) command.counts.download_bytes = bytes;
  Emit(std::move(command));
}

void CommandBuffer::FillBuffer(const Buffer& dst, uint32_t value) {
  const VkBuffer to = dst.handle();
  Emit({[=](VkCommandBuffer c) { vkCmdFillBuffer(c, to, 0, VK_WHOLE_SIZE, value); }});
}

void CommandBuffer::UpdateBuffer(const Buffer& dst, const void* data, VkDeviceSize bytes) {
  const VkBuffer to = dst.handle();
  const auto* p = static_cast<const uint8_t*>(data);
  std::vector<uint8_t> copy(p, p + bytes);  // vkCmdUpdateBuffer copies at record time
  Command command{[=](VkCommandBuffer c) { vkCmdUpdateBuffer(c, to, 0, bytes, copy.data()); }};
  command.counts.upload_bytes = bytes;
  Emit(std::move(command));
}

void CommandBuffer::ResetQueries(const TimestampQueries& queries) {
  const VkQueryPool pool = queries.handle();
  const uint32_t count = queries.count();
  Emit({[=](VkCommandBuffer c) { vkCmdResetQueryPool(c, pool, 0, count); }});
}

void CommandBuffer::WriteTimestamp(const TimestampQueries& queries, uint32_t index) {
  const VkQueryPool pool = queries.handle();
  Emit({[=](VkCommandBuffer c) {
    vkCmdWriteTimestamp(c, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, pool, index);
  }});
}

}  // namespace lpir::vk
