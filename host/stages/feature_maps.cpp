// Stage 5, feature maps, on Vulkan: the kernel's bindings and the one-shot runner.
#include "host/stages/feature_maps.h"

#include <cstdint>
#include <string>
#include <vector>

#include "host/vk/run_once.h"
#include "host/vk/transfer.h"

namespace lpir::vk {
namespace {
#include "shaders/feature_maps.spv.h"  // kFeatureMapsSpv, compiled from shaders/feature_maps.comp

struct Push {
  uint32_t pixels;
};

Error Invalid(const std::string& message) {
  Error e;
  e.result = VK_ERROR_UNKNOWN;
  e.message = "feature_maps: " + message;
  return e;
}
}  // namespace

Result<FeatureMapsStage> FeatureMapsStage::Create(const Device& device,
                                                  const FeatureMapsBuffers& b) {
  PipelineDesc desc;
  desc.name = "feature_maps";
  desc.code = SpirvOf(kFeatureMapsSpv);
  desc.bindings.assign(15, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER);
  desc.bindings[0] = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
  desc.push_constant_bytes = sizeof(Push);
  desc.local_size_x = kLocalSize;
  desc.passes = 3;
  desc.cpu_items = kCpuItems;
  LPIR_VK_ASSIGN_OR_RETURN(
      Kernel kernel, Kernel::Create(device, desc,
                                    {b.params, b.pixel_point, b.r2, b.zt, b.inten, b.pixel_filled,
                                     b.f_range, b.f_inten, b.f_height, b.f_slope, b.f_edge_l,
                                     b.f_edge_r, b.f_varz, b.f_vari, b.feature_pack}));
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

Status RunFeatureMaps(const Context& context, const Params& p, Frame& f, double* gpu_ns) {
  const Device& device = context.device();
  const uint64_t n = f.n;
  const uint64_t pixels = uint64_t(p.width) * p.beams;
  if (pixels > UINT32_MAX) return Invalid("the image has more than 2^32 - 1 pixels");
  if (f.r2.size() != n || f.zt.size() != n || f.inten.size() != n)
    return Invalid("the frame's stage 1 buffers do not hold " + std::to_string(n) + " points");
  if (f.pixel_point.size() != pixels)
    return Invalid("the frame's pixel_point does not hold " + std::to_string(pixels) + " pixels");
  for (uint32_t i : f.pixel_point)
    if (i != kNone && i >= n) return Invalid("pixel_point names a point past n");

  const VkDeviceSize per_point = 4 * n, per_pixel = 4 * pixels;
  const MemoryKind kind = MemoryKind::kDeviceLocal;
  LPIR_VK_ASSIGN_OR_RETURN(Buffer params_buffer, Buffer::Create(device, sizeof(Params), kind));
  LPIR_VK_ASSIGN_OR_RETURN(Buffer pixel_point, Buffer::Create(device, per_pixel, kind));
  LPIR_VK_ASSIGN_OR_RETURN(Buffer r2, Buffer::Create(device, per_point, kind));
  LPIR_VK_ASSIGN_OR_RETURN(Buffer zt, Buffer::Create(device, per_point, kind));
  LPIR_VK_ASSIGN_OR_RETURN(Buffer inten, Buffer::Create(device, per_point, kind));
  // Outputs, in the order of Frame's members and the bindings 5-13.
  std::vector<uint32_t>* filled_out = &f.pixel_filled;
  std::vector<float>* maps_out[8] = {&f.f_range,  &f.f_inten,  &f.f_height, &f.f_slope,
                                     &f.f_edge_l, &f.f_edge_r, &f.f_varz,   &f.f_vari};
  LPIR_VK_ASSIGN_OR_RETURN(Buffer filled, Buffer::Create(device, per_pixel, kind));
  LPIR_VK_ASSIGN_OR_RETURN(Buffer feature_pack,
                           Buffer::Create(device, FeatureMapsStage::PackBytes(pixels), kind));
  std::vector<Buffer> maps;
  for (int k = 0; k < 8; ++k) {
    LPIR_VK_ASSIGN_OR_RETURN(Buffer map, Buffer::Create(device, per_pixel, kind));
    maps.push_back(std::move(map));
  }

  LPIR_VK_ASSIGN_OR_RETURN(Transfer transfer, Transfer::Create(device));
  LPIR_VK_RETURN_IF_ERROR(transfer.Upload(params_buffer, &p, sizeof(Params)));
  if (pixels)
    LPIR_VK_RETURN_IF_ERROR(transfer.Upload(pixel_point, f.pixel_point.data(), per_pixel));
  if (n) {
    LPIR_VK_RETURN_IF_ERROR(transfer.Upload(r2, f.r2.data(), per_point));
    LPIR_VK_RETURN_IF_ERROR(transfer.Upload(zt, f.zt.data(), per_point));
    LPIR_VK_RETURN_IF_ERROR(transfer.Upload(inten, f.inten.data(), per_point));
  }

  FeatureMapsBuffers bindings;
  bindings.params = &params_buffer;
  bindings.pixel_point = &pixel_point;
  bindings.r2 = &r2;
  bindings.zt = &zt;
  bindings.inten = &inten;
  bindings.pixel_filled = &filled;
  bindings.f_range = &maps[0];
  bindings.f_inten = &maps[1];
  bindings.f_height = &maps[2];
  bindings.f_slope = &maps[3];
  bindings.f_edge_l = &maps[4];
  bindings.f_edge_r = &maps[5];
  bindings.f_varz = &maps[6];
  bindings.f_vari = &maps[7];
  bindings.feature_pack = &feature_pack;
  LPIR_VK_ASSIGN_OR_RETURN(FeatureMapsStage stage, FeatureMapsStage::Create(device, bindings));
  LPIR_VK_RETURN_IF_ERROR(RunOnce(
      device, [&](CommandBuffer& cmd) { return stage.Record(cmd, p.width, p.beams); }, gpu_ns));

  filled_out->resize(pixels);
  for (std::vector<float>* m : maps_out) m->resize(pixels);
  if (pixels) {
    LPIR_VK_RETURN_IF_ERROR(transfer.Download(filled, filled_out->data(), per_pixel));
    for (int k = 0; k < 8; ++k)
      LPIR_VK_RETURN_IF_ERROR(transfer.Download(maps[k], maps_out[k]->data(), per_pixel));
  }
  return Status();
}

}  // namespace lpir::vk
