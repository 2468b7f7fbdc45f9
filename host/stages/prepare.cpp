// Stage 1, prepare, on Vulkan: the kernel's bindings and the one-shot runner.
#include "host/stages/prepare.h"

#include <cstdint>
#include <string>

#include "host/vk/run_once.h"
#include "host/vk/transfer.h"

namespace lpir::vk {
namespace {
#include "shaders/prepare.spv.h"  // kPrepareSpv, compiled from shaders/prepare.comp at build time
}  // namespace

Result<PrepareStage> PrepareStage::Create(const Device& device, const PrepareBuffers& b) {
  PipelineDesc desc;
  desc.name = "prepare";
  desc.code = SpirvOf(kPrepareSpv);
  desc.bindings = {VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
                   VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
                   VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
                   VK_DESCRIPTOR_TYPE_STORAGE_BUFFER};
  desc.push_constant_bytes = sizeof(uint32_t);
  desc.local_size_x = kLocalSize;
  LPIR_VK_ASSIGN_OR_RETURN(
      Kernel kernel,
      Kernel::Create(device, desc, {b.params, b.points, b.ring, b.flags, b.zt, b.r2, b.inten}));
  return PrepareStage(std::move(kernel));
}

Status PrepareStage::Record(CommandBuffer& cmd, uint32_t n) const {
  return kernel_.Record(cmd, n, &n);
}

Status RunPrepare(const Context& context, const Cloud& cloud, const Params& p, Frame& f,
                  double* gpu_ns) {
  const Device& device = context.device();
  const uint64_t n = cloud.size();
  if (n > UINT32_MAX || (!cloud.ring.empty() && cloud.ring.size() != n)) {
    Error e;
    e.result = VK_ERROR_UNKNOWN;
    e.message = "prepare: a cloud of " + std::to_string(n) + " points with " +
                std::to_string(cloud.ring.size()) + " ring entries";
    return e;
  }
  Params params = p;
  params.has_ring = cloud.ring.empty() ? 0u : 1u;

  const VkDeviceSize per_point = 4 * n;  // one uint32 / int32 / float per point
  const MemoryKind kind = MemoryKind::kDeviceLocal;
  LPIR_VK_ASSIGN_OR_RETURN(Buffer params_buffer, Buffer::Create(device, sizeof(Params), kind));
  LPIR_VK_ASSIGN_OR_RETURN(Buffer points, Buffer::Create(device, 16 * n, kind));
  LPIR_VK_ASSIGN_OR_RETURN(Buffer ring,
                           Buffer::Create(device, params.has_ring ? per_point : 4, kind));
  LPIR_VK_ASSIGN_OR_RETURN(Buffer flags, Buffer::Create(device, per_point, kind));
  LPIR_VK_ASSIGN_OR_RETURN(Buffer zt, Buffer::Create(device, per_point, kind));
  LPIR_VK_ASSIGN_OR_RETURN(Buffer r2, Buffer::Create(device, per_point, kind));
  LPIR_VK_ASSIGN_OR_RETURN(Buffer inten, Buffer::Create(device, per_point, kind));

  LPIR_VK_ASSIGN_OR_RETURN(Transfer transfer, Transfer::Create(device));
  LPIR_VK_RETURN_IF_ERROR(transfer.Upload(params_buffer, &params, sizeof(Params)));
  LPIR_VK_RETURN_IF_ERROR(transfer.Upload(points, cloud.xyzi.data(), 16 * n));
  if (params.has_ring) LPIR_VK_RETURN_IF_ERROR(transfer.Upload(ring, cloud.ring.data(), per_point));

  PrepareBuffers bindings;
  bindings.params = &params_buffer;
  bindings.points = &points;
  bindings.ring = &ring;
  bindings.flags = &flags;
  bindings.zt = &zt;
  bindings.r2 = &r2;
  bindings.inten = &inten;
  LPIR_VK_ASSIGN_OR_RETURN(PrepareStage stage, PrepareStage::Create(device, bindings));
  LPIR_VK_RETURN_IF_ERROR(RunOnce(
      device, [&](CommandBuffer& cmd) { return stage.Record(cmd, uint32_t(n)); }, gpu_ns));

  f.n = uint32_t(n);
  f.flags.resize(n);
  f.zt.resize(n);
  f.r2.resize(n);
  f.inten.resize(n);
  LPIR_VK_RETURN_IF_ERROR(transfer.Download(flags, f.flags.data(), per_point));
  LPIR_VK_RETURN_IF_ERROR(transfer.Download(zt, f.zt.data(), per_point));
  LPIR_VK_RETURN_IF_ERROR(transfer.Download(r2, f.r2.data(), per_point));
  LPIR_VK_RETURN_IF_ERROR(transfer.Download(inten, f.inten.data(), per_point));
  return Status();
}

}  // namespace lpir::vk
