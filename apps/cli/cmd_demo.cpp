// lpir-gseg demo [--out DIR] [--seed N] [--backend B] [--runs N]: no data needed. Simulates an
// urban street seen by an HDL-64E, segments it (on Vulkan when a device can be set up), checks
// that the CPU reference gives the same bytes, scores the labels against the scene's truth (DG
// protocol), counts car points labelled ground, writes the scan, its labels and the pictures, and
// says where. Its timing keeps set-up apart from the steady state: the segmenter's construction
// (device, pipelines, buffers) and the first frame are stated alone; then kWarmupFrames frames
// untimed, then --runs frames timed, of which the median wall time a frame and the frames per
// second it gives are stated (and on Vulkan the median of the GPU timestamps).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "apps/cli/args.h"
#include "apps/cli/commands.h"
#include "apps/cli/exit_codes.h"
#include "apps/cli/sensor_args.h"
#include "apps/cli/thread_args.h"
#include "apps/cli/timing.h"
#include "apps/sim/scene.h"
#include "apps/viz/images.h"
#include "host/api/segmenter.h"
#include "host/eval/metrics.h"
#include "host/io/kitti_bin.h"
#include "host/io/label_file.h"
#include "host/io/output_paths.h"

namespace fs = std::filesystem;

namespace lpir {
namespace {

constexpr int kWarmupFrames = 3;  // after the first: caches, lazy allocations, clocks settle

const char kHelp[] =
    "usage: lpir-gseg demo [--out DIR (default demo_out)] [--seed N (default 1)]\n"
    "                      [--backend auto|vulkan|cpu (default auto)] [--runs N (default 20)]\n"
    "                      [--threads N] [--set NAME=VALUE ...]\n"
    "  Simulates a street, segments it, checks Vulkan against the CPU reference, scores it and\n"
    "  writes pictures. Timing: set-up (device, pipelines, buffers) and the first frame are\n"
    "  stated apart; then 3 warm-up frames, then N timed frames (1 to 1000): their median wall\n"
    "  time a frame, upload to download, and the frames per second it gives. --threads N: the\n"
    "  CPU backend's threads (default: the cores this process may run on).\n"
    "  (--opt VALUE and --opt=VALUE alike; -o --out, -b --backend)\n" LPIR_SET_HELP;

}  // namespace

int RunDemo(int argc, char** argv) {
  const Args args(argc, argv, {"--help"}, {"--out", "--seed", "--backend", "--runs", "--threads"},
                  {"--set"});
  if (args.Has("--help")) {
    std::fputs(kHelp, stdout);
    std::fputs(kExitCodesLine, stdout);
    return kExitOk;
  }
  SegmenterOptions segmenter_options;
  segmenter_options.backend = ParseBackend(args.Get("--backend", "auto"));
  segmenter_options.all_buffers = true;  // for the pictures
  segmenter_options.threads = ParseThreads(args);
  const std::string out = args.Get("--out", "demo_out");
  const double seed = args.GetNumber("--seed", 1);
  if (!(seed >= 0) || seed > 4294967295.0 || seed != double(uint32_t(seed)))
    throw std::invalid_argument("--seed must be a whole number in [0, 2^32)");
  const double runs = args.GetNumber("--runs", 20);
  if (!(runs >= 1 && runs <= 1000) || runs != double(int(runs)))
    throw std::invalid_argument("--runs must be a whole number from 1 to 1000");
  const SensorProfile sensor = LoadProfileWithSettings("hdl64e", args);
  LoadImages();  // a missing pictures' library stops the demo before any output
  MakeOutputFolder(out);

  SimOptions options;
  options.seed = uint32_t(seed);
  const SimScan scan = Simulate(sensor, options);
  const std::string bin = (fs::path(out) / "demo_scan.bin").string();
  const std::string truth_file = (fs::path(out) / "demo_scan_truth.label").string();
  WriteKittiBin(bin, scan.cloud);
  WriteLabelFile(truth_file, scan.labels);
  std::printf("simulated an urban street (seed %u) seen by an HDL-64E: %zu points -> %s\n",
              options.seed, scan.cloud.size(), bin.c_str());

  const Clock::time_point setup_start = Clock::now();
  Segmenter segmenter(sensor, segmenter_options);
  const double setup_ms = Ms(setup_start, Clock::now());
  if (segmenter_options.backend == Backend::kAuto && segmenter.backend() == Backend::kCpu)
    std::fprintf(stderr, "lpir-gseg demo: note: %s\n", segmenter.backend_note().c_str());
  const bool on_gpu = segmenter.backend() == Backend::kVulkan;
  const std::string on = on_gpu ? segmenter.backend_note() : "the CPU reference";

  const Clock::time_point first_start = Clock::now();
  const Labels first = segmenter.Segment(scan.cloud).label;
  const double first_ms = Ms(first_start, Clock::now());
  for (int k = 0; k < kWarmupFrames; ++k) segmenter.Segment(scan.cloud);
  std::vector<double> wall_ms, device_ms;
  const Frame* frame = nullptr;
  for (int k = 0; k < int(runs); ++k) {
    FrameTimes times;
    const Clock::time_point t0 = Clock::now();
    frame = &segmenter.Segment(scan.cloud, &times);
    wall_ms.push_back(Ms(t0, Clock::now()));
    device_ms.push_back(times.total_ms);
    if (frame->label != first)
      throw RefusedError("frame " + std::to_string(kWarmupFrames + 2 + k) + " on " + on +
                         " labels the same scan differently from the first");
  }
  std::vector<uint32_t> labels(frame->label.begin(), frame->label.end());
  const std::string pred = (fs::path(out) / "demo_scan.label").string();
  WriteLabelFile(pred, labels);
  const double median_ms = Median(wall_ms);
  std::printf("set-up on %s: %.1f ms (device, pipelines, buffers), then the first frame %.2f ms\n",
              on.c_str(), setup_ms, first_ms);
  std::printf(
      "steady state over %d frames after %d warm-up frames: median %.2f ms a frame (wall time, "
      "upload to download), %.1f frames/s",
      int(runs), kWarmupFrames, median_ms, median_ms > 0 ? 1000.0 / median_ms : 0.0);
  if (on_gpu) std::printf("; GPU timestamps median %.2f ms", Median(device_ms));
  std::printf(" -> %s\n", pred.c_str());

  const Scores s = ScoreCounts(CountFrame(Protocol::kDG, frame->label, scan.labels, nullptr));
  size_t car_points = 0, car_ground = 0;
  for (size_t i = 0; i < scan.labels.size(); ++i) {
    if ((scan.labels[i] & 0xFFFF) != SkClass::kCar) continue;
    ++car_points;
    car_ground += frame->label[i];
  }
  if (on_gpu) {
    Segmenter reference(sensor, SegmenterOptions::For(Backend::kCpu));
    const Frame& cpu = reference.Segment(scan.cloud);
    if (cpu.label != frame->label || cpu.why != frame->why)
      throw RefusedError("the CPU reference labels this scan differently from Vulkan");
    std::printf("the CPU reference gives the same labels, byte for byte\n");
  }
  std::printf(
      "against the scene's truth (DG protocol): precision %.2f %%, recall %.2f %%, "
      "F1 %.2f %%, ground IoU %.2f %%\n",
      100 * s.precision, 100 * s.recall, 100 * s.f1, 100 * s.iou);
  std::printf("car points labelled ground: %zu of %zu\n", car_ground, car_points);

  std::vector<uint8_t> truth(scan.labels.size());
  for (size_t i = 0; i < truth.size(); ++i) truth[i] = IsGroundClass(scan.labels[i]) ? 1 : 0;
  const std::string images = (fs::path(out) / "images").string();
  const std::vector<std::string> written =
      WriteImages(images, "demo_scan", scan.cloud, *frame, segmenter.params(), &truth);
  std::printf("wrote %zu pictures to %s/ (start with demo_scan_bev.png: %s)\n", written.size(),
              images.c_str(), kScoredColours);
  return kExitOk;
}

}  // namespace lpir
