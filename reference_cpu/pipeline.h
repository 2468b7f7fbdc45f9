// The whole method on the CPU: stages 1-9 in order, every buffer kept for inspection.
#pragma once
#include "reference_cpu/cloud.h"
#include "reference_cpu/frame.h"
#include "reference_cpu/params.h"

namespace lpir {

struct StageTimes {
  double ms[9] = {};  // wall time of stages 1..9 (index 0 = prepare)
};

// Runs stages 1-9; `times` (optional) receives per-stage wall times.
void RunReference(const Cloud& cloud, const Params& params, const Tables& tables, Frame& frame,
                  StageTimes* times = nullptr);

extern const char* const kStageNames[9];

}  // namespace lpir
