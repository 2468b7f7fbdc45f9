// Kernel: the generic dispatcher. One compute shader ready to run over a 1-D range: a pipeline
// for each of its desc.passes passes (compute_pipeline.h: the pass is specialization constant 1)
// and one descriptor set bound to buffers fixed at creation (allocated once for the largest
// cloud, docs/spec.md, Performance shape), shared by the passes (their set layouts are identical).
// Recording binds, pushes the constants and dispatches ceil(invocations / local size) workgroups;
// the shader skips invocations past its count. The kernel's shape (shape.h, read at creation) sets
// the items per invocation of its chunked passes (specialization constant 2): desc.cpu_items in
// the CPU shape, 1 in the GPU shape; the stage sizes those passes with Chunks(). Kernels made on
// one device from the same description share their pipelines (built once, freed with the last
// kernel that uses them), so each frame slot binds its own buffers without building again.
#pragma once
#include <cstdint>
#include <memory>
#include <vector>

#include "host/vk/buffer.h"
#include "host/vk/command_buffer.h"
#include "host/vk/compute_pipeline.h"
#include "host/vk/descriptor_set.h"
#include "host/vk/device.h"
#include "host/vk/result.h"
#include "host/vk/shape.h"

namespace lpir::vk {

class Kernel {
 public:
  static Result<Kernel> Create(const Device& device, const PipelineDesc& desc,
                               const std::vector<const Buffer*>& buffers);

  // `push` holds desc.push_constant_bytes bytes (nullptr when none). No barrier is recorded.
  // An error when the range needs more workgroups than the device dispatches along x.
  Status Record(CommandBuffer& cmd, uint32_t invocations, const void* push,
                uint32_t pass = 0) const;

  // An error when `invocations` need more workgroups than the device dispatches along x.
  Status CheckGroups(uint64_t invocations) const;

  // The same with the workgroup counts read on the GPU from `args` at `offset` (see
  // CommandBuffer::DispatchIndirect): the shader decides whether its successor runs.
  void RecordIndirect(CommandBuffer& cmd, const Buffer& args, VkDeviceSize offset, const void* push,
                      uint32_t pass = 0) const;

  Shape shape() const { return shape_; }
  // Items (points or pixels) per invocation of the chunked passes.
  uint32_t items() const { return pipelines_->front().items(); }
  // Invocations of a chunked pass over `count` items: ceil(count / items()).
  uint32_t Chunks(uint32_t count) const { return count / items() + (count % items() != 0); }

  // `pass` < desc.passes.
  const ComputePipeline& pipeline(uint32_t pass = 0) const { return (*pipelines_)[pass]; }

  using Pipelines = std::vector<ComputePipeline>;  // pass k: element k

 private:
  Kernel(std::shared_ptr<const Pipelines> pipelines, DescriptorSet set, uint32_t max_groups,
         Shape shape)
      : pipelines_(std::move(pipelines)),
        set_(std::move(set)),
        max_groups_(max_groups),
        shape_(shape) {}
  void Bind(CommandBuffer& cmd, const void* push, uint32_t pass) const;

  std::shared_ptr<const Pipelines> pipelines_;
  DescriptorSet set_;
  uint32_t max_groups_ = 0;
  Shape shape_ = Shape::kGpu;
};

}  // namespace lpir::vk
