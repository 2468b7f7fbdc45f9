#include "reference_cpu/pipeline.h"
namespace lpir {
const char* const kStageNames[9] = {"prepare",        "project",  "grid_reduce",
                                    "coarse_segment", "feature_maps", "classify_pixels",
                                    "fuse",           "grow",     "back_project"};
void RunReference(const Cloud& cloud, const Params&, const Tables&, Frame& frame, StageTimes*) {
  frame.n = uint32_t(cloud.size());
  frame.label.assign(cloud.size(), 0);
  frame.why.assign(cloud.size(), 0);
}
}  // namespace lpir
