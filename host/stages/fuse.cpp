// Stage 7, fuse, on Vulkan: the kernel's bindings and the one-shot runner.
#include "host/stages/fuse.h"

#include <cstdint>
#include <string>

#include "host/vk/run_once.h"
#include "host/vk/transfer.h"

namespace lpir::vk {
namespace {
#include "shaders/fuse.spv.h"  // kFuseSpv, compiled from shaders/fuse.comp at build time

Error SizeError(const std::string& message) { return UsageError("fuse", message); }
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

Status RunFuse(const Context& context, const Params& p, Frame& f, double* gpu_ns) {
  const Device& device = context.device();
  const uint64_t pixels = uint64_t(p.width) * p.beams;
  if (pixels > UINT32_MAX / 4) return SizeError(std::to_string(pixels) + " pixels");
  const struct {
    const char* name;
    size_t size;
  } inputs[] = {{"pixel_class", f.pixel_class.size()},
                {"pixel_point", f.pixel_point.size()},
                {"pixel_filled", f.pixel_filled.size()},
                {"f_range", f.f_range.size()},
                {"f_height", f.f_height.size()}};
  for (const auto& in : inputs)
    if (in.size != pixels)
      return SizeError(std::string(in.name) + " holds " + std::to_string(in.size) +
                       " elements for " + std::to_string(pixels) + " pixels");

  const VkDeviceSize per_pixel = 4 * pixels;
  const VkDeviceSize coarse_bytes = 4 * VkDeviceSize(f.coarse.size());
  const MemoryKind kind = MemoryKind::kDeviceLocal;
  LPIR_VK_ASSIGN_OR_RETURN(Buffer params_buffer, Buffer::Create(device, sizeof(Params), kind));
  LPIR_VK_ASSIGN_OR_RETURN(Buffer pixel_class, Buffer::Create(device, per_pixel, kind));
  LPIR_VK_ASSIGN_OR_RETURN(Buffer pixel_point, Buffer::Create(device, per_pixel, kind));
  LPIR_VK_ASSIGN_OR_RETURN(Buffer coarse, Buffer::Create(device, coarse_bytes, kind));
  LPIR_VK_ASSIGN_OR_RETURN(Buffer pixel_filled, Buffer::Create(device, per_pixel, kind));
  LPIR_VK_ASSIGN_OR_RETURN(Buffer f_range, Buffer::Create(device, per_pixel, kind));
  LPIR_VK_ASSIGN_OR_RETURN(Buffer f_height, Buffer::Create(device, per_pixel, kind));
  LPIR_VK_ASSIGN_OR_RETURN(Buffer pixel_fused, Buffer::Create(device, per_pixel, kind));

  LPIR_VK_ASSIGN_OR_RETURN(Transfer transfer, Transfer::Create(device));
  LPIR_VK_RETURN_IF_ERROR(transfer.Upload(params_buffer, &p, sizeof(Params)));
  if (pixels) {
    LPIR_VK_RETURN_IF_ERROR(transfer.Upload(pixel_class, f.pixel_class.data(), per_pixel));
    LPIR_VK_RETURN_IF_ERROR(transfer.Upload(pixel_point, f.pixel_point.data(), per_pixel));
    LPIR_VK_RETURN_IF_ERROR(transfer.Upload(pixel_filled, f.pixel_filled.data(), per_pixel));
    LPIR_VK_RETURN_IF_ERROR(transfer.Upload(f_range, f.f_range.data(), per_pixel));
    LPIR_VK_RETURN_IF_ERROR(transfer.Upload(f_height, f.f_height.data(), per_pixel));
  }
  if (coarse_bytes) {
    LPIR_VK_RETURN_IF_ERROR(transfer.Upload(coarse, f.coarse.data(), coarse_bytes));
  } else {  // the reference reads 0 in place of coarse[0] when there are no points
    const uint32_t zeros[4] = {0, 0, 0, 0};
    LPIR_VK_RETURN_IF_ERROR(transfer.Upload(coarse, zeros, sizeof(zeros)));
  }

  FuseBuffers bindings;
  bindings.params = &params_buffer;
  bindings.pixel_class = &pixel_class;
  bindings.pixel_point = &pixel_point;
  bindings.coarse = &coarse;
  bindings.pixel_filled = &pixel_filled;
  bindings.f_range = &f_range;
  bindings.f_height = &f_height;
  bindings.pixel_fused = &pixel_fused;
  LPIR_VK_ASSIGN_OR_RETURN(FuseStage stage, FuseStage::Create(device, bindings));
  LPIR_VK_RETURN_IF_ERROR(RunOnce(
      device, [&](CommandBuffer& cmd) { return stage.Record(cmd, p.width, p.beams); }, gpu_ns));

  f.pixel_fused.resize(pixels);
  if (pixels) {
    LPIR_VK_RETURN_IF_ERROR(transfer.Download(pixel_fused, f.pixel_fused.data(), per_pixel));
  }
  return Status();
}

}  // namespace lpir::vk
