// Stage 6, classify pixels, on Vulkan: the kernel's bindings and the one-shot runner.
#include "host/stages/classify_pixels.h"

#include <cstdint>
#include <string>

#include "host/vk/run_once.h"
#include "host/vk/transfer.h"

namespace lpir::vk {
namespace {
#include "shaders/classify_pixels.spv.h"  // kClassifyPixelsSpv, from shaders/classify_pixels.comp
}  // namespace

Result<ClassifyPixelsStage> ClassifyPixelsStage::Create(const Device& device,
                                                        const ClassifyPixelsBuffers& b) {
  PipelineDesc desc;
  desc.name = "classify_pixels";
  desc.code = SpirvOf(kClassifyPixelsSpv);
  desc.bindings.assign(8, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER);
  desc.bindings[0] = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
  desc.push_constant_bytes = sizeof(uint32_t);
  desc.local_size_x = kLocalSize;
  desc.passes = 2;
  LPIR_VK_ASSIGN_OR_RETURN(
      Kernel kernel, Kernel::Create(device, desc,
                                    {b.params, b.pixel_filled, b.f_edge_l, b.f_edge_r, b.f_slope,
                                     b.f_varz, b.f_vari, b.pixel_class}));
  return ClassifyPixelsStage(std::move(kernel));
}

Status ClassifyPixelsStage::Record(CommandBuffer& cmd, uint32_t pixels) const {
  LPIR_VK_RETURN_IF_ERROR(kernel_.Record(cmd, pixels / 4, &pixels, 0));  // quads
  return kernel_.Record(cmd, pixels % 4, &pixels, 1);                    // the rest
}

Status RunClassifyPixels(const Context& context, const Params& p, Frame& f, double* gpu_ns) {
  const Device& device = context.device();
  const uint64_t pixels = uint64_t(p.width) * p.beams;
  if (pixels > UINT32_MAX || f.pixel_filled.size() != pixels || f.f_edge_l.size() != pixels ||
      f.f_edge_r.size() != pixels || f.f_slope.size() != pixels || f.f_varz.size() != pixels ||
      f.f_vari.size() != pixels) {
    Error e;
    e.result = VK_ERROR_UNKNOWN;
    e.message = "classify_pixels: the frame's stage 5 buffers do not hold " +
                std::to_string(pixels) + " pixels";
    return e;
  }

  const VkDeviceSize bytes = 4 * pixels;
  const MemoryKind kind = MemoryKind::kDeviceLocal;
  LPIR_VK_ASSIGN_OR_RETURN(Buffer params_buffer, Buffer::Create(device, sizeof(Params), kind));
  LPIR_VK_ASSIGN_OR_RETURN(Buffer filled, Buffer::Create(device, bytes, kind));
  LPIR_VK_ASSIGN_OR_RETURN(Buffer edge_l, Buffer::Create(device, bytes, kind));
  LPIR_VK_ASSIGN_OR_RETURN(Buffer edge_r, Buffer::Create(device, bytes, kind));
  LPIR_VK_ASSIGN_OR_RETURN(Buffer slope, Buffer::Create(device, bytes, kind));
  LPIR_VK_ASSIGN_OR_RETURN(Buffer varz, Buffer::Create(device, bytes, kind));
  LPIR_VK_ASSIGN_OR_RETURN(Buffer vari, Buffer::Create(device, bytes, kind));
  LPIR_VK_ASSIGN_OR_RETURN(Buffer pixel_class, Buffer::Create(device, bytes, kind));

  LPIR_VK_ASSIGN_OR_RETURN(Transfer transfer, Transfer::Create(device));
  LPIR_VK_RETURN_IF_ERROR(transfer.Upload(params_buffer, &p, sizeof(Params)));
  if (pixels) {
    LPIR_VK_RETURN_IF_ERROR(transfer.Upload(filled, f.pixel_filled.data(), bytes));
    LPIR_VK_RETURN_IF_ERROR(transfer.Upload(edge_l, f.f_edge_l.data(), bytes));
    LPIR_VK_RETURN_IF_ERROR(transfer.Upload(edge_r, f.f_edge_r.data(), bytes));
    LPIR_VK_RETURN_IF_ERROR(transfer.Upload(slope, f.f_slope.data(), bytes));
    LPIR_VK_RETURN_IF_ERROR(transfer.Upload(varz, f.f_varz.data(), bytes));
    LPIR_VK_RETURN_IF_ERROR(transfer.Upload(vari, f.f_vari.data(), bytes));
  }

  ClassifyPixelsBuffers bindings;
  bindings.params = &params_buffer;
  bindings.pixel_filled = &filled;
  bindings.f_edge_l = &edge_l;
  bindings.f_edge_r = &edge_r;
  bindings.f_slope = &slope;
  bindings.f_varz = &varz;
  bindings.f_vari = &vari;
  bindings.pixel_class = &pixel_class;
  LPIR_VK_ASSIGN_OR_RETURN(ClassifyPixelsStage stage,
                           ClassifyPixelsStage::Create(device, bindings));
  LPIR_VK_RETURN_IF_ERROR(RunOnce(
      device, [&](CommandBuffer& cmd) { return stage.Record(cmd, uint32_t(pixels)); }, gpu_ns));

  f.pixel_class.resize(pixels);
  if (pixels) LPIR_VK_RETURN_IF_ERROR(transfer.Download(pixel_class, f.pixel_class.data(), bytes));
  return Status();
}

}  // namespace lpir::vk
