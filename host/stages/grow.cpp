// Stage 8, grow, on Vulkan: the passes of shaders/grow.comp and the one-shot runner.
#include "host/stages/grow.h"

#include <algorithm>
#include <cstdint>
#include <string>
#include <utility>

#include "host/vk/run_once.h"
#include "host/vk/transfer.h"

namespace lpir::vk {
namespace {
#include "shaders/grow.spv.h"  // kGrowSpv, compiled from shaders/grow.comp at build time

Error GrowError(const std::string& message) { return UsageError("grow", message); }

struct Push {
  uint32_t count;  // pixels
};
}  // namespace

Result<GrowStage> GrowStage::Create(const Device& device, const GrowBuffers& b) {
  PipelineDesc desc;
  desc.name = "grow";
  desc.code = SpirvOf(kGrowSpv);
  desc.bindings.assign(10, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER);
  desc.bindings[0] = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
  desc.push_constant_bytes = sizeof(Push);
  desc.local_size_x = kLocalSize;
  desc.passes = kPasses;
  LPIR_VK_ASSIGN_OR_RETURN(
      Kernel kernel,
      Kernel::Create(device, desc,
                     {b.params, b.pixel_fused, b.f_inten, b.f_height, b.f_range, b.pixel_grown,
                      b.pixel_comp, b.pixel_label, b.grow_reach, b.grow_sizes}));
  return GrowStage(std::move(kernel));
}

Status GrowStage::Record(CommandBuffer& cmd, uint32_t width, uint32_t beams) const {
  const Push push{width * beams};
  for (uint32_t pass = 0; pass < kPasses; ++pass) {
    if (pass > 0) cmd.ComputeToCompute();
    LPIR_VK_RETURN_IF_ERROR(kernel_.Record(cmd, push.count, &push, pass));
  }
  return Status();
}

Status RunGrow(const Context& context, const Params& p, Frame& f, double* gpu_ns) {
  const Device& device = context.device();
  const uint64_t pixels = uint64_t(p.width) * p.beams;
  if (pixels >= UINT32_MAX / 4) return GrowError(std::to_string(pixels) + " pixels");
  const struct {
    const char* name;
    size_t size;
  } inputs[] = {{"pixel_fused", f.pixel_fused.size()},
                {"f_inten", f.f_inten.size()},
                {"f_height", f.f_height.size()},
                {"f_range", f.f_range.size()}};
  for (const auto& in : inputs)
    if (in.size != pixels)
      return GrowError(std::string(in.name) + " holds " + std::to_string(in.size) +
                       " elements for " + std::to_string(pixels) + " pixels");

  // At least one element per buffer (an empty image still binds them).
  const VkDeviceSize per_pixel = 4 * std::max<uint64_t>(pixels, 1);
  const MemoryKind kind = MemoryKind::kDeviceLocal;
  LPIR_VK_ASSIGN_OR_RETURN(Buffer params_buffer, Buffer::Create(device, sizeof(Params), kind));
  LPIR_VK_ASSIGN_OR_RETURN(Buffer pixel_fused, Buffer::Create(device, per_pixel, kind));
  LPIR_VK_ASSIGN_OR_RETURN(Buffer f_inten, Buffer::Create(device, per_pixel, kind));
  LPIR_VK_ASSIGN_OR_RETURN(Buffer f_height, Buffer::Create(device, per_pixel, kind));
  LPIR_VK_ASSIGN_OR_RETURN(Buffer f_range, Buffer::Create(device, per_pixel, kind));
  LPIR_VK_ASSIGN_OR_RETURN(Buffer pixel_grown, Buffer::Create(device, per_pixel, kind));
  LPIR_VK_ASSIGN_OR_RETURN(Buffer pixel_comp, Buffer::Create(device, per_pixel, kind));
  LPIR_VK_ASSIGN_OR_RETURN(Buffer pixel_label, Buffer::Create(device, per_pixel, kind));
  LPIR_VK_ASSIGN_OR_RETURN(Buffer grow_reach,
                           Buffer::Create(device, GrowStage::ReachBytes(pixels), kind));
  LPIR_VK_ASSIGN_OR_RETURN(Buffer grow_sizes, Buffer::Create(device, per_pixel, kind));

  LPIR_VK_ASSIGN_OR_RETURN(Transfer transfer, Transfer::Create(device));
  LPIR_VK_RETURN_IF_ERROR(transfer.Upload(params_buffer, &p, sizeof(Params)));
  if (pixels) {
    const VkDeviceSize bytes = 4 * pixels;
    LPIR_VK_RETURN_IF_ERROR(transfer.Upload(pixel_fused, f.pixel_fused.data(), bytes));
    LPIR_VK_RETURN_IF_ERROR(transfer.Upload(f_inten, f.f_inten.data(), bytes));
    LPIR_VK_RETURN_IF_ERROR(transfer.Upload(f_height, f.f_height.data(), bytes));
    LPIR_VK_RETURN_IF_ERROR(transfer.Upload(f_range, f.f_range.data(), bytes));
  }

  const GrowBuffers bindings{&params_buffer, &pixel_fused, &f_inten,     &f_height,   &f_range,
                             &pixel_grown,   &pixel_comp,  &pixel_label, &grow_reach, &grow_sizes};
  LPIR_VK_ASSIGN_OR_RETURN(GrowStage stage, GrowStage::Create(device, bindings));
  LPIR_VK_RETURN_IF_ERROR(RunOnce(
      device, [&](CommandBuffer& cmd) { return stage.Record(cmd, p.width, p.beams); }, gpu_ns));

  f.pixel_grown.resize(pixels);
  f.pixel_comp.resize(pixels);
  f.pixel_label.resize(pixels);
  if (pixels) {
    const VkDeviceSize bytes = 4 * pixels;
    LPIR_VK_RETURN_IF_ERROR(transfer.Download(pixel_grown, f.pixel_grown.data(), bytes));
    LPIR_VK_RETURN_IF_ERROR(transfer.Download(pixel_comp, f.pixel_comp.data(), bytes));
    LPIR_VK_RETURN_IF_ERROR(transfer.Download(pixel_label, f.pixel_label.data(), bytes));
  }
  return Status();
}

}  // namespace lpir::vk
