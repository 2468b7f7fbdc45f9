// Stage 8, grow, on Vulkan: the passes of shaders/grow.comp and the one-shot runner.
#include "host/stages/grow.h"

#include "host/vk/run_once.h"

#include <algorithm>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "host/vk/transfer.h"

namespace lpir::vk {
namespace {
#include "shaders/grow.spv.h"  // kGrowSpv, compiled from shaders/grow.comp at build time

Error GrowError(const std::string& message) { return UsageError("grow", message); }

// The push constants of shaders/grow.comp.
struct Push {
  uint32_t sweep, count, budget;
};
enum Mode : uint32_t {
  kReset = 0,  // per flags word
  kInit = 1,
  kList = 2,   // one invocation
  kSweep = 3,  // sweeps 0 .. budget - 1, per list entry, indirect
  kMerge = 4,  // per row and 4 columns
  kFlatten = 5,
  kFinish = 6,
  kSteps = 7,       // per list entry, indirect (sweep 0's workgroup count)
  kFinishTail = 8,  // the last pixels % 4 (kInit and kFinish: quads of pixels)
  kRuns = 9,        // per quad of pixels, the last pixels % 4 included (as kFlatten)
  kModes = 10
};
}  // namespace

Result<GrowStage> GrowStage::Create(const Device& device, const GrowBuffers& b,
                                    uint32_t max_iters) {
  if (max_iters == 0) return GrowError("grow_max_iters is 0");
  if (!b.flags) return GrowError("no flags buffer");
  if (b.flags->size() < 4 * VkDeviceSize(FlagWords(max_iters)))
    return GrowError("the flags buffer holds fewer than " + std::to_string(FlagWords(max_iters)) +
                     " words");
  PipelineDesc desc;
  desc.name = "grow";
  desc.code = SpirvOf(kGrowSpv);
  desc.bindings.assign(11, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER);
  desc.bindings[0] = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
  desc.push_constant_bytes = sizeof(Push);
  desc.local_size_x = kLocalSize;
  desc.passes = kModes;
  LPIR_VK_ASSIGN_OR_RETURN(
      Kernel kernel,
      Kernel::Create(device, desc,
                     {b.params, b.pixel_fused, b.f_inten, b.f_height, b.f_range, b.pixel_grown,
                      b.pixel_comp, b.pixel_label, b.scratch, b.sizes, b.flags}));
  return GrowStage(std::move(kernel), b.flags, max_iters);
}

Status GrowStage::Record(CommandBuffer& cmd, uint32_t width, uint32_t beams) const {
  const uint32_t pixels = width * beams;
  const uint32_t budget = max_iters_;
  auto pass = [&](uint32_t mode, uint32_t invocations) {
    const Push push{0, pixels, budget};
    return kernel_.Record(cmd, invocations, &push, mode);
  };
  LPIR_VK_RETURN_IF_ERROR(pass(kReset, FlagWords(budget)));
  cmd.ComputeToCompute();
  LPIR_VK_RETURN_IF_ERROR(pass(kInit, pixels / 4));
  cmd.ComputeToCompute();
  LPIR_VK_RETURN_IF_ERROR(pass(kList, 1));
  cmd.ComputeToIndirect();
  const Push steps{0, pixels, budget};
  kernel_.RecordIndirect(cmd, *flags_, 4 * 3, &steps, kSteps);
  // Sweeps over the list (at most `pixels` entries: checked by the init pass).
  for (uint32_t k = 0; k < budget; ++k) {
    cmd.ComputeToIndirect();
    const Push push{k, pixels, budget};
    kernel_.RecordIndirect(cmd, *flags_, 4 * 3 * VkDeviceSize(k + 1), &push, kSweep);
  }
  const uint32_t quads = pixels / 4 + (pixels % 4 != 0);
  const uint32_t row_quads = beams * ((width + 3) / 4);
  for (auto [mode, invocations] :
       {std::pair{kRuns, quads}, {kMerge, row_quads}, {kFlatten, quads}}) {
    cmd.ComputeToCompute();
    LPIR_VK_RETURN_IF_ERROR(pass(mode, invocations));
  }
  cmd.ComputeToCompute();
  // At least one invocation: invocation 0 writes the summary word.
  LPIR_VK_RETURN_IF_ERROR(pass(kFinish, std::max(pixels / 4, 1u)));
  return pass(kFinishTail, pixels % 4);
}

Status RunGrow(const Context& context, const Params& p, Frame& f, GrowReport* report,
               double* gpu_ns) {
  const Device& device = context.device();
  const uint64_t pixels = uint64_t(p.width) * p.beams;
  if (pixels > UINT32_MAX / 4) return GrowError(std::to_string(pixels) + " pixels");
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
  const uint32_t budget = p.grow_max_iters;
  if (budget == 0) return GrowError("grow_max_iters is 0");

  // At least one element per buffer (an empty image still binds them).
  const VkDeviceSize per_pixel = 4 * std::max<uint64_t>(pixels, 1);
  const VkDeviceSize flag_bytes = 4 * VkDeviceSize(GrowStage::FlagWords(budget));
  const MemoryKind kind = MemoryKind::kDeviceLocal;
  LPIR_VK_ASSIGN_OR_RETURN(Buffer params_buffer, Buffer::Create(device, sizeof(Params), kind));
  LPIR_VK_ASSIGN_OR_RETURN(Buffer pixel_fused, Buffer::Create(device, per_pixel, kind));
  LPIR_VK_ASSIGN_OR_RETURN(Buffer f_inten, Buffer::Create(device, per_pixel, kind));
  LPIR_VK_ASSIGN_OR_RETURN(Buffer f_height, Buffer::Create(device, per_pixel, kind));
  LPIR_VK_ASSIGN_OR_RETURN(Buffer f_range, Buffer::Create(device, per_pixel, kind));
  LPIR_VK_ASSIGN_OR_RETURN(Buffer pixel_grown, Buffer::Create(device, per_pixel, kind));
  LPIR_VK_ASSIGN_OR_RETURN(Buffer pixel_comp, Buffer::Create(device, per_pixel, kind));
  LPIR_VK_ASSIGN_OR_RETURN(Buffer pixel_label, Buffer::Create(device, per_pixel, kind));
  LPIR_VK_ASSIGN_OR_RETURN(Buffer scratch, Buffer::Create(device, per_pixel, kind));
  LPIR_VK_ASSIGN_OR_RETURN(Buffer sizes, Buffer::Create(device, per_pixel, kind));
  LPIR_VK_ASSIGN_OR_RETURN(Buffer flags, Buffer::Create(device, flag_bytes, kind));

  LPIR_VK_ASSIGN_OR_RETURN(Transfer transfer, Transfer::Create(device));
  LPIR_VK_RETURN_IF_ERROR(transfer.Upload(params_buffer, &p, sizeof(Params)));
  if (pixels) {
    const VkDeviceSize bytes = 4 * pixels;
    LPIR_VK_RETURN_IF_ERROR(transfer.Upload(pixel_fused, f.pixel_fused.data(), bytes));
    LPIR_VK_RETURN_IF_ERROR(transfer.Upload(f_inten, f.f_inten.data(), bytes));
    LPIR_VK_RETURN_IF_ERROR(transfer.Upload(f_height, f.f_height.data(), bytes));
    LPIR_VK_RETURN_IF_ERROR(transfer.Upload(f_range, f.f_range.data(), bytes));
  }

  GrowBuffers bindings;
  bindings.params = &params_buffer;
  bindings.pixel_fused = &pixel_fused;
  bindings.f_inten = &f_inten;
  bindings.f_height = &f_height;
  bindings.f_range = &f_range;
  bindings.pixel_grown = &pixel_grown;
  bindings.pixel_comp = &pixel_comp;
  bindings.pixel_label = &pixel_label;
  bindings.scratch = &scratch;
  bindings.sizes = &sizes;
  bindings.flags = &flags;
  LPIR_VK_ASSIGN_OR_RETURN(GrowStage stage, GrowStage::Create(device, bindings, budget));
  LPIR_VK_RETURN_IF_ERROR(
      RunOnce(device, [&](CommandBuffer& cmd) { return stage.Record(cmd, p.width, p.beams); }, gpu_ns));

  std::vector<uint32_t> flag_words(GrowStage::FlagWords(budget));
  LPIR_VK_RETURN_IF_ERROR(transfer.Download(flags, flag_words.data(), flag_bytes));
  const GrowReport r = GrowStage::ReadReport(flag_words.data(), budget);
  if (report) *report = r;
  f.pixel_grown.resize(pixels);
  f.pixel_comp.resize(pixels);
  f.pixel_label.resize(pixels);
  if (pixels) {
    const VkDeviceSize bytes = 4 * pixels;
    LPIR_VK_RETURN_IF_ERROR(transfer.Download(pixel_grown, f.pixel_grown.data(), bytes));
    LPIR_VK_RETURN_IF_ERROR(transfer.Download(pixel_comp, f.pixel_comp.data(), bytes));
    LPIR_VK_RETURN_IF_ERROR(transfer.Download(pixel_label, f.pixel_label.data(), bytes));
  }
  if (!r.converged())
    return GrowError("no fixed point within grow_max_iters = " + std::to_string(budget) +
                     " sweeps");
  return Status();
}

}  // namespace lpir::vk
