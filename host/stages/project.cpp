// Stage 2, project, on Vulkan: the kernel's bindings and the one-shot runner.
#include "host/stages/project.h"

#include <cstdint>
#include <string>

#include "host/vk/run_once.h"
#include "host/vk/transfer.h"

namespace lpir::vk {
namespace {
#include "shaders/project.spv.h"  // kProjectSpv, compiled from shaders/project.comp at build time

struct Push {
  uint32_t n;
};

Error StageError(const std::string& message) { return UsageError("project", message); }

}  // namespace

Result<ProjectStage> ProjectStage::Create(const Device& device, const ProjectBuffers& b) {
  PipelineDesc desc;
  desc.name = "project";
  desc.code = SpirvOf(kProjectSpv);
  desc.bindings = {VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER};
  for (int i = 1; i <= 11; ++i) desc.bindings.push_back(VK_DESCRIPTOR_TYPE_STORAGE_BUFFER);
  desc.push_constant_bytes = sizeof(Push);
  desc.local_size_x = kLocalSize;
  desc.passes = 3;
  desc.cpu_items = kCpuItems;
  LPIR_VK_ASSIGN_OR_RETURN(
      Kernel kernel,
      Kernel::Create(device, desc,
                     {b.params, b.points, b.ring, b.flags, b.r2, b.column_dir, b.beam_bound,
                      b.beam_origin, b.point_pixel, b.pixel_key, b.pixel_point, b.project_exact}));
  return ProjectStage(std::move(kernel), b.pixel_key, b.pixel_point, b.project_exact);
}

Status ProjectStage::Record(CommandBuffer& cmd, uint32_t n) const {
  cmd.FillBuffer(*pixel_key_, 0xFFFFFFFFu);  // kNone
  cmd.FillBuffer(*pixel_point_, 0xFFFFFFFFu);
  const uint32_t header[4] = {0, 1, 1, 0};  // pass 1's dispatch arguments, the list's length
  cmd.UpdateBuffer(*project_exact_, header, sizeof(header));
  cmd.TransferToCompute();
  const Push push{n};
  LPIR_VK_RETURN_IF_ERROR(kernel_.Record(cmd, kernel_.Chunks(n), &push, 0));
  cmd.ComputeToIndirect();
  kernel_.RecordIndirect(cmd, *project_exact_, 0, &push, 1);
  cmd.ComputeToCompute();
  return kernel_.Record(cmd, n, &push, 2);
}

Status RunProject(const Context& context, const Cloud& cloud, const Params& p, const Tables& t,
                  Frame& f, double* gpu_ns) {
  const Device& device = context.device();
  const uint64_t n = cloud.size();
  if (n > UINT32_MAX || (!cloud.ring.empty() && cloud.ring.size() != n))
    return StageError("a cloud of " + std::to_string(n) + " points with " +
                      std::to_string(cloud.ring.size()) + " ring entries");
  if (f.n != n || f.flags.size() != n || f.r2.size() != n)
    return StageError("stage 1 buffers of " + std::to_string(f.flags.size()) + " / " +
                      std::to_string(f.r2.size()) + " entries for " + std::to_string(n) +
                      " points (run Prepare first)");
  if (p.width == 0 || p.beams == 0 || t.column_dir.size() != 2 * size_t(p.width) ||
      t.beam_bound.size() + 1 != p.beams || t.beam_origin.size() + 1 != p.beams)
    return StageError("tables of " + std::to_string(t.column_dir.size()) + " column / " +
                      std::to_string(t.beam_bound.size()) + " bound / " +
                      std::to_string(t.beam_origin.size()) + " origin entries for " +
                      std::to_string(p.width) + " x " + std::to_string(p.beams));
  const uint64_t pixels = uint64_t(p.width) * p.beams;
  if (pixels >= UINT32_MAX) return StageError(std::to_string(pixels) + " pixels");
  Params params = p;
  params.has_ring = cloud.ring.empty() ? 0u : 1u;

  const VkDeviceSize per_point = 4 * n, per_pixel = 4 * pixels;
  const VkDeviceSize bound_bytes = 4 * t.beam_bound.size();
  const MemoryKind kind = MemoryKind::kDeviceLocal;
  LPIR_VK_ASSIGN_OR_RETURN(Buffer params_buffer, Buffer::Create(device, sizeof(Params), kind));
  LPIR_VK_ASSIGN_OR_RETURN(Buffer points, Buffer::Create(device, 16 * n, kind));
  LPIR_VK_ASSIGN_OR_RETURN(Buffer ring,
                           Buffer::Create(device, params.has_ring ? per_point : 4, kind));
  LPIR_VK_ASSIGN_OR_RETURN(Buffer flags, Buffer::Create(device, per_point, kind));
  LPIR_VK_ASSIGN_OR_RETURN(Buffer r2, Buffer::Create(device, per_point, kind));
  LPIR_VK_ASSIGN_OR_RETURN(Buffer column_dir, Buffer::Create(device, 8 * uint64_t(p.width), kind));
  LPIR_VK_ASSIGN_OR_RETURN(Buffer beam_bound, Buffer::Create(device, bound_bytes, kind));
  LPIR_VK_ASSIGN_OR_RETURN(Buffer beam_origin, Buffer::Create(device, bound_bytes, kind));
  LPIR_VK_ASSIGN_OR_RETURN(Buffer point_pixel, Buffer::Create(device, per_point, kind));
  LPIR_VK_ASSIGN_OR_RETURN(Buffer pixel_key, Buffer::Create(device, per_pixel, kind));
  LPIR_VK_ASSIGN_OR_RETURN(Buffer pixel_point, Buffer::Create(device, per_pixel, kind));
  LPIR_VK_ASSIGN_OR_RETURN(Buffer project_exact,
                           Buffer::Create(device, ProjectStage::ExactListBytes(n), kind));

  LPIR_VK_ASSIGN_OR_RETURN(Transfer transfer, Transfer::Create(device));
  LPIR_VK_RETURN_IF_ERROR(transfer.Upload(params_buffer, &params, sizeof(Params)));
  LPIR_VK_RETURN_IF_ERROR(transfer.Upload(points, cloud.xyzi.data(), 16 * n));
  if (params.has_ring) LPIR_VK_RETURN_IF_ERROR(transfer.Upload(ring, cloud.ring.data(), per_point));
  LPIR_VK_RETURN_IF_ERROR(transfer.Upload(flags, f.flags.data(), per_point));
  LPIR_VK_RETURN_IF_ERROR(transfer.Upload(r2, f.r2.data(), per_point));
  LPIR_VK_RETURN_IF_ERROR(transfer.Upload(column_dir, t.column_dir.data(), 8 * size_t(p.width)));
  LPIR_VK_RETURN_IF_ERROR(transfer.Upload(beam_bound, t.beam_bound.data(), bound_bytes));
  LPIR_VK_RETURN_IF_ERROR(transfer.Upload(beam_origin, t.beam_origin.data(), bound_bytes));

  ProjectBuffers bindings;
  bindings.params = &params_buffer;
  bindings.points = &points;
  bindings.ring = &ring;
  bindings.flags = &flags;
  bindings.r2 = &r2;
  bindings.column_dir = &column_dir;
  bindings.beam_bound = &beam_bound;
  bindings.beam_origin = &beam_origin;
  bindings.point_pixel = &point_pixel;
  bindings.pixel_key = &pixel_key;
  bindings.pixel_point = &pixel_point;
  bindings.project_exact = &project_exact;
  LPIR_VK_ASSIGN_OR_RETURN(ProjectStage stage, ProjectStage::Create(device, bindings));
  LPIR_VK_RETURN_IF_ERROR(RunOnce(
      device, [&](CommandBuffer& cmd) { return stage.Record(cmd, uint32_t(n)); }, gpu_ns));

  f.point_pixel.resize(n);
  f.pixel_key.resize(pixels);
  f.pixel_point.resize(pixels);
  LPIR_VK_RETURN_IF_ERROR(transfer.Download(point_pixel, f.point_pixel.data(), per_point));
  LPIR_VK_RETURN_IF_ERROR(transfer.Download(pixel_key, f.pixel_key.data(), per_pixel));
  LPIR_VK_RETURN_IF_ERROR(transfer.Download(pixel_point, f.pixel_point.data(), per_pixel));
  return Status();
}

}  // namespace lpir::vk
