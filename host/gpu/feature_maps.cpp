// feature_maps, on Vulkan: the kernel's bindings and its recording.
#include "host/gpu/feature_maps.h"

#include <cstdint>

namespace lpir::vk {
namespace {
#include "shaders/feature_maps.spv.h"  // kFeatureMapsSpv, compiled from shaders/feature_maps.comp

struct Push {
  uint32_t pixels;
};
}  // namespace

Result<FeatureMapsStage> FeatureMapsStage::Create(const Device& device,
                                                  const FeatureMapsBuffers& b) {
  PipelineDesc desc;
  desc.name = "feature_maps";
  desc.code = SpirvOf(kFeatureMapsSpv);
  desc.bindings.assign(12, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER);
  desc.bindings[0] = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
  desc.push_constant_bytes = sizeof(Push);
  desc.local_size_x = kLocalSize;
  desc.passes = 3;
  desc.cpu_items = kCpuItems;
  LPIR_VK_ASSIGN_OR_RETURN(
      Kernel kernel,
      Kernel::Create(device, desc,
                     {b.params, b.pixel_point, b.r2, b.zt, b.pixel_filled, b.f_range, b.f_height,
                      b.f_slope, b.f_edge_l, b.f_edge_r, b.f_varz, b.feature_pack}));
  return FeatureMapsStage(std::move(kernel));
}

Status FeatureMapsStage::Record(CommandBuffer& cmd, uint32_t width, uint32_t beams) const {
  const uint32_t pixels = width * beams, runs = kernel_.Chunks(width) * beams;
  // Pass 1 measures four pixels an invocation where no quad straddles rows, pass 0 one.
  const bool quads = width % 4 == 0;
  const Push measure{quads ? pixels / 4 : pixels}, features{runs};
  LPIR_VK_RETURN_IF_ERROR(kernel_.Record(cmd, measure.pixels, &measure, quads ? 1 : 0));
  cmd.ComputeToCompute();
  return kernel_.Record(cmd, runs, &features, 2);
}

}  // namespace lpir::vk
