#include "reference_cpu/pipeline.h"

#include <chrono>

#include "reference_cpu/stages.h"

namespace lpir {

const char* const kStageNames[kStageCount] = {"prepare",        "project",      "grid_reduce",
                                              "coarse_segment", "feature_maps", "classify_pixels",
                                              "fuse",           "grow",         "back_project"};

void RunReference(const Cloud& cloud, const Params& params, const Tables& tables, Frame& frame,
                  FrameTimes* times) {
  Params p = params;
  p.has_ring = cloud.ring.empty() ? 0u : 1u;
  using Clock = std::chrono::steady_clock;
  if (times) *times = FrameTimes();
  auto t0 = Clock::now();
  int stage = 0;
  auto lap = [&] {
    const auto t1 = Clock::now();
    if (times) {
      times->stage_ms[stage] = std::chrono::duration<double, std::milli>(t1 - t0).count();
      times->total_ms += times->stage_ms[stage];
    }
    t0 = t1;
    ++stage;
  };
  Prepare(cloud, p, frame), lap();
  Project(cloud, p, tables, frame), lap();
  GridReduce(p, tables, frame), lap();
  CoarseSegment(cloud, p, tables, frame), lap();
  FeatureMaps(p, frame), lap();
  ClassifyPixels(p, frame), lap();
  Fuse(p, frame), lap();
  Grow(p, frame), lap();
  BackProject(p, frame), lap();
}

}  // namespace lpir
