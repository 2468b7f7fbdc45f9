// The CPU reference, single-threaded, on the six consecutive SemanticKITTI 00 scans: one
// benchmark per scan, each repetition one whole frame (every stage), 20 repetitions so the
// reported median is over 20 runs. Per-stage milliseconds are counters (mean per frame).
// Run: build/reference_bench  (data from ../shared/data; absent -> nothing to run, says so).
#include <benchmark/benchmark.h>

#include <cstdio>
#include <filesystem>
#include <string>

#include "bench/kitti_scans.h"
#include "host/api/segmenter.h"
#include "host/io/kitti_bin.h"
#include "host/io/sensor_profile.h"

namespace lpir {
namespace {

void BM_Reference(benchmark::State& state, const std::string& path) {
  const Cloud cloud = ReadKittiBin(path);
  SegmenterOptions options = SegmenterOptions::For(Backend::kCpu);
  options.threads = 1;
  Segmenter segmenter(LoadSensorProfile("hdl64e", LPIR_SENSORS_DIR), options);
  // Check before timing: every point labelled, some ground, some non-ground.
  const Frame& check = segmenter.Segment(cloud);
  size_t ground = 0;
  for (uint8_t l : check.label) ground += l;
  if (check.label.size() != cloud.size() || ground == 0 || ground == cloud.size()) {
    state.SkipWithError("reference output failed its sanity check");
    return;
  }
  FrameTimes times, sum;
  for (auto _ : state) {
    segmenter.Segment(cloud, &times);
    for (int k = 0; k < kStageCount; ++k) sum.stage_ms[k] += times.stage_ms[k];
  }
  for (int k = 0; k < kStageCount; ++k)
    state.counters[std::string(kStageNames[k]) + "_ms"] =
        benchmark::Counter(sum.stage_ms[k] / double(state.iterations()));
  state.counters["points"] = double(cloud.size());
}

}  // namespace
}  // namespace lpir

int main(int argc, char** argv) {
  const std::vector<std::string> scans = lpir::bench::Kitti00Scans("reference_bench");
  if (scans.empty()) return 0;
  for (const std::string& path : scans) {
    benchmark::RegisterBenchmark(("BM_Reference/" + lpir::bench::ScanLabel(path)).c_str(),
                                 lpir::BM_Reference, path)
        ->Unit(benchmark::kMillisecond)
        ->Iterations(1)
        ->Repetitions(20)
        ->ReportAggregatesOnly(true);
  }
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
