// Stage 9, back-project, on Vulkan: the kernel's bindings and the one-shot runner.
#include "host/stages/back_project.h"

#include <cstdint>
#include <string>

#include "host/vk/run_once.h"
#include "host/vk/transfer.h"

namespace lpir::vk {
namespace {
#include "shaders/back_project.spv.h"  // kBackProjectSpv, from shaders/back_project.comp

Error BackProjectError(const std::string& message) { return UsageError("back_project", message); }
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

Status RunBackProject(const Context& context, const Params& p, Frame& f, BackProjectWords* words,
                      double* gpu_ns) {
  const Device& device = context.device();
  const uint64_t n = f.n, pixels = uint64_t(p.width) * p.beams;
  if (pixels > UINT32_MAX / 4 || n > UINT32_MAX / 4)
    return BackProjectError(std::to_string(n) + " points, " + std::to_string(pixels) + " pixels");
  const struct {
    const char* name;
    size_t size, want;
  } inputs[] = {{"flags", f.flags.size(), n},
                {"point_pixel", f.point_pixel.size(), n},
                {"r2", f.r2.size(), n},
                {"zt", f.zt.size(), n},
                {"coarse", f.coarse.size(), n},
                {"pixel_point", f.pixel_point.size(), pixels},
                {"pixel_label", f.pixel_label.size(), pixels},
                {"f_range", f.f_range.size(), pixels},
                {"f_height", f.f_height.size(), pixels}};
  for (const auto& in : inputs)
    if (in.size != in.want)
      return BackProjectError(std::string(in.name) + " holds " + std::to_string(in.size) +
                              " elements, not " + std::to_string(in.want));

  const VkDeviceSize per_point = 4 * n, per_pixel = 4 * pixels;
  const MemoryKind kind = MemoryKind::kDeviceLocal;
  LPIR_VK_ASSIGN_OR_RETURN(Buffer params_buffer, Buffer::Create(device, sizeof(Params), kind));
  LPIR_VK_ASSIGN_OR_RETURN(Buffer flags, Buffer::Create(device, per_point, kind));
  LPIR_VK_ASSIGN_OR_RETURN(Buffer point_pixel, Buffer::Create(device, per_point, kind));
  LPIR_VK_ASSIGN_OR_RETURN(Buffer pixel_point, Buffer::Create(device, per_pixel, kind));
  LPIR_VK_ASSIGN_OR_RETURN(Buffer pixel_label, Buffer::Create(device, per_pixel, kind));
  LPIR_VK_ASSIGN_OR_RETURN(Buffer f_range, Buffer::Create(device, per_pixel, kind));
  LPIR_VK_ASSIGN_OR_RETURN(Buffer f_height, Buffer::Create(device, per_pixel, kind));
  LPIR_VK_ASSIGN_OR_RETURN(Buffer r2, Buffer::Create(device, per_point, kind));
  LPIR_VK_ASSIGN_OR_RETURN(Buffer zt, Buffer::Create(device, per_point, kind));
  LPIR_VK_ASSIGN_OR_RETURN(Buffer coarse, Buffer::Create(device, per_point, kind));
  const VkDeviceSize out_bytes = BackProjectStage::LabelWhyBytes(n);
  LPIR_VK_ASSIGN_OR_RETURN(Buffer label_why, Buffer::Create(device, out_bytes, kind));

  LPIR_VK_ASSIGN_OR_RETURN(Transfer transfer, Transfer::Create(device));
  LPIR_VK_RETURN_IF_ERROR(transfer.Upload(params_buffer, &p, sizeof(Params)));
  if (n) {
    LPIR_VK_RETURN_IF_ERROR(transfer.Upload(flags, f.flags.data(), per_point));
    LPIR_VK_RETURN_IF_ERROR(transfer.Upload(point_pixel, f.point_pixel.data(), per_point));
    LPIR_VK_RETURN_IF_ERROR(transfer.Upload(r2, f.r2.data(), per_point));
    LPIR_VK_RETURN_IF_ERROR(transfer.Upload(zt, f.zt.data(), per_point));
    LPIR_VK_RETURN_IF_ERROR(transfer.Upload(coarse, f.coarse.data(), per_point));
  }
  if (pixels) {
    LPIR_VK_RETURN_IF_ERROR(transfer.Upload(pixel_point, f.pixel_point.data(), per_pixel));
    LPIR_VK_RETURN_IF_ERROR(transfer.Upload(pixel_label, f.pixel_label.data(), per_pixel));
    LPIR_VK_RETURN_IF_ERROR(transfer.Upload(f_range, f.f_range.data(), per_pixel));
    LPIR_VK_RETURN_IF_ERROR(transfer.Upload(f_height, f.f_height.data(), per_pixel));
  }

  BackProjectBuffers bindings;
  bindings.params = &params_buffer;
  bindings.flags = &flags;
  bindings.point_pixel = &point_pixel;
  bindings.pixel_point = &pixel_point;
  bindings.pixel_label = &pixel_label;
  bindings.f_range = &f_range;
  bindings.f_height = &f_height;
  bindings.r2 = &r2;
  bindings.zt = &zt;
  bindings.coarse = &coarse;
  bindings.label_why = &label_why;
  LPIR_VK_ASSIGN_OR_RETURN(BackProjectStage stage, BackProjectStage::Create(device, bindings));
  LPIR_VK_RETURN_IF_ERROR(RunOnce(
      device, [&](CommandBuffer& cmd) { return stage.Record(cmd, uint32_t(n)); }, gpu_ns));

  BackProjectWords local;
  BackProjectWords& out = words ? *words : local;
  out.label_why.assign(out_bytes, 0);
  if (n) LPIR_VK_RETURN_IF_ERROR(transfer.Download(label_why, out.label_why.data(), out_bytes));
  f.label_why.assign(out.label_why.begin(), out.label_why.begin() + n);
  f.label.resize(n);
  f.why.resize(n);
  for (uint64_t i = 0; i < n; ++i) {
    const uint8_t byte = f.label_why[i];
    if (WhyOf(byte) > kWhyNoise || LabelOf(byte) != (WhyOf(byte) == kWhyGround))
      return BackProjectError("point " + std::to_string(i) + ": byte " + std::to_string(byte) +
                              " is no label and why");
    f.label[i] = LabelOf(byte);
    f.why[i] = WhyOf(byte);
  }
  return Status();
}

}  // namespace lpir::vk
