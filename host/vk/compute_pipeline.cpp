// Compute pipeline creation: shader module (dropped once the pipeline exists), set layout,
// pipeline layout, pipeline with the workgroup size specialized.
#include "host/vk/compute_pipeline.h"

#include <algorithm>

namespace lpir::vk {

Result<ComputePipeline> ComputePipeline::Create(const Device& device, const PipelineDesc& desc) {
  const VkDevice vk_device = device.handle();
  const std::string& what = desc.name;
  const VkPhysicalDeviceLimits& limits = device.limits();
  if (desc.push_constant_bytes > limits.maxPushConstantsSize || desc.push_constant_bytes % 4) {
    Error e;
    e.result = VK_ERROR_FEATURE_NOT_PRESENT;
    e.message = desc.name + ": " + std::to_string(desc.push_constant_bytes) +
                " bytes of push constants (a multiple of 4, at most " +
                std::to_string(limits.maxPushConstantsSize) + " on " + device.name() + ")";
    return e;
  }
  if (desc.local_size_x == 0 || desc.items == 0) {
    Error e;
    e.result = VK_ERROR_INITIALIZATION_FAILED;
    e.message = desc.name + (desc.items ? ": workgroup size 0" : ": 0 items per invocation");
    return e;
  }
  if (!desc.code.words || desc.code.bytes == 0 || desc.code.bytes % 4) {
    Error e;
    e.result = VK_ERROR_INITIALIZATION_FAILED;
    e.message = desc.name + ": no SPIR-V";
    return e;
  }

  ComputePipeline pipeline;
  pipeline.bindings_ = desc.bindings;
  pipeline.push_constant_bytes_ = desc.push_constant_bytes;
  // The stage's size where the device allows it, else the device's largest (Vulkan guarantees
  // 128); shaders read it as gl_WorkGroupSize and Kernel counts workgroups with it.
  pipeline.local_size_x_ = std::min({desc.local_size_x, limits.maxComputeWorkGroupSize[0],
                                     limits.maxComputeWorkGroupInvocations});
  pipeline.items_ = desc.items;
  pipeline.name_ = desc.name;

  VkShaderModuleCreateInfo module_info{};
  module_info.sType = VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO;
  module_info.codeSize = desc.code.bytes;
  module_info.pCode = desc.code.words;
  VkShaderModule module_handle = VK_NULL_HANDLE;
  LPIR_VK_CHECK(vkCreateShaderModule(vk_device, &module_info, nullptr, &module_handle),
                "vkCreateShaderModule", what);
  const DeviceHandle<VkShaderModule, vkDestroyShaderModule> module(vk_device, module_handle);

  std::vector<VkDescriptorSetLayoutBinding> bindings(desc.bindings.size());
  for (size_t i = 0; i < bindings.size(); ++i) {
    bindings[i].binding = uint32_t(i);
    bindings[i].descriptorType = desc.bindings[i];
    bindings[i].descriptorCount = 1;
    bindings[i].stageFlags = VK_SHADER_STAGE_COMPUTE_BIT;
  }
  VkDescriptorSetLayoutCreateInfo set_info{};
  set_info.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO;
  set_info.bindingCount = uint32_t(bindings.size());
  set_info.pBindings = bindings.data();
  VkDescriptorSetLayout set_layout = VK_NULL_HANDLE;
  LPIR_VK_CHECK(vkCreateDescriptorSetLayout(vk_device, &set_info, nullptr, &set_layout),
                "vkCreateDescriptorSetLayout", what);
  pipeline.set_layout_ =
      DeviceHandle<VkDescriptorSetLayout, vkDestroyDescriptorSetLayout>(vk_device, set_layout);

  VkPushConstantRange push{};
  push.stageFlags = VK_SHADER_STAGE_COMPUTE_BIT;
  push.offset = 0;
  push.size = desc.push_constant_bytes;
  VkPipelineLayoutCreateInfo layout_info{};
  layout_info.sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO;
  layout_info.setLayoutCount = 1;
  layout_info.pSetLayouts = &set_layout;
  layout_info.pushConstantRangeCount = desc.push_constant_bytes ? 1 : 0;
  layout_info.pPushConstantRanges = desc.push_constant_bytes ? &push : nullptr;
  VkPipelineLayout layout = VK_NULL_HANDLE;
  LPIR_VK_CHECK(vkCreatePipelineLayout(vk_device, &layout_info, nullptr, &layout),
                "vkCreatePipelineLayout", what);
  pipeline.layout_ = DeviceHandle<VkPipelineLayout, vkDestroyPipelineLayout>(vk_device, layout);

  const uint32_t constants[3] = {pipeline.local_size_x_, desc.pass, desc.items};
  const VkSpecializationMapEntry entries[3] = {{0, 0, sizeof(uint32_t)},
                                               {1, sizeof(uint32_t), sizeof(uint32_t)},
                                               {2, 2 * sizeof(uint32_t), sizeof(uint32_t)}};
  VkSpecializationInfo specialization{};
  specialization.mapEntryCount = 3;
  specialization.pMapEntries = entries;
  specialization.dataSize = sizeof(constants);
  specialization.pData = constants;

  VkComputePipelineCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO;
  info.stage.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
  info.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
  info.stage.module = module.get();
  info.stage.pName = "main";
  info.stage.pSpecializationInfo = &specialization;
  info.layout = layout;
  VkPipeline handle = VK_NULL_HANDLE;
  LPIR_VK_CHECK(vkCreateComputePipelines(vk_device, VK_NULL_HANDLE, 1, &info, nullptr, &handle),
                "vkCreateComputePipelines", what);
  pipeline.pipeline_ = DeviceHandle<VkPipeline, vkDestroyPipeline>(vk_device, handle);
  return pipeline;
}

}  // namespace lpir::vk
