// Command pool and buffer creation, recording helpers, submission.
#include "host/vk/command_buffer.h"

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

void CommandBuffer::BindPipeline(const ComputePipeline& pipeline) {
  vkCmdBindPipeline(cmd_.get(), VK_PIPELINE_BIND_POINT_COMPUTE, pipeline.handle());
}

void CommandBuffer::BindDescriptorSet(const ComputePipeline& pipeline, const DescriptorSet& set) {
  const VkDescriptorSet handle = set.handle();
  vkCmdBindDescriptorSets(cmd_.get(), VK_PIPELINE_BIND_POINT_COMPUTE, pipeline.layout(), 0, 1,
                          &handle, 0, nullptr);
}

void CommandBuffer::PushConstants(const ComputePipeline& pipeline, const void* data,
                                  uint32_t bytes) {
  vkCmdPushConstants(cmd_.get(), pipeline.layout(), VK_SHADER_STAGE_COMPUTE_BIT, 0, bytes, data);
}

void CommandBuffer::Dispatch(uint32_t groups_x, uint32_t groups_y, uint32_t groups_z) {
  vkCmdDispatch(cmd_.get(), groups_x, groups_y, groups_z);
  ++counts_.dispatches;
  counts_.workgroups += uint64_t(groups_x) * groups_y * groups_z;
}

void CommandBuffer::DispatchIndirect(const Buffer& args, VkDeviceSize offset) {
  vkCmdDispatchIndirect(cmd_.get(), args.handle(), offset);
  ++counts_.dispatches;
  ++counts_.indirect_dispatches;
}

void CommandBuffer::Barrier(VkPipelineStageFlags src_stage, VkAccessFlags src_access,
                            VkPipelineStageFlags dst_stage, VkAccessFlags dst_access) {
  VkMemoryBarrier barrier{};
  barrier.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER;
  barrier.srcAccessMask = src_access;
  barrier.dstAccessMask = dst_access;
  vkCmdPipelineBarrier(cmd_.get(), src_stage, dst_stage, 0, 1, &barrier, 0, nullptr, 0, nullptr);
  ++counts_.barriers;
}

void CommandBuffer::ComputeToCompute() {
  Barrier(VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
          VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
          VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT);
}

void CommandBuffer::ComputeToIndirect() {
  Barrier(VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
          VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_DRAW_INDIRECT_BIT,
          VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT |
              VK_ACCESS_INDIRECT_COMMAND_READ_BIT);
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
  const VkBufferCopy region{src_offset, dst_offset, bytes};
  vkCmdCopyBuffer(cmd_.get(), src.handle(), dst.handle(), 1, &region);
  const bool src_host = src.kind() == MemoryKind::kHostVisible;
  const bool dst_host = dst.kind() == MemoryKind::kHostVisible;
  if (src_host && !dst_host) counts_.upload_bytes += bytes;
  if (!src_host && dst_host) counts_.download_bytes += bytes;
}

void CommandBuffer::FillBuffer(const Buffer& dst, uint32_t value) {
  vkCmdFillBuffer(cmd_.get(), dst.handle(), 0, VK_WHOLE_SIZE, value);
}

void CommandBuffer::UpdateBuffer(const Buffer& dst, const void* data, VkDeviceSize bytes) {
  vkCmdUpdateBuffer(cmd_.get(), dst.handle(), 0, bytes, data);
  counts_.upload_bytes += bytes;
}

void CommandBuffer::ResetQueries(const TimestampQueries& queries) {
  vkCmdResetQueryPool(cmd_.get(), queries.handle(), 0, queries.count());
}

void CommandBuffer::WriteTimestamp(const TimestampQueries& queries, uint32_t index) {
  vkCmdWriteTimestamp(cmd_.get(), VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, queries.handle(), index);
}

}  // namespace lpir::vk
