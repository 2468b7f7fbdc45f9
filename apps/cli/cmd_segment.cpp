// lpir-gseg segment INPUT... --sensor NAME --out DIR [options]: labels every point of every input
// cloud (files, folders of them, and every PointCloud2 message of one topic of each recorded
// drive) and writes each output where OutputPaths puts it (host/io/output_paths.h): a cloud
// file's DIR/<its path below the folder given>.label, or the cloud with a label field; a drive's
// labels and index.csv go to DIR when it is the only input, else to DIR/<drive stem>/ (with
// --format mcap|bag also the whole drive with its labelled clouds there). The inputs are listed
// by ListInputs (host/drive/inputs.h) and read in turn: cloud files in a row as one source, each
// drive as its own; a drive that cannot be opened among several inputs is one failure, named,
// and the others are still segmented. Two inputs of one output are refused before anything is
// written, and a folder is made only when something is written into it. On Vulkan the next frame
// is read while the device works on the previous ones (frames in flight). A frame that cannot be
// read or segmented (a bad file, a damaged part of a drive, a message that does not decode) is
// reported and skipped; the exit code is then 1 and the last line (stderr) counts the failures.
// Output levels: --quiet prints errors only; the default adds the progress (stderr) and one
// summary line at the end (stdout); --verbose adds a line first naming the backend and a line
// per frame. --report writes every frame's figures to a CSV or JSON file (frame_report.h).
#include <malloc.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <filesystem>
#include <map>
#include <memory>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "apps/cli/args.h"
#include "apps/cli/commands.h"
#include "apps/cli/drive_output.h"
#include "apps/cli/exit_codes.h"
#include "apps/cli/frame_report.h"
#include "apps/cli/frame_source.h"
#include "apps/cli/help_text.h"
#include "apps/cli/invalid_reasons.h"
#include "apps/cli/mount_tally.h"
#include "apps/cli/progress.h"
#include "apps/cli/sensor_args.h"
#include "apps/cli/thread_args.h"
#include "apps/cli/timing.h"
#include "apps/cli/truth.h"
#include "apps/viz/images.h"
#include "host/api/segmenter.h"
#include "host/api/sensor_fit.h"
#include "host/drive/chunk_pool.h"
#include "host/drive/drive.h"
#include "host/drive/inputs.h"
#include "host/io/cloud_file.h"
#include "host/io/io_error.h"
#include "host/io/label_file.h"
#include "host/io/output_paths.h"

namespace fs = std::filesystem;

namespace lpir {
namespace {

const char kHelp[] =
    "usage: lpir-gseg segment INPUT... --sensor NAME --out DIR [options]\n"
    "  (--opt VALUE and --opt=VALUE alike; -s, -o, -b, -f, -t, -r, -q, -v: the short forms)\n"
    "  INPUT            cloud files ({clouds}), recorded drives, or folders of\n"
    "                   them (a folder's other entries are passed over); a cloud file writes\n"
    "                   DIR/<its name>.label, one found in a folder DIR/<its path below that\n"
    "                   folder>.label. Two inputs that would write one output are refused,\n"
    "                   naming both, before anything is written\n"
    "  -r, --recursive  folders: also the cloud files and drives of their subfolders, at the\n"
    "                   same paths below DIR (kitti/00/velodyne/000000.bin ->\n"
    "                   DIR/00/velodyne/000000.label)\n"
    "  drives           .mcap or .db3 (ROS 2), a ROS 2 bag folder (metadata.yaml and its split\n"
    "                   .mcap or .db3 files, read as one drive), .bag or .bag.active (ROS 1):\n"
    "                   every sensor_msgs/PointCloud2 message of the topic is labelled as\n"
    "                   <sequence, 6 digits>_<header stamp in ns>.label and listed in\n"
    "                   index.csv (sequence,stamp_ns,topic,points,ground_fraction,ms,file), in\n"
    "                   DIR when the drive is the only input, else in DIR/<drive stem>/\n"
    "  -t, --topic T    the drives' topic (needless when a drive has one PointCloud2 topic;\n"
    "                   `lpir-gseg topics DRIVE` lists them)\n"
    "  --chunks A:B     one drive: only its messages in chunks A to B (numbered from 1;\n"
    "                   `lpir-gseg topics DRIVE --chunks` counts them), named and indexed with\n"
    "                   the sequence numbers a whole run gives them; chunks before A are skipped\n"
    "                   without decompressing them when the drive has an index\n"
    "  --read-threads N threads decompressing a drive's chunks ahead (1 to 64; default: the\n"
    "                   CPU count, at most 8, or LPIR_READ_THREADS; 1: decompressed in turn)\n"
    "  -s, --sensor NAME\n"
    "                   sensor profile (hdl64e, hdl32e, vlp32c, os1-64, ...) or a profile "
    "file\n" LPIR_SET_HELP
    "  -o, --out DIR    where DIR/<stem>.label (uint32 per point: 1 ground, 0 non-ground) go;\n"
    "                   made when the first output is written\n"
    "  -f, --format F   label (default), {writable clouds}: the cloud with a label field instead;\n"
    "                   mcap (drives only): <drive stem>.mcap beside its labels, every topic of\n"
    "                   the drive as it was plus <topic>/labelled (a uint32 label field),\n"
    "                   <topic>/ground and <topic>/nonground; bag (ROS 1 .bag and .bag.active\n"
    "                   only): the same as a ROS 1 bag\n"
    "  --report FILE    a .csv or .json file: per frame its input, points, ground fraction,\n"
    "                   invalid points by reason, ms, backend and device, or its error\n"
    "  --nuscenes       .bin files hold 5 floats per point (x y z intensity ring); files named\n"
    "                   *.pcd.bin are read that way without it, other .bin files as KITTI\n"
    "  --images         also write pictures of every stage to DIR/images/\n"
    "  --gt PATH        ground truth .label file or folder (matched by stem) for the pictures\n"
    "  --max-points N   largest cloud accepted (default: the sensor's beams x width x 2, one\n"
    "                   point a pixel and as many second returns; 262144 for hdl64e)\n"
    "  -b, --backend B  vulkan (any device, lavapipe included), cpu (the reference) or auto\n"
    "                   (default: Vulkan on a GPU, else the reference with a note saying why;\n"
    "                   a CPU driver such as lavapipe only with vulkan or --device). Both give\n"
    "                   the same bytes\n"
    "  --device D       Vulkan device: index or part of its name (`lpir-gseg devices` lists them)\n"
    "  --batch N        Vulkan: N frames a command buffer, interleaved pass by pass (offline\n"
    "                   relabelling of a folder; default 1)\n"
    "  --threads N      CPU backend: threads (1 to 1024; default: the cores this process may\n"
    "                   run on). Two frames are in flight, each on threads / 2 of them; 1: the\n"
    "                   reference on one thread. The labels are the same at any count\n"
    "  --timings        per-stage times of every frame (GPU timestamps on Vulkan, wall time on\n"
    "                   the CPU) and their medians at the end\n"
    "  -q, --quiet      errors only (nothing on success)\n"
    "  -v, --verbose    also a line first naming the backend, and a line per frame (the figures\n"
    "                   of --report)\n"
    "Environment: LPIR_VK_VALIDATION=1 turns the Vulkan validation layer on.\n";

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

// A share of the inputs read as one source: cloud files in a row, or one drive.
struct Unit {
  std::vector<std::string> files;  // the cloud files (empty for a drive)
  std::string drive;               // the drive ("" for files)
  std::string out_dir;             // where its outputs go: DIR, or a drive's own (OutputPath)
};

// What the command line asks for.
struct SegmentArgs {
  std::vector<std::string> inputs;
  std::vector<Unit> units;            // the inputs listed (ListInputs) and grouped, in order
  std::vector<SkippedInput> skipped;  // the folders' entries ListInputs passed over
  size_t files = 0, drives = 0;
  std::string sensor, out_dir, format, gt, topic, report;
  bool images = false, has_gt = false, quiet = false, verbose = false, timings = false;
  bool drive = false;      // the one input is a recorded drive: its outputs go to DIR
  bool recursive = false;  // --recursive
  std::map<std::string, std::string> outputs;  // a cloud file -> its output (OutputPaths)
  ChunkRange chunks;                           // --chunks (first 0: every chunk)
  unsigned read_threads = 0;                   // --read-threads (0: DefaultReadThreads)
  SegmenterOptions options;
  ReadOptions read;
};

// "A:B" with whole numbers 1 <= A <= B; std::invalid_argument otherwise.
ChunkRange ParseChunkRange(const std::string& text) {
  const size_t colon = text.find(':');
  auto number = [](const std::string& s) -> uint64_t {
    if (s.empty() || s.size() > 18 || s.find_first_not_of("0123456789") != std::string::npos)
      return 0;
    return std::stoull(s);
  };
  ChunkRange r;
  if (colon != std::string::npos) {
    r.first = number(text.substr(0, colon));
    r.last = number(text.substr(colon + 1));
  }
  if (r.first < 1 || r.last < r.first)
    throw std::invalid_argument("--chunks must be A:B, chunk numbers from 1 with A <= B, not '" +
                                text + "'");
  return r;
}

// OutputPaths of the inputs listed, for --format `format`; its refusal says how outputs are named.
std::vector<std::string> Outputs(const std::vector<RunInput>& listed, const std::string& out_dir,
                                 const std::string& format) {
  try {
    return OutputPaths(listed, out_dir, "." + format);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(std::string(e.what()) +
                                "; nothing written (each output is named after its input's "
                                "path below the folder given; --recursive keeps subfolders "
                                "apart)");
  }
}

// The command line's options, checked; std::invalid_argument names the bad one.
SegmentArgs ParseSegmentArgs(const Args& args) {
  SegmentArgs a;
  a.inputs = args.positional();
  if (a.inputs.empty()) throw std::invalid_argument("no INPUT given\n" + HelpText(kHelp));
  a.out_dir = args.Require("--out");
  a.recursive = args.Has("--recursive");
  a.format = args.Get("--format", "label");
  const std::vector<RunInput> listed = ListInputs(a.inputs, a.recursive, &a.skipped);
  for (const RunInput& in : listed) ++(in.drive ? a.drives : a.files);
  a.drive = listed.size() == 1 && listed[0].drive;
  if (!a.drives && args.Has("--topic"))
    throw std::invalid_argument("--topic is for recorded drives (.mcap, .db3, .bag, bag folders)");
  a.topic = args.Get("--topic");
  if (args.Has("--chunks")) {
    if (!a.drive)
      throw std::invalid_argument("--chunks is for one recorded drive (.mcap, .bag), given alone");
    a.chunks = ParseChunkRange(args.Get("--chunks"));
  }
  if (args.Has("--read-threads")) {
    const double n = args.GetNumber("--read-threads", 0);
    if (!(n >= 1 && n <= kMaxReadThreads) || n != double(unsigned(n)))
      throw std::invalid_argument("--read-threads must be a whole number from 1 to " +
                                  std::to_string(kMaxReadThreads));
    a.read_threads = unsigned(n);
  }
  const CloudFormat* cloud_format = CloudFormatOf("." + a.format);
  if (a.format != "label" && a.format != "mcap" && a.format != "bag" &&
      !(cloud_format && cloud_format->write_labelled))
    throw std::invalid_argument("--format must be label, " + CloudFormatList(true) +
                                ", mcap or bag, not '" + a.format + "'");
  const bool whole = a.format == "mcap" || a.format == "bag";  // the drive written back whole
  for (const RunInput& in : listed) {
    if (whole && !in.drive)
      throw std::invalid_argument("--format " + a.format +
                                  " is for recorded drives (.mcap, .db3, .bag, bag folders), not "
                                  "cloud files such as " +
                                  in.path);
    if (a.format == "bag" && DriveFormatOf(in.path) != DriveFormat::kRos1Bag)
      throw std::invalid_argument(
          "--format bag writes a ROS 1 bag, for a ROS 1 .bag input (.bag, .bag.active): " +
          in.path + " is a ROS 2 drive (.mcap, .db3, bag folder), which takes --format mcap");
  }
  if (whole && args.Has("--chunks"))
    throw std::invalid_argument("--format " + a.format +
                                " writes the whole drive back: it takes no --chunks");
  a.report = args.Get("--report");
  if (args.Has("--report") && !FrameReport::IsReportName(a.report))
    throw std::invalid_argument("--report must name a .csv or .json file, not '" + a.report + "'");
  const double max_points = args.GetNumber("--max-points", 0);  // 0: from the sensor profile
  if (args.Has("--max-points") && (!(max_points >= 1) || max_points > 1e8))
    throw std::invalid_argument("--max-points must be between 1 and 1e8");
  a.options.backend = ParseBackend(args.Get("--backend", "auto"));
  a.options.device = args.Get("--device");
  a.options.max_points = size_t(max_points);
  a.images = args.Has("--images");
  a.options.all_buffers = a.images;  // the pictures show every stage
  const double batch = args.GetNumber("--batch", 1);
  if (!(batch >= 1 && batch <= 64) || batch != double(uint32_t(batch)))
    throw std::invalid_argument("--batch must be a whole number from 1 to 64");
  a.options.batch = uint32_t(batch);
  a.options.threads = ParseThreads(args);
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
  CheckOutputFolder(a.out_dir);
  // a drive alone writes into DIR itself (one input cannot clash)
  const std::vector<std::string> outputs =
      a.drive ? std::vector<std::string>{a.out_dir} : Outputs(listed, a.out_dir, a.format);
  for (size_t i = 0; i < listed.size(); ++i) {
    const RunInput& in = listed[i];
    if (!in.drive) {
      a.outputs[in.path] = outputs[i];
      if (a.units.empty() || !a.units.back().drive.empty()) a.units.push_back({{}, "", a.out_dir});
      a.units.back().files.push_back(in.path);
      continue;
    }
    const Unit u{{}, in.path, outputs[i]};
    if (whole) {
      const fs::path copy = fs::path(u.out_dir) / (DriveStem(in.path) + "." + a.format);
      std::error_code ec;
      if (fs::equivalent(copy, in.path, ec))
        throw std::invalid_argument(copy.string() + " is the drive being read: give --format " +
                                    a.format + " another --out");
    }
    a.units.push_back(u);
  }
  return a;
}

// "cpu" or "vulkan", and the device: the Vulkan device's name or "CPU reference".
std::string BackendName(const Segmenter& s) {
  return s.backend() == Backend::kVulkan ? "vulkan" : "cpu";
}
std::string DeviceName(const Segmenter& s) {
  const std::string prefix = "Vulkan on ";
  const std::string& note = s.backend_note();
  if (s.backend() != Backend::kVulkan) return "CPU reference";
  return note.rfind(prefix, 0) == 0 ? note.substr(prefix.size()) : note;
}

// The frames of the inputs' sources through one segmenter, frames in flight: each read while the
// device works on the ones before, collected oldest first, its labels (and pictures, index line,
// report row, labelled message) written, a failure reported and counted. A failure first collects
// the frames before it, so that every output and message keeps the input's order.
class SegmentRun {
 public:
  SegmentRun(const SegmentArgs& a, Segmenter& segmenter, FrameReport* report)
      : a_(a),
        segmenter_(segmenter),
        report_(report),
        timings_(segmenter.backend() == Backend::kVulkan) {}

  // Reads, submits and collects every frame of `source`, a drive's writing into `out_dir` (with
  // its `index` and whole copy `drive_out`, when not null), under a progress of its own; returns
  // the frames of it that failed.
  size_t Run(FrameSource& source, const std::string& out_dir, DriveIndex* index,
             LabelledDrive* drive_out) {
    out_dir_ = out_dir;
    index_ = index;
    drive_out_ = drive_out;
    source_count_ = source.count();
    const size_t failed_before = failures_;
    progress_ = std::make_unique<Progress>(source.count(),  // 0: unknown
                                           source.count() != 1 && !a_.quiet);
    FrameInput in;
    std::string error;
    for (;;) {
      const SourceStep step = source.Next(&in, &error);
      if (step == SourceStep::kEnd) break;
      Note(in.note);
      if (step == SourceStep::kFailed) {
        while (!jobs_.empty()) Finish();
        Fail(in, error);
        continue;
      }
      FitWarnings(in);
      try {
        while (!segmenter_.CanSubmit()) Finish();
        // Borrowed: the job holds the cloud until Finish has collected its frame (no copy on the
        // CPU backend; std::deque keeps the element in place as jobs are added).
        jobs_.push_back(std::move(in));
        try {
          segmenter_.SubmitBorrowed(jobs_.back().cloud);
        } catch (...) {
          in = std::move(jobs_.back());
          jobs_.pop_back();
          throw;
        }
      } catch (const std::exception& e) {
        while (!jobs_.empty()) Finish();
        Fail(in, Where(in) + ": " + e.what());
      }
    }
    while (!jobs_.empty()) Finish();
    if (drive_out_) {
      drive_out_->Close();
      CopyProblems();
    }
    progress_.reset();  // the status line ends here
    return failures_ - failed_before;
  }

  // An input that gave no frame at all (a drive that could not be opened): named on stderr and
  // in the report, counted.
  void FailInput(const std::string& input, const std::string& error) {
    FrameInput in;
    in.input = input;
    in.from_drive = true;
    Fail(in, error);
  }

  // Each stage's median time over every frame, when --timings asked for them.
  void PrintMedians() const {
    if (a_.timings) std::fputs(timings_.Medians().c_str(), stdout);
  }

  size_t frames() const { return frames_; }
  size_t invalid() const { return invalid_; }
  const InvalidReasons& reasons() const { return reasons_; }
  const MountTally& mounts() const { return mounts_; }

 private:
  // The frame as messages name it: the file, or "<drive>: <topic> message <sequence>".
  static std::string Where(const FrameInput& in) {
    if (!in.from_drive) return in.input;
    return in.input + ": " + in.topic + " message " + std::to_string(in.sequence);
  }

  static FrameRecord Record(const FrameInput& in) {
    FrameRecord r;
    r.input = in.input;
    r.from_drive = in.has_message;
    r.sequence = in.sequence;
    r.stamp_ns = in.stamp_ns;
    r.topic = in.topic;
    return r;
  }

  // The first reader's note of the run above the progress (a folder of files from one writer
  // would repeat it for every file); none with --quiet.
  void Note(const std::string& note) {
    if (note.empty() || noted_ || a_.quiet) return;
    noted_ = true;
    const char* once = source_count_ == 1 ? "" : " (said for the first such file only)";
    Print(stderr, "lpir-gseg segment: note: " + note + once + "\n");
  }

  // The first frame that does not look like the profile's sensor (host/api/sensor_fit.h: rings past
  // the beams, elevations outside its table), named with what is wrong, once a run (a wrong
  // --sensor would repeat it for every frame); none with --quiet.
  void FitWarnings(const FrameInput& in) {
    if (fit_warned_ || a_.quiet) return;
    const SensorProfile& sensor = segmenter_.sensor();
    const std::vector<std::string> warnings =
        SensorFitWarnings(MeasureSensorFit(in.cloud, sensor), sensor);
    if (warnings.empty()) return;
    fit_warned_ = true;
    const char* once = source_count_ == 1 && a_.units.size() == 1 ? "" : " (said once a run)";
    for (const std::string& w : warnings)
      Print(stderr, "lpir-gseg segment: warning: " + Where(in) + ": " + w + once + "\n");
  }

  // `error` (naming the frame) above the progress and in the report.
  void Fail(const FrameInput& in, const std::string& error) {
    ++failures_;
    Print(stderr, "lpir-gseg segment: error: " + error + "\n");
    if (report_) {
      FrameRecord r = Record(in);
      r.error = error;
      report_->Add(r);
    }
    if (progress_ && (in.has_message || !in.from_drive)) progress_->Step();  // damage: none
  }

  // `text` above the progress, when there is one.
  void Print(std::FILE* to, const std::string& text) {
    if (progress_)
      progress_->Print(to, text);
    else
      std::fputs(text.c_str(), to);
  }

  // The damaged parts the whole-drive output met while copying, above the progress and counted.
  void CopyProblems() {
    for (const std::string& problem : drive_out_->TakeProblems()) {
      ++failures_;
      Print(stderr, "lpir-gseg segment: error: " + problem + "\n");
    }
  }

  // Collects the oldest frame in flight and writes what it gives; the job leaves the queue last,
  // its cloud having been read in place by the frame.
  void Finish() {
    const struct PopFront {
      std::deque<FrameInput>& jobs;
      ~PopFront() { jobs.pop_front(); }
    } pop{jobs_};
    const FrameInput& job = jobs_.front();
    try {
      FrameTimes times;
      const Frame& frame = segmenter_.Collect(&times);
      const std::string file = Write(job, frame);
      FrameRecord r = Record(job);
      r.points = job.cloud.size();
      {  // counted in locals, so that the loop becomes vector code
        const uint8_t* label = frame.label.data();
        const uint8_t* why = frame.why.data();
        size_t ground = 0, invalid = 0;
        for (uint32_t i = 0; i < frame.n; ++i) ground += label[i], invalid += why[i] == kWhyInvalid;
        r.ground += ground, r.invalid += invalid;
      }
      r.ms = times.total_ms;
      r.mount = segmenter_.mount().mount;
      r.mount_estimated = segmenter_.mount().estimated;
      mounts_.Add(segmenter_.mount());
      if (r.invalid)
        r.reasons =
            CountInvalidReasons(job.cloud, segmenter_.params(),
                                segmenter_.sensor().pattern == ScanPattern::kSpinning, frame.why);
      ++frames_;
      invalid_ += r.invalid;
      reasons_.not_finite += r.reasons.not_finite;
      reasons_.at_origin += r.reasons.at_origin;
      reasons_.out_of_range += r.reasons.out_of_range;
      reasons_.bad_ring += r.reasons.bad_ring;
      if (index_) index_->Add(job, r.ground, r.ms, file);
      if (report_) report_->Add(r);
      std::string lines;
      if (a_.verbose) lines += FrameLine(job.stem, r, per_frame_ ? &segmenter_.mount() : nullptr);
      if (a_.timings) lines += timings_.Add(job.stem, times);
      if (!lines.empty()) progress_->Print(stdout, lines);
      progress_->Step(job.cloud.size(), r.ground);
    } catch (const std::exception& e) {
      if (dynamic_cast<const IoError*>(&e))  // names the file already
        Fail(job, e.what());
      else
        Fail(job, Where(job) + ": " + e.what());
    }
    if (drive_out_) CopyProblems();
  }

  // The labels as a .label file, a labelled cloud or a labelled message, and with --images the
  // pictures; returns the name written inside the drive's folder ("" for a file, and for a
  // message of the whole copy). A file's output is its OutputPath (a_.outputs), a message's
  // <drive's folder>/<stem>, the folder made first; the pictures go to DIR/images/<the output's
  // folder below DIR>.
  std::string Write(const FrameInput& job, const Frame& frame) {
    const auto planned = a_.outputs.find(job.input);
    const fs::path path = planned != a_.outputs.end() && !job.from_drive
                              ? fs::path(planned->second)
                              : fs::path(out_dir_) / (job.stem + "." + a_.format);
    if (!drive_out_ && made_.insert(path.parent_path().string()).second)
      MakeOutputFolder(path.parent_path().string());
    if (drive_out_) {
      drive_out_->AddLabelled(job, frame.label);
    } else if (a_.format == "label") {
      std::vector<uint32_t> labels(frame.label.begin(), frame.label.end());
      WriteLabelFile(path.string(), labels);
    } else {
      WriteLabelledCloud(path.string(), job.cloud, frame.label);
    }
    if (a_.images) {
      std::vector<uint8_t> truth;
      if (a_.has_gt) truth = LoadTruth(a_.gt, job.stem, job.cloud.size());
      const fs::path out(a_.out_dir);
      WriteImages((out / "images" / path.parent_path().lexically_relative(out)).string(), job.stem,
                  job.cloud, frame, segmenter_.params(), truth.empty() ? nullptr : &truth);
    }
    return drive_out_ || !job.from_drive ? "" : path.filename().string();
  }

  // "<stem>: N points, G % ground, T ms", the frame's own mount when `mount` is given
  // (MountTally::FrameClause), and the invalid points by reason when there are any:
  // " (K invalid: a NaN/Inf, b at the origin, c out of range, d ring outside the beams)", naming
  // those > 0.
  static std::string FrameLine(const std::string& stem, const FrameRecord& r,
                               const MountEstimate* mount) {
    char buf[160];
    std::snprintf(buf, sizeof(buf), "%s: %zu points, %.1f %% ground, %.2f ms", stem.c_str(),
                  r.points, r.points ? 100.0 * double(r.ground) / double(r.points) : 0.0, r.ms);
    std::string line = buf;
    if (mount) line += MountTally::FrameClause(*mount);
    if (r.invalid)
      line +=
          " (" + std::to_string(r.invalid) + " invalid: " + DescribeInvalidReasons(r.reasons) + ")";
    return line + "\n";
  }

  const SegmentArgs& a_;
  Segmenter& segmenter_;
  FrameReport* report_;  // optional, not owned (also index_, drive_out_)
  Timings timings_;
  // The source being run: where a drive's outputs go, its index and whole copy (optional), how
  // many frames it holds (0: unknown), its progress.
  std::string out_dir_;
  DriveIndex* index_ = nullptr;
  LabelledDrive* drive_out_ = nullptr;
  size_t source_count_ = 0;
  std::unique_ptr<Progress> progress_;
  std::deque<FrameInput> jobs_;
  std::set<std::string> made_;  // output folders made so far
  size_t failures_ = 0;
  size_t frames_ = 0;       // segmented and written
  size_t invalid_ = 0;      // points of those frames labelled invalid
  InvalidReasons reasons_;  // the same points by reason
  MountTally mounts_;       // the frames' mounts
  const bool per_frame_ = segmenter_.sensor().mount == MountSource::kPerFrame;
  bool noted_ = false;       // a reader's note was printed
  bool fit_warned_ = false;  // a sensor-fit warning was printed
};

// A unit's frames read one ahead (ReadAhead): its cloud files, or its drive's topic (chosen by
// ChooseCloudTopic; *topic set to it), the drive's notes printed first (but with --quiet).
// A drive whose topics cannot be listed (damage where a .db3 keeps its counts) is still read
// up to the damage when --topic names the topic: a warning then, and no count for the progress.
std::unique_ptr<FrameSource> OpenSource(const SegmentArgs& a, const Unit& u, std::string* topic) {
  if (u.drive.empty()) return ReadAhead(OpenFileSource(u.files, a.read));
  const std::string& drive = u.drive;
  std::unique_ptr<DriveReader> reader = OpenDrive(drive, a.read_threads);
  std::vector<DriveTopic> topics;
  bool listed = false;
  try {
    topics = reader->Topics();
    listed = true;
  } catch (const IoError& e) {
    if (a.topic.empty())
      throw IoError(drive, std::string("its topics cannot be listed (") + e.what() +
                               "); --topic T reads T's messages up to the damage");
    if (!a.quiet)
      std::fprintf(stderr, "lpir-gseg segment: warning: %s; reading %s up to the damage\n",
                   e.what(), a.topic.c_str());
    *topic = a.topic;
  }
  if (listed) *topic = ChooseCloudTopic(drive, topics, a.topic, reader->ListingDamage());
  if (!a.quiet)
    for (const std::string& note : reader->Notes())
      std::fprintf(stderr, "lpir-gseg segment: note: %s\n", note.c_str());
  size_t count = 0;  // a range's share is unknown
  for (const DriveTopic& t : topics)
    if (t.name == *topic && a.chunks.first == 0) count = size_t(t.messages);
  return ReadAhead(OpenDriveSource(drive, std::move(reader), *topic, a.chunks, count,
                                   a.format == "mcap" || a.format == "bag"));
}

// "1 file", "3 messages".
std::string Count(size_t n, const std::string& unit) {
  return std::to_string(n) + " " + unit + (n == 1 ? "" : "s");
}

// What a run of several units did, for its summary and last lines.
struct Tally {
  size_t file_frames = 0, file_failures = 0;
  size_t messages = 0, messages_listed = 0;  // labelled; listed (when every drive's is known)
  bool listed_known = true;
  size_t drives_opened = 0;                                    // each has its folder of outputs
  std::vector<std::pair<std::string, size_t>> drive_problems;  // drive, problems (0: not read)
};

}  // namespace

int RunSegment(int argc, char** argv) {
  // Every frame allocates and frees buffers of the same sizes (the cloud read, its copy, the
  // stages' buffers on each thread). glibc by default maps the largest afresh and hands freed
  // memory at the top of a heap back to the system, so each frame page-faults it in again; with
  // these two limits the freed memory stays in the process and the next frame reuses it.
  mallopt(M_MMAP_THRESHOLD, 256 << 20);
  mallopt(M_TRIM_THRESHOLD, 1 << 30);
  const Args args(
      argc, argv,
      {"--images", "--nuscenes", "--quiet", "--verbose", "--timings", "--recursive", "--help"},
      {"--sensor", "--out", "--format", "--gt", "--max-points", "--backend", "--device", "--batch",
       "--topic", "--report", "--chunks", "--read-threads", "--threads"},
      {"--set"});
  if (args.Has("--help")) {
    std::fputs(HelpText(kHelp).c_str(), stdout);
    std::fputs(kExitCodesLine, stdout);
    return kExitOk;
  }
  const SegmentArgs a = ParseSegmentArgs(args);
  if (a.images) LoadImages();  // a missing pictures' library stops the run before any output
  const SensorProfile sensor = LoadProfileWithSettings(a.sensor, args);
  if (a.verbose)
    for (const SkippedInput& s : a.skipped)
      std::fprintf(stderr, "lpir-gseg segment: note: passed over %s: %s\n", s.path.c_str(),
                   s.why.c_str());
  const bool single = a.units.size() == 1;
  // One source alone opens before the segmenter is made: a lone drive that cannot be opened, or
  // lacks the --topic asked for, stops the command before any set-up.
  std::string topic;
  std::unique_ptr<FrameSource> source;
  if (single) source = OpenSource(a, a.units[0], &topic);
  Segmenter segmenter(sensor, a.options);
  if (!a.quiet && a.options.backend == Backend::kAuto && segmenter.backend() == Backend::kCpu)
    std::fprintf(stderr, "lpir-gseg segment: note: %s\n", segmenter.backend_note().c_str());
  std::unique_ptr<FrameReport> report;
  if (!a.report.empty())
    report = std::make_unique<FrameReport>(a.report, BackendName(segmenter), DeviceName(segmenter));
  const std::string on =
      segmenter.backend() == Backend::kVulkan ? segmenter.backend_note() : "the CPU reference";
  const std::string threads = segmenter.backend() == Backend::kVulkan
                                  ? ""
                                  : " (" + std::to_string(segmenter.threads()) + " thread" +
                                        (segmenter.threads() == 1 ? ")" : "s)");
  // "30 files", "3 messages of /points in D", "30 files and 2 drives"
  std::string what;
  if (single) {
    what = std::string(source->unit()) + (source->count() == 1 ? "" : "s");
    if (a.drive) what += " of " + topic + " in " + a.units[0].drive;
  } else {
    what = a.files ? Count(a.files, "file") : "";
    if (a.drives) what += (what.empty() ? "" : " and ") + Count(a.drives, "drive");
  }
  if (a.verbose)
    std::printf("segmenting %s%s with sensor '%s' on %s%s\n",
                single ? (std::to_string(source->count()) + " ").c_str() : "", what.c_str(),
                segmenter.sensor().name.c_str(), on.c_str(), threads.c_str());
  const auto start = std::chrono::steady_clock::now();
  SegmentRun run(a, segmenter, report.get());
  size_t failures = 0;
  Tally tally;
  for (const Unit& u : a.units) {
    // A drive's folder, index and whole copy are made once its source has opened; among several
    // inputs a drive that cannot be opened is that input's failure, and nothing of it is written.
    std::unique_ptr<DriveIndex> index;
    std::unique_ptr<LabelledDrive> drive_out;
    try {
      if (!single) source = OpenSource(a, u, &topic);
      if (!u.drive.empty()) {
        const fs::path out(u.out_dir);
        MakeOutputFolder(u.out_dir);
        index = std::make_unique<DriveIndex>((out / "index.csv").string());
        if (a.format == "mcap" || a.format == "bag")
          drive_out = std::make_unique<LabelledDrive>(
              u.drive, (out / (DriveStem(u.drive) + "." + a.format)).string(), topic,
              a.format == "bag" ? LabelledDrive::Format::kBag : LabelledDrive::Format::kMcap);
        ++tally.drives_opened;
      }
    } catch (const std::exception& e) {
      if (single) throw;
      const std::string error = e.what();
      run.FailInput(u.drive, error.rfind(u.drive, 0) == 0 ? error : u.drive + ": " + error);
      ++failures;
      tally.drive_problems.emplace_back(u.drive, 0);
      continue;
    }
    const size_t frames_before = run.frames();
    const size_t failed = run.Run(*source, u.out_dir, index.get(), drive_out.get());
    failures += failed;
    if (index) index->Close();
    const size_t frames = run.frames() - frames_before;
    if (u.drive.empty()) {
      tally.file_frames += frames;
      tally.file_failures += failed;
    } else {
      tally.messages += frames;
      tally.messages_listed += source->count();
      tally.listed_known = tally.listed_known && source->count() > 0;
      if (failed) tally.drive_problems.emplace_back(u.drive, failed);
    }
    source.reset();
  }
  run.PrintMedians();
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (report) report->Close(run.frames(), failures, seconds);
  if (!a.quiet) {
    // "segmented 30 of 30 files on X in 1.20 s, 25.0 frames/s, 2 failed, 12 invalid points
    // (non-ground: 12 ring outside the beams); labels in OUT": short, so that beside the note
    // above it fits 120 columns with a folder of some 35 characters; the failures and the invalid
    // points only when there are some (the last line counts the failures too); the sensor with
    // --verbose
    char buf[128];
    std::snprintf(buf, sizeof(buf), " in %.2f s, %.1f frames/s", seconds,
                  seconds > 0 ? double(run.frames()) / seconds : 0.0);
    if (failures) std::snprintf(buf + std::strlen(buf), 32, ", %zu failed", failures);
    std::string done;
    if (single) {
      // a drive whose count is unknown (0): "segmented 2 messages of /points in D ..."
      const size_t total = a.drive ? tally.messages_listed : a.files;
      const std::string of = total || !a.drive ? " of " + std::to_string(total) : "";
      done = std::to_string(run.frames()) + of + " " + what;
    } else {
      // "segmented 30 of 30 files and 14 of 14 messages of 3 drives ..."
      if (a.files) done = std::to_string(tally.file_frames) + " of " + Count(a.files, "file");
      if (a.drives) {
        const std::string of =
            tally.listed_known ? " of " + std::to_string(tally.messages_listed) : "";
        done += (done.empty() ? "" : " and ") + std::to_string(tally.messages) + of + " message" +
                (tally.messages_listed == 1 && tally.listed_known ? "" : "s") + " of " +
                Count(a.drives, "drive");
      }
    }
    std::string line = "segmented " + done + " on " + on + buf;
    if (run.invalid())
      line += ", " + std::to_string(run.invalid()) +
              " invalid points (non-ground: " + DescribeInvalidReasons(run.reasons()) + ")";
    if (sensor.mount == MountSource::kPerFrame && run.frames())
      line += "; " + run.mounts().Summary(segmenter.params().sensor_height);
    const std::string outputs = a.format == "label"  ? "labels"
                                : a.format == "mcap" ? "labelled MCAP"
                                : a.format == "bag"  ? "labelled bag"
                                                     : a.format + " clouds";
    line += run.frames() || tally.drives_opened ? "; " + outputs + " in " + a.out_dir + "\n"
                                                : "; nothing written\n";
    std::fputs(line.c_str(), stdout);
  }
  if (!failures) return kExitOk;
  // a damaged part may hold any number of messages: a drive's problems are counted apart
  for (const auto& [drive, problems] : tally.drive_problems)
    if (problems)
      std::fprintf(stderr,
                   "lpir-gseg segment: %s: %zu problem%s (damaged parts, or messages that do not "
                   "decode, each named above); every other message labelled\n",
                   drive.c_str(), problems, problems == 1 ? "" : "s");
    else
      std::fprintf(stderr, "lpir-gseg segment: %s: not read (named above)\n", drive.c_str());
  if (tally.file_failures)
    std::fprintf(stderr, "lpir-gseg segment: %zu of %zu files failed\n", tally.file_failures,
                 a.files);
  if (!single)
    std::fprintf(stderr, "lpir-gseg segment: %zu of %zu inputs with problems (each named above)\n",
                 tally.file_failures + tally.drive_problems.size(), a.files + a.drives);
  return kExitSomeFailed;
}

}  // namespace lpir
