// classify_pixels, on Vulkan: the kernel's bindings and its recording.
#include "host/gpu/classify_pixels.h"

#include <cstdint>

namespace lpir::vk {
namespace {
#include "shaders/classify_pixels.spv.h"  // kClassifyPixelsSpv, from shaders/classify_pixels.comp
}  // namespace

Result<ClassifyPixelsStage> ClassifyPixelsStage::Create(const Device& device,
                                                        const ClassifyPixelsBuffers& b) {
  PipelineDesc desc;
  desc.name = "classify_pixels";
  desc.code = SpirvOf(kClassifyPixelsSpv);
  desc.bindings.assign(7, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER);
  desc.bindings[0] = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
  desc.push_constant_bytes = sizeof(uint32_t);
  desc.local_size_x = kLocalSize;
  desc.passes = 2;
  LPIR_VK_ASSIGN_OR_RETURN(
      Kernel kernel, Kernel::Create(device, desc,
                                    {b.params, b.pixel_filled, b.f_edge_l, b.f_edge_r, b.f_slope,
                                     b.f_varz, b.pixel_class}));
  return ClassifyPixelsStage(std::move(kernel));
}

Status ClassifyPixelsStage::Record(CommandBuffer& cmd, uint32_t pixels) const {
  LPIR_VK_RETURN_IF_ERROR(kernel_.Record(cmd, pixels / 4, &pixels, 0));  // quads
  return kernel_.Record(cmd, pixels % 4, &pixels, 1);                    // the rest
}

}  // namespace lpir::vk
