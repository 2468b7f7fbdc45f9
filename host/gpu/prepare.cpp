// prepare, on Vulkan: the kernel's bindings and its recording.
#include "host/gpu/prepare.h"

#include <cstdint>

namespace lpir::vk {
namespace {
#include "shaders/prepare.spv.h"  // kPrepareSpv, compiled from shaders/prepare.comp at build time
}  // namespace

Result<PrepareStage> PrepareStage::Create(const Device& device, const PrepareBuffers& b) {
  PipelineDesc desc;
  desc.name = "prepare";
  desc.code = SpirvOf(kPrepareSpv);
  desc.bindings = {VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
                   VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
                   VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER};
  desc.push_constant_bytes = sizeof(uint32_t);
  desc.local_size_x = kLocalSize;
  LPIR_VK_ASSIGN_OR_RETURN(
      Kernel kernel,
      Kernel::Create(device, desc, {b.params, b.points, b.ring, b.flags, b.zt, b.r2}));
  return PrepareStage(std::move(kernel));
}

Status PrepareStage::Record(CommandBuffer& cmd, uint32_t n) const {
  return kernel_.Record(cmd, n, &n);
}

}  // namespace lpir::vk
