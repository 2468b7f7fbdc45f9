#include "reference_cpu/pipeline.h"

#include <chrono>

#include "reference_cpu/stages.h"

namespace lpir {
namespace {

// A stage's call with the arguments its parameter list takes: the four lists a table line may
// give (reference_cpu/stage_table.def).
void Call(void (*stage)(const Cloud&, const Params&, Frame&, Threads), const Cloud& cloud,
          const Params& p, const Tables&, Frame& f, Threads threads) {
  stage(cloud, p, f, threads);
}
void Call(void (*stage)(const Cloud&, const Params&, const Tables&, Frame&, Threads),
          const Cloud& cloud, const Params& p, const Tables& t, Frame& f, Threads threads) {
  stage(cloud, p, t, f, threads);
}
void Call(void (*stage)(const Params&, const Tables&, Frame&, Threads), const Cloud&,
          const Params& p, const Tables& t, Frame& f, Threads threads) {
  stage(p, t, f, threads);
}
void Call(void (*stage)(const Params&, Frame&, Threads), const Cloud&, const Params& p,
          const Tables&, Frame& f, Threads threads) {
  stage(p, f, threads);
}

}  // namespace

void RunReference(const Cloud& cloud, const Params& params, const Tables& tables, Frame& frame,
                  FrameTimes* times, Threads threads) {
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
#define LPIR_STAGE(name, Type, parameters) Call(Type, cloud, p, tables, frame, threads), lap();
#define LPIR_BUFFER LPIR_IGNORE
#define LPIR_HOST_BUFFER LPIR_IGNORE
#define LPIR_SCRATCH LPIR_IGNORE
#include "reference_cpu/stage_table.def"
}

}  // namespace lpir
