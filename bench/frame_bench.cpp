// One whole frame, end to end (upload, every stage, download; Segmenter::Segment), on the CPU
// reference and on the Vulkan device (lavapipe unless LPIR_VK_DEVICE names another), on the six
// consecutive SemanticKITTI 00 scans: one benchmark per scan and backend, 20 repetitions, median
// reported. Before timing, each checks that its labels equal the CPU reference's byte for byte.
// Counters: the per-stage times (reference: wall time; Vulkan: GPU timestamps), mean per frame.
// The reference runs on one thread.
// Run: build/bench/frame_bench  (data from ../shared/data; absent -> nothing to run, says so).
#include <benchmark/benchmark.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <string>

#include "bench/kitti_scans.h"
#include "host/api/segmenter.h"
#include "host/io/kitti_bin.h"
#include "host/io/sensor_profile.h"

namespace lpir {
namespace {

void BM_Frame(benchmark::State& state, const std::string& path, Backend backend) {
  const Cloud cloud = ReadKittiBin(path);
  const SensorProfile sensor = LoadSensorProfile("hdl64e", LPIR_SENSORS_DIR);
  SegmenterOptions options = SegmenterOptions::For(backend);
  options.threads = 1;
  if (const char* device = std::getenv("LPIR_VK_DEVICE")) options.device = device;
  std::unique_ptr<Segmenter> segmenter;
  try {
    segmenter = std::make_unique<Segmenter>(sensor, options);
  } catch (const std::exception& e) {
    state.SkipWithError(e.what());
    return;
  }
  Segmenter reference(sensor, SegmenterOptions::For(Backend::kCpu));
  if (segmenter->Segment(cloud).label != reference.Segment(cloud).label) {
    state.SkipWithError("labels differ from the CPU reference's");
    return;
  }
  FrameTimes times, sum;
  for (auto _ : state) {
    segmenter->Segment(cloud, &times);
    for (int k = 0; k < kStageCount; ++k) sum.stage_ms[k] += times.stage_ms[k];
    sum.upload_ms += times.upload_ms, sum.download_ms += times.download_ms;
    sum.total_ms += times.total_ms;
  }
  const double n = double(state.iterations());
  for (int k = 0; k < kStageCount; ++k)
    state.counters[std::string(kStageNames[k]) + "_ms"] = benchmark::Counter(sum.stage_ms[k] / n);
  if (backend == Backend::kVulkan) {
    state.counters["upload_ms"] = benchmark::Counter(sum.upload_ms / n);
    state.counters["download_ms"] = benchmark::Counter(sum.download_ms / n);
    state.counters["gpu_total_ms"] = benchmark::Counter(sum.total_ms / n);
  }
  state.SetLabel(segmenter->backend_note());
}

}  // namespace
}  // namespace lpir

int main(int argc, char** argv) {
  const std::vector<std::string> scans = lpir::bench::Kitti00Scans("frame_bench");
  if (scans.empty()) return 0;
  for (const std::string& path : scans) {
    for (lpir::Backend backend : {lpir::Backend::kCpu, lpir::Backend::kVulkan}) {
      const std::string bench = std::string("BM_Frame/") +
                                (backend == lpir::Backend::kCpu ? "cpu" : "vulkan") + "/" +
                                lpir::bench::ScanLabel(path);
      benchmark::RegisterBenchmark(bench.c_str(), lpir::BM_Frame, path, backend)
          ->Unit(benchmark::kMillisecond)
          ->Iterations(1)
          ->Repetitions(20)
          ->ReportAggregatesOnly(true)
          ->UseRealTime();
    }
  }
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
