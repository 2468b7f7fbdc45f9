// fuse, on Vulkan: the kernel's bindings and its recording.
#include "host/gpu/fuse.h"

#include <cstdint>

namespace lpir::vk {
namespace {
#include "shaders/fuse.spv.h"  // kFuseSpv, compiled from shaders/fuse.comp at build time
}  // namespace

Result<FuseStage> FuseStage::Create(const Device& device, const FuseBuffers& b) {
  PipelineDesc desc;
  desc.name = "fuse";
  desc.code = SpirvOf(kFuseSpv);
  desc.bindings = {VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
                   VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
                   VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
                   VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER};
  desc.push_constant_bytes = sizeof(uint32_t);
  desc.local_size_x = kLocalSize;
  desc.passes = 2;
  LPIR_VK_ASSIGN_OR_RETURN(Kernel kernel,
                           Kernel::Create(device, desc,
                                          {b.params, b.pixel_class, b.pixel_point, b.coarse,
                                           b.pixel_filled, b.f_range, b.f_height, b.pixel_fused}));
  return FuseStage(std::move(kernel));
}

Status FuseStage::Record(CommandBuffer& cmd, uint32_t width, uint32_t beams) const {
  const uint32_t pixels = width * beams;
  if (width % 4 == 0) return kernel_.Record(cmd, pixels / 4, &pixels, 1);  // quads
  return kernel_.Record(cmd, pixels, &pixels, 0);
}

}  // namespace lpir::vk
