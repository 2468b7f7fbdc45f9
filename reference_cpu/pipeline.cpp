#include "reference_cpu/pipeline.h"

#include <chrono>

#include "reference_cpu/stages.h"

namespace lpir {
namespace {

// A stage's call with the arguments its parameter list takes: the four lists a table line may
// give (reference_cpu/stage_table.def).
void Call(void (*stage)(const Cloud&, const Params&, Frame&), const Cloud& cloud, const Params& p,
          const Tables&, Frame& f) {
  stage(cloud, p, f);
}
void Call(void (*stage)(const Cloud&, const Params&, const Tables&, Frame&), const Cloud& cloud,
          const Params& p, const Tables& t, Frame& f) {
  stage(cloud, p, t, f);
}
void Call(void (*stage)(const Params&, const Tables&, Frame&), const Cloud&, const Params& p,
          const Tables& t, Frame& f) {
  stage(p, t, f);
}
void Call(void (*stage)(const Params&, Frame&), const Cloud&, const Params& p, const Tables&,
          Frame& f) {
  stage(p, f);
}

}  // namespace

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
#define LPIR_STAGE(name, Type, parameters) Call(Type, cloud, p, tables, frame), lap();
#define LPIR_BUFFER LPIR_IGNORE
#define LPIR_HOST_BUFFER LPIR_IGNORE
#define LPIR_SCRATCH LPIR_IGNORE
#include "reference_cpu/stage_table.def"
}

}  // namespace lpir
