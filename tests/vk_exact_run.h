// Runs shaders/test_exact.comp (the exact helpers of shaders/common/exact.glsl, one case an
// invocation) on a device, for the tests that compare it with reference_cpu/exact.h.
#pragma once
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <vector>

#include "host/vk/buffer.h"
#include "host/vk/command_buffer.h"
#include "host/vk/device.h"
#include "host/vk/fence.h"
#include "host/vk/kernel.h"
#include "shaders/common/test_exact.h"

namespace lpir::test {
namespace exact_run {
#include "shaders/test_exact.spv.h"  // kTestExactSpv
}  // namespace exact_run

// Runs test_exact.comp over the cases with a workgroup of `local_size` asked for: *out_words gets
// its outputs (kExactOutputs words a case; the buffer is filled with 0xAB bytes before), *used the
// workgroup size the pipeline got.
inline void RunTestExact(const vk::Device& dev, const std::vector<ExactCase>& cases,
                         uint32_t local_size, std::vector<uint32_t>* out_words, uint32_t* used) {
  const uint32_t n = uint32_t(cases.size());
  vk::Result<vk::Buffer> in =
      vk::Buffer::Create(dev, sizeof(ExactCase) * n, vk::MemoryKind::kHostVisible);
  ASSERT_TRUE(in.ok()) << in.message();
  const size_t out_bytes = sizeof(uint32_t) * kExactOutputs * size_t(n);
  vk::Result<vk::Buffer> out = vk::Buffer::Create(dev, out_bytes, vk::MemoryKind::kHostVisible);
  ASSERT_TRUE(out.ok()) << out.message();
  std::memcpy(in->mapped(), cases.data(), sizeof(ExactCase) * n);
  std::memset(out->mapped(), 0xAB, out_bytes);

  vk::PipelineDesc desc;
  desc.name = "test_exact";
  desc.code = vk::SpirvOf(exact_run::kTestExactSpv);
  desc.bindings = {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER};
  desc.push_constant_bytes = sizeof(uint32_t);
  desc.local_size_x = local_size;
  vk::Result<vk::Kernel> kernel = vk::Kernel::Create(dev, desc, {&in.value(), &out.value()});
  ASSERT_TRUE(kernel.ok()) << kernel.message();
  if (used) *used = kernel->pipeline().local_size_x();
  vk::Result<vk::CommandBuffer> cmd = vk::CommandBuffer::Create(dev);
  ASSERT_TRUE(cmd.ok()) << cmd.message();
  vk::Result<vk::Fence> fence = vk::Fence::Create(dev);
  ASSERT_TRUE(fence.ok()) << fence.message();

  ASSERT_TRUE(cmd->Begin().ok());
  vk::Status recorded = kernel->Record(cmd.value(), n, &n);
  ASSERT_TRUE(recorded.ok()) << recorded.message();
  cmd->ComputeToHost();
  ASSERT_TRUE(cmd->End().ok());
  vk::Status ran = cmd->SubmitAndWait(fence.value());
  ASSERT_TRUE(ran.ok()) << ran.message();
  const uint32_t* words = static_cast<const uint32_t*>(out->mapped());
  out_words->assign(words, words + kExactOutputs * size_t(n));
}

}  // namespace lpir::test
