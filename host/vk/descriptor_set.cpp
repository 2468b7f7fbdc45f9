// Descriptor set creation: a pool sized for exactly one set, the set, and its buffer writes.
#include "host/vk/descriptor_set.h"

#include <algorithm>
#include <map>
#include <string>

namespace lpir::vk {

Result<DescriptorSet> DescriptorSet::Create(const Device& device, const ComputePipeline& pipeline,
                                            const std::vector<const Buffer*>& buffers) {
  const std::vector<VkDescriptorType>& types = pipeline.bindings();
  const std::string& what = pipeline.name();
  if (buffers.size() != types.size() ||
      std::any_of(buffers.begin(), buffers.end(), [](const Buffer* b) { return !b; })) {
    Error e;
    e.result = VK_ERROR_INITIALIZATION_FAILED;
    e.message = what + ": " + std::to_string(types.size()) + " buffers to bind, got " +
                std::to_string(buffers.size()) + " (or a null one)";
    return e;
  }

  std::map<VkDescriptorType, uint32_t> counts;
  for (VkDescriptorType type : types) ++counts[type];
  std::vector<VkDescriptorPoolSize> sizes;
  for (const auto& [type, count] : counts) sizes.push_back({type, count});
  VkDescriptorPoolCreateInfo pool_info{};
  pool_info.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO;
  pool_info.maxSets = 1;
  pool_info.poolSizeCount = uint32_t(sizes.size());
  pool_info.pPoolSizes = sizes.data();
  VkDescriptorPool pool = VK_NULL_HANDLE;
  LPIR_VK_CHECK(vkCreateDescriptorPool(device.handle(), &pool_info, nullptr, &pool),
                "vkCreateDescriptorPool", what);
  DescriptorSet set;
  set.pool_ = DeviceHandle<VkDescriptorPool, vkDestroyDescriptorPool>(device.handle(), pool);

  const VkDescriptorSetLayout layout = pipeline.set_layout();
  VkDescriptorSetAllocateInfo alloc{};
  alloc.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO;
  alloc.descriptorPool = pool;
  alloc.descriptorSetCount = 1;
  alloc.pSetLayouts = &layout;
  LPIR_VK_CHECK(vkAllocateDescriptorSets(device.handle(), &alloc, set.set_.out()),
                "vkAllocateDescriptorSets", what);

  std::vector<VkDescriptorBufferInfo> infos(types.size());
  std::vector<VkWriteDescriptorSet> writes(types.size());
  for (size_t i = 0; i < types.size(); ++i) {
    infos[i].buffer = buffers[i]->handle();
    infos[i].offset = 0;
    infos[i].range =
        types[i] == VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER
            ? std::min<VkDeviceSize>(buffers[i]->size(), device.limits().maxUniformBufferRange)
            : VK_WHOLE_SIZE;
    writes[i].sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET;
    writes[i].dstSet = set.set_.get();
    writes[i].dstBinding = uint32_t(i);
    writes[i].descriptorCount = 1;
    writes[i].descriptorType = types[i];
    writes[i].pBufferInfo = &infos[i];
  }
  vkUpdateDescriptorSets(device.handle(), uint32_t(writes.size()), writes.data(), 0, nullptr);
  return set;
}

}  // namespace lpir::vk
