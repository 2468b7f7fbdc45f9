// The whole method on the CPU: stages 1-9 in order, every buffer kept for inspection.
#pragma once
#include "reference_cpu/cloud.h"
#include "reference_cpu/frame.h"
#include "reference_cpu/params.h"

namespace lpir {

// Time of one frame in milliseconds: stage by stage (kStageNames order), the cloud's upload,
// the labels' download, and the whole frame. The CPU reference measures wall time (it uploads and
// downloads nothing: 0); Vulkan measures GPU timestamps (all -1 on a device without them).
constexpr int kStageCount = 9;  // stages 1-9, in run order (kStageNames)

struct FrameTimes {
  double upload_ms = 0, stage_ms[kStageCount] = {}, download_ms = 0, total_ms = 0;
};

// Runs stages 1-9; `times` (optional) receives per-stage wall times.
void RunReference(const Cloud& cloud, const Params& params, const Tables& tables, Frame& frame,
                  FrameTimes* times = nullptr);

extern const char* const kStageNames[kStageCount];

}  // namespace lpir
