// ComputePipeline: one compute shader from SPIR-V embedded at build time (<build>/shaders/
// <stage>.spv.h, k<Stage>Spv), with its descriptor set layout (set 0: binding i of the type
// bindings[i], storage or uniform buffers), an optional push-constant block and three
// specialization constants: 0 the workgroup size (`layout(local_size_x_id = 0) in;`), 1 the pass
// of a stage of several passes (`layout(constant_id = 1) const uint kPass = 0u;`), 2 the points
// or pixels per invocation of a stage's chunked passes (`layout(constant_id = 2) const uint
// kItems = 1u;`, chosen by the device's shape: shape.h); a shader ignores those it does not
// declare. One pipeline per pass: a CPU driver such as lavapipe runs every branch of a shader
// under a lane mask (an `if` skips no code), so a pass chosen at run time would pay for the code
// of all the others.
#pragma once
#include <vulkan/vulkan.h>

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "host/vk/device.h"
#include "host/vk/handle.h"
#include "host/vk/result.h"

namespace lpir::vk {

struct Spirv {
  const uint32_t* words = nullptr;
  size_t bytes = 0;
};
template <size_t N>
Spirv SpirvOf(const uint32_t (&words)[N]) {
  return Spirv{words, sizeof(words)};
}

struct PipelineDesc {
  std::string name;  // the stage's name, for error messages
  Spirv code;
  std::vector<VkDescriptorType> bindings;  // set 0, binding i
  uint32_t push_constant_bytes = 0;        // 0: none (at most 128, the guaranteed minimum)
  uint32_t local_size_x = 64;              // specialization constant 0 (at most the device's)
  uint32_t pass = 0;                       // specialization constant 1 (multi-pass stages)
  uint32_t passes = 1;                     // Kernel: one pipeline for each pass 0 .. passes - 1
  uint32_t items = 1;                      // specialization constant 2 (chunked passes)
  uint32_t cpu_items = 1;                  // Kernel: `items` in the CPU shape (the GPU's is 1)
};

class ComputePipeline {
 public:
  static Result<ComputePipeline> Create(const Device& device, const PipelineDesc& desc);

  ComputePipeline(ComputePipeline&&) noexcept = default;
  ComputePipeline& operator=(ComputePipeline&&) noexcept = default;

  VkPipeline handle() const { return pipeline_.get(); }
  VkPipelineLayout layout() const { return layout_.get(); }
  VkDescriptorSetLayout set_layout() const { return set_layout_.get(); }
  const std::vector<VkDescriptorType>& bindings() const { return bindings_; }
  uint32_t push_constant_bytes() const { return push_constant_bytes_; }
  uint32_t local_size_x() const { return local_size_x_; }
  uint32_t items() const { return items_; }
  const std::string& name() const { return name_; }

 private:
  ComputePipeline() = default;

  DeviceHandle<VkDescriptorSetLayout, vkDestroyDescriptorSetLayout> set_layout_;
  DeviceHandle<VkPipelineLayout, vkDestroyPipelineLayout> layout_;
  DeviceHandle<VkPipeline, vkDestroyPipeline> pipeline_;
  std::vector<VkDescriptorType> bindings_;
  uint32_t push_constant_bytes_ = 0;
  uint32_t local_size_x_ = 0;
  uint32_t items_ = 1;
  std::string name_;
};

}  // namespace lpir::vk
