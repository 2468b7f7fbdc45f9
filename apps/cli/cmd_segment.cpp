// lpir-gseg segment INPUT... --sensor NAME --out DIR [options]: labels every point of every input
// cloud (files, or folders of them) and writes DIR/<stem>.label, or the cloud with a label field.
// On Vulkan the next file is read while the device works on the previous ones (frames in
// flight). A file that cannot be read or segmented is reported and skipped; the exit code is then
// 1 and the last line counts the failures.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <deque>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "apps/cli/args.h"
#include "apps/cli/commands.h"
#include "apps/cli/progress.h"
#include "apps/cli/truth.h"
#include "apps/viz/images.h"
#include "host/io/cloud_file.h"
#include "host/io/io_error.h"
#include "host/io/label_file.h"
#include "host/io/sensor_profile.h"
#include "host/segmenter.h"

namespace fs = std::filesystem;

namespace lpir {
namespace {

const char kHelp[] =
    "usage: lpir-gseg segment INPUT... --sensor NAME --out DIR [options]\n"
    "  INPUT            cloud files (.bin KITTI, .pcd, .ply) or folders of them\n"
    "  --sensor NAME    sensor profile (hdl64e, hdl32e, vlp32c, os1-64, ...) or a profile file\n"
    "  --out DIR        where DIR/<stem>.label (uint32 per point: 1 ground, 0 non-ground) go\n"
    "  --format F       label (default), pcd or ply: the cloud with a label field instead\n"
    "  --nuscenes       .bin files hold 5 floats per point (x y z intensity ring); files named\n"
    "                   *.pcd.bin are read that way without it, other .bin files as KITTI\n"
    "  --images         also write pictures of every stage to DIR/images/\n"
    "  --gt PATH        ground truth .label file or folder (matched by stem) for the pictures\n"
    "  --max-points N   largest cloud accepted (default: the sensor's beams x width x 2, one\n"
    "                   point a pixel and as many second returns; 262144 for hdl64e)\n"
    "  --backend B      vulkan (any device, lavapipe included), cpu (the reference) or auto\n"
    "                   (default: Vulkan on a GPU, else the reference with a note saying why;\n"
    "                   a CPU driver such as lavapipe only with vulkan or --device). Both give\n"
    "                   the same bytes\n"
    "  --device D       Vulkan device: index or part of its name (`lpir-gseg devices` lists them)\n"
    "  --batch N        Vulkan: N frames a command buffer, interleaved pass by pass (offline\n"
    "                   relabelling of a folder; default 1)\n"
    "  --timings        per-stage times of every frame (GPU timestamps on Vulkan, wall time on\n"
    "                   the CPU) and their medians at the end\n"
    "  --quiet          no per-frame lines\n"
    "Environment: LPIR_VK_VALIDATION=1 turns the Vulkan validation layer on.\n";

// Input clouds: files as given, folders expanded to their cloud files in name order.
std::vector<std::string> ListInputs(const std::vector<std::string>& inputs) {
  std::vector<std::string> files;
  for (const std::string& in : inputs) {
    std::error_code ec;
    if (fs::is_directory(in, ec)) {
      std::vector<std::string> found;
      for (const auto& entry : fs::directory_iterator(in, ec))
        if (entry.is_regular_file() && IsCloudFile(entry.path().string()))
          found.push_back(entry.path().string());
      if (found.empty()) throw std::invalid_argument(in + ": folder holds no cloud files");
      std::sort(found.begin(), found.end());
      files.insert(files.end(), found.begin(), found.end());
    } else {
      files.push_back(in);  // a missing file is reported when it is read
    }
  }
  return files;
}

// One file between its reading and its writing.
struct Job {
  std::string file, stem;
  Cloud cloud;
};

double Median(std::vector<double> v) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  const size_t h = v.size() / 2;
  return v.size() % 2 ? v[h] : 0.5 * (v[h - 1] + v[h]);
}

// Per-stage times of every frame, printed as the frames finish and summarised at the end.
class Timings {
 public:
  explicit Timings(bool gpu) : gpu_(gpu) {}
  void Add(const std::string& stem, const FrameTimes& t) {
    std::printf("%s times (ms):", stem.c_str());
    if (gpu_) std::printf(" upload %.3f", t.upload_ms);
    for (int k = 0; k < kStageCount; ++k) std::printf(" %s %.3f", kStageNames[k], t.stage_ms[k]);
    if (gpu_) std::printf(" download %.3f", t.download_ms);
    std::printf(" total %.3f\n", t.total_ms);
    upload_.push_back(t.upload_ms), download_.push_back(t.download_ms),
        total_.push_back(t.total_ms);
    for (int k = 0; k < kStageCount; ++k) stage_[k].push_back(t.stage_ms[k]);
  }
  void PrintMedians() const {
    if (total_.empty()) return;
    std::printf("median over %zu frame%s (%s, ms):", total_.size(), total_.size() == 1 ? "" : "s",
                gpu_ ? "GPU timestamps" : "CPU wall time");
    if (gpu_) std::printf(" upload %.3f", Median(upload_));
    for (int k = 0; k < kStageCount; ++k)
      std::printf(" %s %.3f", kStageNames[k], Median(stage_[k]));
    if (gpu_) std::printf(" download %.3f", Median(download_));
    std::printf(" total %.3f\n", Median(total_));
  }

 private:
  bool gpu_;
  std::vector<double> upload_, download_, total_, stage_[kStageCount];
};

}  // namespace

int RunSegment(int argc, char** argv) {
  const Args args(argc, argv, {"--images", "--nuscenes", "--quiet", "--timings", "--help"},
                  {"--sensor", "--out", "--format", "--gt", "--max-points", "--backend", "--device",
                   "--batch"});
  if (args.Has("--help")) {
    std::fputs(kHelp, stdout);
    return 0;
  }
  if (args.positional().empty())
    throw std::invalid_argument("no INPUT given\n" + std::string(kHelp));
  const std::string format = args.Get("--format", "label");
  if (format != "label" && format != "pcd" && format != "ply")
    throw std::invalid_argument("--format must be label, pcd or ply, not '" + format + "'");
  const double max_points = args.GetNumber("--max-points", 0);  // 0: from the sensor profile
  if (args.Has("--max-points") && (!(max_points >= 1) || max_points > 1e8))
    throw std::invalid_argument("--max-points must be between 1 and 1e8");
  const std::string out_dir = args.Require("--out");
  SegmenterOptions options;
  options.backend = ParseBackend(args.Get("--backend", "auto"));
  options.device = args.Get("--device");
  options.max_points = size_t(max_points);
  options.all_buffers = args.Has("--images");  // the pictures show every stage
  const double batch = args.GetNumber("--batch", 1);
  if (!(batch >= 1 && batch <= 64) || batch != double(uint32_t(batch)))
    throw std::invalid_argument("--batch must be a whole number from 1 to 64");
  options.batch = uint32_t(batch);
  const char* validation = std::getenv("LPIR_VK_VALIDATION");
  options.validation = validation && *validation && std::string(validation) != "0";
  const SensorProfile sensor = LoadSensorProfile(args.Require("--sensor"), SensorsDir());
  const std::vector<std::string> files = ListInputs(args.positional());
  Segmenter segmenter(sensor, options);
  if (options.backend == Backend::kAuto && segmenter.backend() == Backend::kCpu)
    std::fprintf(stderr, "lpir-gseg segment: note: %s\n", segmenter.backend_note().c_str());
  fs::create_directories(out_dir);
  ReadOptions read_options;
  if (args.Has("--nuscenes")) read_options.bin_layout = BinLayout::kNuScenes5;
  const bool quiet = args.Has("--quiet");
  const bool on_gpu = segmenter.backend() == Backend::kVulkan;

  std::printf("segmenting %zu file%s with sensor '%s' on %s\n", files.size(),
              files.size() == 1 ? "" : "s", segmenter.sensor().name.c_str(),
              on_gpu ? segmenter.backend_note().c_str() : "the CPU reference");
  Progress progress(files.size(), files.size() > 1);
  Timings timings(on_gpu);
  size_t failures = 0;
  auto report = [&](const std::string& file, const std::exception& e) {
    ++failures;
    if (dynamic_cast<const IoError*>(&e))  // names the file already
      std::fprintf(stderr, "lpir-gseg segment: error: %s\n", e.what());
    else
      std::fprintf(stderr, "lpir-gseg segment: error: %s: %s\n", file.c_str(), e.what());
  };
  // Collects the oldest frame in flight and writes what it gives.
  std::deque<Job> jobs;
  auto finish = [&] {
    const Job job = std::move(jobs.front());
    jobs.pop_front();
    try {
      FrameTimes times;
      const Frame& frame = segmenter.Collect(&times);
      size_t ground = 0, invalid = 0;
      for (uint32_t i = 0; i < frame.n; ++i) {
        ground += frame.label[i];
        invalid += frame.why[i] == kWhyInvalid;
      }
      if (format == "label") {
        std::vector<uint32_t> labels(frame.label.begin(), frame.label.end());
        WriteLabelFile((fs::path(out_dir) / (job.stem + ".label")).string(), labels);
      } else {
        WriteLabelledCloud((fs::path(out_dir) / (job.stem + "." + format)).string(), job.cloud,
                           frame.label, format == "pcd" ? CloudFormat::kPcd : CloudFormat::kPly);
      }
      if (args.Has("--images")) {
        std::vector<uint8_t> truth;
        if (args.Has("--gt")) truth = LoadTruth(args.Get("--gt"), job.stem, job.cloud.size());
        WriteImages((fs::path(out_dir) / "images").string(), job.stem, job.cloud, frame,
                    segmenter.params(), truth.empty() ? nullptr : &truth);
      }
      if (!quiet) {
        std::printf("%s: %zu points, %.1f %% ground, %.2f ms", job.stem.c_str(), job.cloud.size(),
                    job.cloud.size() ? 100.0 * double(ground) / double(job.cloud.size()) : 0.0,
                    times.total_ms);
        if (invalid)
          std::printf(" (%zu invalid points: NaN/Inf, at the origin or out of range; non-ground)",
                      invalid);
        std::printf("\n");
      }
      if (args.Has("--timings")) timings.Add(job.stem, times);
    } catch (const std::exception& e) {
      report(job.file, e);
    }
    progress.Step(job.stem);
  };
  for (const std::string& file : files) {
    Job job{file, fs::path(file).stem().string(), {}};
    try {
      job.cloud = ReadCloud(file, read_options);
      while (!segmenter.CanSubmit()) finish();
      segmenter.Submit(job.cloud);
      jobs.push_back(std::move(job));
    } catch (const std::exception& e) {
      report(file, e);
      progress.Step(job.stem);
    }
  }
  while (!jobs.empty()) finish();
  if (args.Has("--timings")) timings.PrintMedians();
  if (failures) {
    std::fprintf(stderr, "lpir-gseg segment: %zu of %zu files failed\n", failures, files.size());
    return 1;
  }
  std::printf("wrote %zu %s file%s to %s\n", files.size(), format.c_str(),
              files.size() == 1 ? "" : "s", out_dir.c_str());
  return 0;
}

}  // namespace lpir
