// project, on Vulkan: the kernel's bindings and its recording.
#include "host/gpu/project.h"

#include <cstdint>

namespace lpir::vk {
namespace {
#include "shaders/project.spv.h"  // kProjectSpv, compiled from shaders/project.comp at build time

struct Push {
  uint32_t n;
};
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

}  // namespace lpir::vk
