// lpir-gseg demo [--out DIR] [--seed N] [--backend B]: no data needed. Simulates an urban street
// seen by an HDL-64E, segments it (on Vulkan when a device can be set up), checks that the CPU
// reference gives the same bytes, scores the labels against the scene's truth (DG protocol),
// counts car points labelled ground, writes the scan, its labels and the pictures, and says where.
#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "apps/cli/args.h"
#include "apps/cli/commands.h"
#include "apps/sim/scene.h"
#include "apps/viz/images.h"
#include "host/eval/metrics.h"
#include "host/io/kitti_bin.h"
#include "host/io/label_file.h"
#include "host/io/sensor_profile.h"
#include "host/segmenter.h"

namespace fs = std::filesystem;

namespace lpir {

int RunDemo(int argc, char** argv) {
  const Args args(argc, argv, {"--help"}, {"--out", "--seed", "--backend"});
  if (args.Has("--help")) {
    std::fputs(
        "usage: lpir-gseg demo [--out DIR (default demo_out)] [--seed N (default 1)]\n"
        "                      [--backend auto|vulkan|cpu (default auto)]\n",
        stdout);
    return 0;
  }
  SegmenterOptions segmenter_options;
  segmenter_options.backend = ParseBackend(args.Get("--backend", "auto"));
  segmenter_options.all_buffers = true;  // for the pictures
  const std::string out = args.Get("--out", "demo_out");
  const double seed = args.GetNumber("--seed", 1);
  if (!(seed >= 0) || seed > 4294967295.0 || seed != double(uint32_t(seed)))
    throw std::invalid_argument("--seed must be a whole number in [0, 2^32)");
  fs::create_directories(out);

  const SensorProfile sensor = LoadSensorProfile("hdl64e", SensorsDir());
  SimOptions options;
  options.seed = uint32_t(seed);
  const SimScan scan = Simulate(sensor, options);
  const std::string bin = (fs::path(out) / "demo_scan.bin").string();
  const std::string truth_file = (fs::path(out) / "demo_scan_truth.label").string();
  WriteKittiBin(bin, scan.cloud);
  WriteLabelFile(truth_file, scan.labels);
  std::printf("simulated an urban street (seed %u) seen by an HDL-64E: %zu points -> %s\n",
              options.seed, scan.cloud.size(), bin.c_str());

  Segmenter segmenter(sensor, segmenter_options);
  if (segmenter_options.backend == Backend::kAuto && segmenter.backend() == Backend::kCpu)
    std::fprintf(stderr, "lpir-gseg demo: note: %s\n", segmenter.backend_note().c_str());
  FrameTimes times;
  const Frame& frame = segmenter.Segment(scan.cloud, &times);
  std::vector<uint32_t> labels(frame.label.begin(), frame.label.end());
  const std::string pred = (fs::path(out) / "demo_scan.label").string();
  WriteLabelFile(pred, labels);

  const Scores s = ScoreCounts(CountFrame(Protocol::kDG, frame.label, scan.labels, nullptr));
  size_t car_points = 0, car_ground = 0;
  for (size_t i = 0; i < scan.labels.size(); ++i) {
    if ((scan.labels[i] & 0xFFFF) != SkClass::kCar) continue;
    ++car_points;
    car_ground += frame.label[i];
  }
  const bool on_gpu = segmenter.backend() == Backend::kVulkan;
  std::printf("segmented in %.2f ms (%s) on %s -> %s\n", times.total_ms,
              on_gpu ? "GPU timestamps" : "wall time",
              on_gpu ? segmenter.backend_note().c_str() : "the CPU reference", pred.c_str());
  if (on_gpu) {
    Segmenter reference(sensor, SegmenterOptions::For(Backend::kCpu));
    const Frame& cpu = reference.Segment(scan.cloud);
    if (cpu.label != frame.label || cpu.why != frame.why)
      throw std::runtime_error("the CPU reference labels this scan differently from Vulkan");
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
      WriteImages(images, "demo_scan", scan.cloud, frame, segmenter.params(), &truth);
  std::printf(
      "wrote %zu pictures to %s/ (start with demo_scan_bev.png: TP green, TN red, "
      "FP blue, FN yellow)\n",
      written.size(), images.c_str());
  return 0;
}

}  // namespace lpir
