// The whole method on the CPU: every stage of reference_cpu/stage_table.def in order, every buffer
// kept for inspection.
#pragma once
#include <iterator>

#include "reference_cpu/cloud.h"
#include "reference_cpu/frame.h"
#include "reference_cpu/params.h"
#include "reference_cpu/threads.h"

namespace lpir {

// The stages' names in run order, one per LPIR_STAGE line of the table.
inline constexpr const char* kStageNames[] = {
#define LPIR_STAGE(name, Type, parameters) #name,
#define LPIR_BUFFER LPIR_IGNORE
#define LPIR_HOST_BUFFER LPIR_IGNORE
#define LPIR_SCRATCH LPIR_IGNORE
#include "reference_cpu/stage_table.def"
};
constexpr int kStageCount = int(std::size(kStageNames));

// Time of one frame in milliseconds: stage by stage (kStageNames order), the cloud's upload,
// the labels' download, and the whole frame. The CPU reference measures wall time (it uploads and
// downloads nothing: 0); Vulkan measures GPU timestamps (all -1 on a device without them).
struct FrameTimes {
  double upload_ms = 0, stage_ms[kStageCount] = {}, download_ms = 0, total_ms = 0;
};

// Runs every stage in order, each split over `threads` (the same bytes at any count: one runs the
// reference's loops on the calling thread); `times` (optional) receives per-stage wall times.
void RunReference(const Cloud& cloud, const Params& params, const Tables& tables, Frame& frame,
                  FrameTimes* times = nullptr, Threads threads = Threads());

}  // namespace lpir
