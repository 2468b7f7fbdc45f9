// project, on Vulkan: shaders/project.comp behind the generic dispatcher. ProjectStage
// is bound once to the frame's buffers and recorded every frame.
#pragma once
#include <cstdint>

#include "host/gpu/frame_buffers.h"
#include "host/vk/buffer.h"
#include "host/vk/command_buffer.h"
#include "host/vk/device.h"
#include "host/vk/kernel.h"
#include "host/vk/result.h"

namespace lpir::vk {

// The bindings of shaders/project.comp.
struct ProjectBuffers {
  const Buffer* params = nullptr;       // one Params (uniform); has_ring says whether ring is read
  const Buffer* points = nullptr;       // vec4 x, y, z, raw intensity per point (the raw cloud)
  const Buffer* ring = nullptr;         // int32 per point; any buffer when has_ring is 0
  const Buffer* flags = nullptr;        // uint32 per point, prepare
  const Buffer* r2 = nullptr;           // float per point, prepare
  const Buffer* column_dir = nullptr;   // Tables::column_dir, 2 * width floats
  const Buffer* beam_bound = nullptr;   // Tables::beam_bound, beams - 1 floats
  const Buffer* beam_origin = nullptr;  // Tables::beam_origin, beams - 1 floats
  const Buffer* point_pixel = nullptr;  // out: uint32 per point
  const Buffer* pixel_key = nullptr;    // out: uint32 per pixel (exactly width * beams of them:
  const Buffer* pixel_point = nullptr;  // out: uint32 per pixel  Record fills the whole buffers)
  const Buffer* project_exact = nullptr;  // scratch: ProjectStage::ExactListBytes(n)
};

class ProjectStage {
 public:
  static constexpr uint32_t kLocalSize = 64;
  // Points per invocation of pass 0 in the CPU shape (host/vk/shape.h; the GPU shape's is 1).
  static constexpr uint32_t kCpuItems = 32;

  // The exact list for up to n points: four header words and an index per point.
  static VkDeviceSize ExactListBytes(uint64_t n) { return 4 * (4 + n); }

  static Result<ProjectStage> Create(const Device& device, const ProjectBuffers& buffers);
  // Bound to one frame of a frame pipeline (host/gpu/frame_buffers.h).
  static Result<ProjectStage> Create(const Device& device, const FrameBuffers& b) {
    const TableBuffers& t = *b.tables;
    return Create(device,
                  ProjectBuffers{&b.params, &b.points, &b.ring, &b.flags, &b.r2, &t.column_dir,
                                 &t.beam_bound, &t.beam_origin, &b.point_pixel, &b.pixel_key,
                                 &b.pixel_point, &b.project_exact});
  }

  // Records the clear of pixel_key and pixel_point to kNone and of the exact list's header, the
  // pixel pass 0, the exact pass 1 over the listed points (indirect), and the winner pass 2 over
  // n points, with barriers between them. No barrier before the clear or after the last
  // dispatch: the caller orders them with the stages around (prepare's writes must be visible
  // to compute and the clear must not overtake earlier reads of the pixel buffers).
  Status Record(CommandBuffer& cmd, uint32_t n) const;
  // The same over a frame of `size` (the frame pipeline's call).
  Status Record(CommandBuffer& cmd, const FrameSize& size) const { return Record(cmd, size.n); }

  // The kernel's shape (host/vk/shape.h), read from LPIR_VK_SHAPE or the device at Create.
  Shape shape() const { return kernel_.shape(); }

 private:
  ProjectStage(Kernel kernel, const Buffer* pixel_key, const Buffer* pixel_point,
               const Buffer* project_exact)
      : kernel_(std::move(kernel)),
        pixel_key_(pixel_key),
        pixel_point_(pixel_point),
        project_exact_(project_exact) {}

  Kernel kernel_;
  const Buffer* pixel_key_;
  const Buffer* pixel_point_;
  const Buffer* project_exact_;
};

}  // namespace lpir::vk
