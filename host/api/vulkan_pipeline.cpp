#include "host/api/vulkan_pipeline.h"

#include <stdexcept>
#include <utility>

#include "host/gpu/frame_pipeline.h"

namespace lpir {
namespace {

void ThrowIfError(const vk::Status& status) {
  if (!status.ok()) throw std::runtime_error("Vulkan: " + status.message());
}

}  // namespace

vk::Result<std::unique_ptr<VulkanPipeline>> VulkanPipeline::Create(
    const vk::ContextOptions& context_options, const Params& params, const Tables& tables,
    uint32_t max_points, uint32_t slots, uint32_t batch) {
  std::unique_ptr<VulkanPipeline> made(new VulkanPipeline(batch));
  LPIR_VK_ASSIGN_OR_RETURN(vk::Context context, vk::Context::Create(context_options));
  made->context_ = std::make_unique<vk::Context>(std::move(context));
  LPIR_VK_ASSIGN_OR_RETURN(
      vk::FramePipeline pipeline,
      vk::FramePipeline::Create(*made->context_, params, tables, max_points, slots));
  made->pipeline_ = std::make_unique<vk::FramePipeline>(std::move(pipeline));
  return vk::Result<std::unique_ptr<VulkanPipeline>>(std::move(made));
}

VulkanPipeline::VulkanPipeline(uint32_t batch) : batch_(batch) {}
VulkanPipeline::~VulkanPipeline() = default;

void VulkanPipeline::Stage(uint32_t slot, const Cloud& cloud, const Mount& mount, bool) {
  ThrowIfError(pipeline_->Stage(slot, cloud, mount));  // into the slot's staging buffer
}

void VulkanPipeline::SubmitStaged(uint32_t first, uint32_t count) {
  ThrowIfError(pipeline_->SubmitStaged(first, count));
}

void VulkanPipeline::Collect(uint32_t slot, Frame& out, bool all_buffers, FrameTimes* times) {
  ThrowIfError(pipeline_->Collect(slot, out, all_buffers, times));
}

std::string VulkanPipeline::device_name() const { return context_->device().name(); }

uint64_t VulkanPipeline::device_bytes() const { return pipeline_->device_bytes(); }

bool VulkanPipeline::on_cpu_driver() const {
  return context_->device().properties().deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU;
}

}  // namespace lpir
