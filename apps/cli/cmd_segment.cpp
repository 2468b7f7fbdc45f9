// lpir-gseg segment INPUT... --sensor NAME --out DIR [options]: labels every point of every input
// cloud (files, or folders of them) and writes DIR/<stem>.label, or the cloud with a label field.
// On Vulkan the next file is read while the device works on the previous ones (frames in
// flight). A file that cannot be read or segmented is reported and skipped; the exit code is then
// 1 and the last line (stderr) counts the failures. Output levels: --quiet prints errors only;
// the default adds the progress (stderr) and one summary line at the end (stdout); --verbose
// adds a line first naming the backend and a line per frame.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <deque>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "apps/cli/args.h"
#include "apps/cli/commands.h"
#include "apps/cli/exit_codes.h"
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
    "  --quiet          errors only (nothing on success)\n"
    "  --verbose        also a line first naming the backend, and a line per frame\n"
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

// Per-stage times of every frame, a line each as the frames finish and their medians at the end.
class Timings {
 public:
  explicit Timings(bool gpu) : gpu_(gpu) {}
  // Records a frame's times; returns its line.
  std::string Add(const std::string& stem, const FrameTimes& t) {
    std::string line = stem + " times (ms):";
    if (gpu_) line += Ms(" upload", t.upload_ms);
    for (int k = 0; k < kStageCount; ++k)
      line += Ms(std::string(" ") + kStageNames[k], t.stage_ms[k]);
    if (gpu_) line += Ms(" download", t.download_ms);
    line += Ms(" total", t.total_ms) + "\n";
    upload_.push_back(t.upload_ms), download_.push_back(t.download_ms),
        total_.push_back(t.total_ms);
    for (int k = 0; k < kStageCount; ++k) stage_[k].push_back(t.stage_ms[k]);
    return line;
  }
  // The medians' line ("" before any frame).
  std::string Medians() const {
    if (total_.empty()) return "";
    std::string line = "median over " + std::to_string(total_.size()) + " frame" +
                       (total_.size() == 1 ? "" : "s") + " (" +
                       (gpu_ ? "GPU timestamps" : "CPU wall time") + ", ms):";
    if (gpu_) line += Ms(" upload", Median(upload_));
    for (int k = 0; k < kStageCount; ++k)
      line += Ms(std::string(" ") + kStageNames[k], Median(stage_[k]));
    if (gpu_) line += Ms(" download", Median(download_));
    return line + Ms(" total", Median(total_)) + "\n";
  }

 private:
  static std::string Ms(const std::string& name, double ms) {
    char buf[32];
    std::snprintf(buf, sizeof(buf), " %.3f", ms);
    return name + buf;
  }

  bool gpu_;
  std::vector<double> upload_, download_, total_, stage_[kStageCount];
};

// What the command line asks for.
struct SegmentArgs {
  std::vector<std::string> inputs;
  std::string sensor, out_dir, format, gt;
  bool images = false, has_gt = false, quiet = false, verbose = false, timings = false;
  SegmenterOptions options;
  ReadOptions read;
};

// The command line's options, checked; std::invalid_argument names the bad one.
SegmentArgs ParseSegmentArgs(const Args& args) {
  SegmentArgs a;
  a.inputs = args.positional();
  if (a.inputs.empty()) throw std::invalid_argument("no INPUT given\n" + std::string(kHelp));
  a.format = args.Get("--format", "label");
  if (a.format != "label" && a.format != "pcd" && a.format != "ply")
    throw std::invalid_argument("--format must be label, pcd or ply, not '" + a.format + "'");
  const double max_points = args.GetNumber("--max-points", 0);  // 0: from the sensor profile
  if (args.Has("--max-points") && (!(max_points >= 1) || max_points > 1e8))
    throw std::invalid_argument("--max-points must be between 1 and 1e8");
  a.out_dir = args.Require("--out");
  a.options.backend = ParseBackend(args.Get("--backend", "auto"));
  a.options.device = args.Get("--device");
  a.options.max_points = size_t(max_points);
  a.images = args.Has("--images");
  a.options.all_buffers = a.images;  // the pictures show every stage
  const double batch = args.GetNumber("--batch", 1);
  if (!(batch >= 1 && batch <= 64) || batch != double(uint32_t(batch)))
    throw std::invalid_argument("--batch must be a whole number from 1 to 64");
  a.options.batch = uint32_t(batch);
  const char* validation = std::getenv("LPIR_VK_VALIDATION");
  a.options.validation = validation && *validation && std::string(validation) != "0";
  a.sensor = args.Require("--sensor");
  if (args.Has("--nuscenes")) a.read.bin_layout = BinLayout::kNuScenes5;
  a.has_gt = args.Has("--gt");
  a.gt = args.Get("--gt");
  a.quiet = args.Has("--quiet");
  a.verbose = args.Has("--verbose");
  if (a.quiet && a.verbose) throw std::invalid_argument("--quiet and --verbose exclude each other");
  a.timings = args.Has("--timings");
  return a;
}

// The files through one segmenter, frames in flight: each read while the device works on the
// ones before, collected oldest first, its labels (and pictures) written, a failure reported
// and counted.
class SegmentRun {
 public:
  SegmentRun(const SegmentArgs& a, Segmenter& segmenter, size_t files)
      : a_(a),
        segmenter_(segmenter),
        progress_(files, files > 1 && !a.quiet),
        timings_(segmenter.backend() == Backend::kVulkan) {}

  // Reads `file` and submits it, first collecting frames until the segmenter takes one more.
  void Submit(const std::string& file) {
    Job job{file, fs::path(file).stem().string(), {}};
    try {
      job.cloud = ReadCloud(file, a_.read);
      while (!segmenter_.CanSubmit()) Finish();
      segmenter_.Submit(job.cloud);
      jobs_.push_back(std::move(job));
    } catch (const std::exception& e) {
      Report(file, e);
      progress_.Step();
    }
  }

  // Collects every frame still in flight; returns the files that failed.
  size_t FinishAll() {
    while (!jobs_.empty()) Finish();
    if (a_.timings) progress_.Print(stdout, timings_.Medians());
    return failures_;
  }

  // Prints a line above the progress.
  void Print(std::FILE* to, const std::string& text) { progress_.Print(to, text); }

  size_t frames() const { return frames_; }
  size_t invalid() const { return invalid_; }

 private:
  void Report(const std::string& file, const std::exception& e) {
    ++failures_;
    if (dynamic_cast<const IoError*>(&e))  // names the file already
      progress_.Print(stderr, std::string("lpir-gseg segment: error: ") + e.what() + "\n");
    else
      progress_.Print(stderr, "lpir-gseg segment: error: " + file + ": " + e.what() + "\n");
  }

  // Collects the oldest frame in flight and writes what it gives.
  void Finish() {
    const Job job = std::move(jobs_.front());
    jobs_.pop_front();
    try {
      FrameTimes times;
      const Frame& frame = segmenter_.Collect(&times);
      Write(job, frame);
      size_t ground = 0, invalid = 0;
      for (uint32_t i = 0; i < frame.n; ++i) {
        ground += frame.label[i];
        invalid += frame.why[i] == kWhyInvalid;
      }
      ++frames_;
      invalid_ += invalid;
      std::string lines;
      if (a_.verbose) lines += FrameLine(job, ground, invalid, times);
      if (a_.timings) lines += timings_.Add(job.stem, times);
      if (!lines.empty()) progress_.Print(stdout, lines);
      progress_.Step(job.cloud.size(), ground);
    } catch (const std::exception& e) {
      Report(job.file, e);
      progress_.Step();
    }
  }

  // The labels as a .label file or a labelled cloud, and with --images the pictures.
  void Write(const Job& job, const Frame& frame) const {
    const fs::path out(a_.out_dir);
    if (a_.format == "label") {
      std::vector<uint32_t> labels(frame.label.begin(), frame.label.end());
      WriteLabelFile((out / (job.stem + ".label")).string(), labels);
    } else {
      WriteLabelledCloud((out / (job.stem + "." + a_.format)).string(), job.cloud, frame.label,
                         a_.format == "pcd" ? CloudFormat::kPcd : CloudFormat::kPly);
    }
    if (!a_.images) return;
    std::vector<uint8_t> truth;
    if (a_.has_gt) truth = LoadTruth(a_.gt, job.stem, job.cloud.size());
    WriteImages((out / "images").string(), job.stem, job.cloud, frame, segmenter_.params(),
                truth.empty() ? nullptr : &truth);
  }

  // "<stem>: N points, G % ground, T ms", and the invalid points when there are any.
  static std::string FrameLine(const Job& job, size_t ground, size_t invalid,
                               const FrameTimes& times) {
    const size_t n = job.cloud.size();
    char buf[160];
    std::snprintf(buf, sizeof(buf), "%s: %zu points, %.1f %% ground, %.2f ms", job.stem.c_str(), n,
                  n ? 100.0 * double(ground) / double(n) : 0.0, times.total_ms);
    std::string line = buf;
    if (invalid) line += " (" + std::to_string(invalid) + " invalid)";
    return line + "\n";
  }

  const SegmentArgs& a_;
  Segmenter& segmenter_;
  Progress progress_;
  Timings timings_;
  std::deque<Job> jobs_;
  size_t failures_ = 0;
  size_t frames_ = 0;   // segmented and written
  size_t invalid_ = 0;  // points of those frames labelled invalid
};

}  // namespace

int RunSegment(int argc, char** argv) {
  const Args args(argc, argv,
                  {"--images", "--nuscenes", "--quiet", "--verbose", "--timings", "--help"},
                  {"--sensor", "--out", "--format", "--gt", "--max-points", "--backend", "--device",
                   "--batch"});
  if (args.Has("--help")) {
    std::fputs(kHelp, stdout);
    std::fputs(kExitCodesLine, stdout);
    return kExitOk;
  }
  const SegmentArgs a = ParseSegmentArgs(args);
  const SensorProfile sensor = LoadSensorProfile(a.sensor, SensorsDir());
  const std::vector<std::string> files = ListInputs(a.inputs);
  Segmenter segmenter(sensor, a.options);
  if (!a.quiet && a.options.backend == Backend::kAuto && segmenter.backend() == Backend::kCpu)
    std::fprintf(stderr, "lpir-gseg segment: note: %s\n", segmenter.backend_note().c_str());
  fs::create_directories(a.out_dir);
  const std::string on =
      segmenter.backend() == Backend::kVulkan ? segmenter.backend_note() : "the CPU reference";
  const char* plural = files.size() == 1 ? "" : "s";
  if (a.verbose)
    std::printf("segmenting %zu file%s with sensor '%s' on %s\n", files.size(), plural,
                segmenter.sensor().name.c_str(), on.c_str());
  const auto start = std::chrono::steady_clock::now();
  size_t failures = 0;
  std::string summary;
  {
    SegmentRun run(a, segmenter, files.size());
    for (const std::string& file : files) run.Submit(file);
    failures = run.FinishAll();
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (!a.quiet) {
      // "segmented 30 of 30 files on X in 1.2 s (25.0 frames/s), 0 failed, 12 invalid points
      // (non-ground); labels in OUT"
      char buf[128];
      std::snprintf(buf, sizeof(buf), " in %.2f s (%.1f frames/s), %zu failed", seconds,
                    seconds > 0 ? double(run.frames()) / seconds : 0.0, failures);
      std::string line = "segmented " + std::to_string(run.frames()) + " of " +
                         std::to_string(files.size()) + " file" + plural + " with sensor '" +
                         segmenter.sensor().name + "' on " + on + buf;
      if (run.invalid())
        line += ", " + std::to_string(run.invalid()) +
                " invalid points (NaN/Inf, at the origin or out of range: non-ground)";
      line += "; " + std::string(a.format == "label" ? "labels" : a.format + " clouds") + " in " +
              a.out_dir + "\n";
      summary = line;
    }
  }  // the progress line ends here, above the summary
  std::fputs(summary.c_str(), stdout);
  if (failures) {
    std::fprintf(stderr, "lpir-gseg segment: %zu of %zu files failed\n", failures, files.size());
    return kExitSomeFailed;
  }
  return kExitOk;
}

}  // namespace lpir
