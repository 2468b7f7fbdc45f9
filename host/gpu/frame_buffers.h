// What the frame pipeline hands every Vulkan stage: one frame's device buffers, named as in
// reference_cpu/stage_table.def, and the frame's size. A stage binds its kernel to them once
// (XStage::Create(device, const FrameBuffers&)) and records against the size every frame
// (XStage::Record(cmd, const FrameSize&)).
#pragma once
#include <cstdint>

#include "host/vk/buffer.h"
#include "reference_cpu/frame.h"

namespace lpir::vk {

// The tables' device buffers (lpir::Tables, as floats), shared by the frames in flight.
struct TableBuffers {
  Buffer column_dir, beam_bound, beam_origin, ring_bound2, ring_inner;
};

// One frame's device buffers: the inputs, then a buffer per LPIR_BUFFER and LPIR_SCRATCH line of
// the table, each holding the table's layout for the pipeline's largest frame.
struct FrameBuffers {
  const TableBuffers* tables = nullptr;
  Buffer params;  // one Params (uniform)
  Buffer points;  // vec4 x, y, z, raw intensity per point (the cloud)
  Buffer ring;    // int32 per point (read only when Params::has_ring)
#define LPIR_STAGE LPIR_IGNORE
#define LPIR_BUFFER(stage, name, type, per, stride) Buffer name;
#define LPIR_HOST_BUFFER LPIR_IGNORE
#define LPIR_SCRATCH(stage, name, type, per, stride, extra) Buffer name;
#include "reference_cpu/stage_table.def"
};

// A frame's extent as the stages' Record calls take it.
struct FrameSize {
  uint32_t n = 0;                 // points
  uint32_t width = 0, beams = 0;  // the image (Params::width, Params::beams)
  uint32_t pixels = 0;            // width * beams
  uint32_t cells = 0;             // CellCount(params)
};

}  // namespace lpir::vk
