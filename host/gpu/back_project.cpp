// back_project, on Vulkan: the kernel's bindings and its recording.
#include "host/gpu/back_project.h"

#include <cstdint>

namespace lpir::vk {
namespace {
#include "shaders/back_project.spv.h"  // kBackProjectSpv, from shaders/back_project.comp
}  // namespace

Result<BackProjectStage> BackProjectStage::Create(const Device& device,
                                                  const BackProjectBuffers& b) {
  PipelineDesc desc;
  desc.name = "back_project";
  desc.code = SpirvOf(kBackProjectSpv);
  desc.bindings = {VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER};
  for (int k = 0; k < 10; ++k) desc.bindings.push_back(VK_DESCRIPTOR_TYPE_STORAGE_BUFFER);
  desc.push_constant_bytes = sizeof(uint32_t);
  desc.local_size_x = kLocalSize;
  LPIR_VK_ASSIGN_OR_RETURN(
      Kernel kernel, Kernel::Create(device, desc,
                                    {b.params, b.flags, b.point_pixel, b.pixel_point, b.pixel_label,
                                     b.f_range, b.f_height, b.r2, b.zt, b.coarse, b.label_why}));
  return BackProjectStage(std::move(kernel));
}

Status BackProjectStage::Record(CommandBuffer& cmd, uint32_t n) const {
  return kernel_.Record(cmd, n / 4 + (n % 4 != 0), &n);  // four points an invocation
}

}  // namespace lpir::vk
