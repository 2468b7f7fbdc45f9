// lpir-gseg segment INPUT... --sensor NAME --out DIR [options]: labels every point of every input
// cloud (files, or folders of them, or every PointCloud2 message of one topic of one recorded
// drive) and writes DIR/<stem>.label, or the cloud with a label field (a drive: also
// DIR/index.csv, and with --format mcap|bag the whole drive with its labelled clouds). On Vulkan
// the next frame is read while the device works on the previous ones (frames in flight). A frame
// that cannot be read or segmented (a bad file, a damaged part of a drive, a message that does not
// decode) is reported and skipped; the exit code is then 1 and the last line (stderr) counts the
// failures. Output levels: --quiet prints errors only; the default adds the progress (stderr) and
// one summary line at the end (stdout); --verbose adds a line first naming the backend and a line
// per frame. --report writes every frame's figures to a CSV or JSON file (frame_report.h).
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
#include "apps/cli/invalid_reasons.h"
#include "apps/cli/progress.h"
#include "apps/cli/sensor_args.h"
#include "apps/cli/timing.h"
#include "apps/cli/truth.h"
#include "apps/viz/images.h"
#include "host/drive/chunk_pool.h"
#include "host/drive/drive.h"
#include "host/io/cloud_file.h"
#include "host/io/io_error.h"
#include "host/io/label_file.h"
#include "host/io/output_paths.h"
#include "host/segmenter.h"

namespace fs = std::filesystem;

namespace lpir {
namespace {

const char kHelp[] =
    "usage: lpir-gseg segment INPUT... --sensor NAME --out DIR [options]\n"
    "       lpir-gseg segment DRIVE [--topic T] --sensor NAME --out DIR [options]\n"
    "  (--opt VALUE and --opt=VALUE alike; -s, -o, -b, -f, -t, -r, -q, -v: the short forms)\n"
    "  INPUT            cloud files (.bin KITTI, .pcd, .ply) or folders of them; each writes\n"
    "                   DIR/<its name>.label, a file found in a folder DIR/<its path below that\n"
    "                   folder>.label. Two inputs that would write one output are refused,\n"
    "                   naming both, before anything is written\n"
    "  -r, --recursive  folders: also the cloud files of their subfolders, at the same paths\n"
    "                   below DIR (kitti/00/velodyne/000000.bin -> DIR/00/velodyne/000000.label)\n"
    "  DRIVE            one recorded drive (.mcap or .db3 ROS 2, .bag ROS 1), on its own: every\n"
    "                   sensor_msgs/PointCloud2 message of the topic is labelled as\n"
    "                   DIR/<sequence, 6 digits>_<header stamp in ns>.label and listed in\n"
    "                   DIR/index.csv (sequence,stamp_ns,topic,points,ground_fraction,ms,file)\n"
    "  -t, --topic T    the drive's topic (needless when it has one PointCloud2 topic;\n"
    "                   `lpir-gseg topics DRIVE` lists them)\n"
    "  --chunks A:B     only the messages in the drive's chunks A to B (numbered from 1;\n"
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
    "  -f, --format F   label (default), pcd or ply: the cloud with a label field instead;\n"
    "                   mcap (a drive only): DIR/<drive stem>.mcap, every topic of the drive as\n"
    "                   it was plus <topic>/labelled (a uint32 label field), <topic>/ground\n"
    "                   and <topic>/nonground; bag (a ROS 1 .bag only): the same as a ROS 1 bag\n"
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
    "  --timings        per-stage times of every frame (GPU timestamps on Vulkan, wall time on\n"
    "                   the CPU) and their medians at the end\n"
    "  -q, --quiet      errors only (nothing on success)\n"
    "  -v, --verbose    also a line first naming the backend, and a line per frame (the figures\n"
    "                   of --report)\n"
    "Environment: LPIR_VK_VALIDATION=1 turns the Vulkan validation layer on.\n";

// The cloud files in `folder`, and with `recursive` in its subfolders too (not following links
// to folders), sorted by path.
std::vector<std::string> CloudFilesIn(const std::string& folder, bool recursive) {
  std::vector<std::string> found;
  std::error_code ec;
  auto take = [&found](const fs::directory_entry& entry) {
    std::error_code file_ec;
    if (entry.is_regular_file(file_ec) && IsCloudFile(entry.path().string()))
      found.push_back(entry.path().string());
  };
  if (recursive) {
    for (fs::recursive_directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec))
      take(*it);
  } else {
    for (fs::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec)) take(*it);
  }
  std::sort(found.begin(), found.end());
  return found;
}

// Input clouds: files as given, folders expanded to their cloud files in path order (with
// `recursive`, their subfolders' too), each with the folder it was found in (OutputPath).
// std::invalid_argument for a folder without cloud files, saying so when its subfolders hold some.
std::vector<RunInput> ListInputs(const std::vector<std::string>& inputs, bool recursive) {
  std::vector<RunInput> files;
  for (const std::string& in : inputs) {
    std::error_code ec;
    if (!fs::is_directory(in, ec)) {
      files.push_back({in, "", false});  // a missing file is reported when it is read
      continue;
    }
    const std::vector<std::string> found = CloudFilesIn(in, recursive);
    if (found.empty()) {
      const size_t below = recursive ? 0 : CloudFilesIn(in, true).size();
      throw std::invalid_argument(
          in + ": folder holds no cloud files" +
          (below ? ", but its subfolders hold " + std::to_string(below) +
                       ": --recursive (-r) segments them, each to its path below the folder"
                 : ""));
    }
    for (const std::string& f : found) files.push_back({f, in, false});
  }
  return files;
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
  std::string sensor, out_dir, format, gt, topic, report;
  bool images = false, has_gt = false, quiet = false, verbose = false, timings = false;
  bool drive = false;                          // inputs is one recorded drive
  bool recursive = false;                      // --recursive
  std::vector<RunInput> files;                 // the cloud files (not for a drive)
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

// The command line's options, checked; std::invalid_argument names the bad one.
SegmentArgs ParseSegmentArgs(const Args& args) {
  SegmentArgs a;
  a.inputs = args.positional();
  if (a.inputs.empty()) throw std::invalid_argument("no INPUT given\n" + std::string(kHelp));
  for (const std::string& in : a.inputs) a.drive = a.drive || IsDriveFile(in);
  if (a.drive && a.inputs.size() != 1)
    throw std::invalid_argument(
        "a recorded drive is segmented on its own: give one drive, or cloud files and folders");
  if (!a.drive && args.Has("--topic"))
    throw std::invalid_argument("--topic is for a recorded drive (.mcap, .db3, .bag)");
  a.topic = args.Get("--topic");
  if (args.Has("--chunks")) {
    if (!a.drive) throw std::invalid_argument("--chunks is for a recorded drive (.mcap, .bag)");
    a.chunks = ParseChunkRange(args.Get("--chunks"));
  }
  if (args.Has("--read-threads")) {
    const double n = args.GetNumber("--read-threads", 0);
    if (!(n >= 1 && n <= kMaxReadThreads) || n != double(unsigned(n)))
      throw std::invalid_argument("--read-threads must be a whole number from 1 to " +
                                  std::to_string(kMaxReadThreads));
    a.read_threads = unsigned(n);
  }
  a.format = args.Get("--format", "label");
  if (a.format != "label" && a.format != "pcd" && a.format != "ply" && a.format != "mcap" &&
      a.format != "bag")
    throw std::invalid_argument("--format must be label, pcd, ply, mcap or bag, not '" + a.format +
                                "'");
  if (a.format == "mcap" && !a.drive)
    throw std::invalid_argument("--format mcap is for a recorded drive (.mcap, .db3, .bag)");
  if (a.format == "bag" && (!a.drive || DriveFormatOf(a.inputs[0]) != DriveFormat::kRos1Bag))
    throw std::invalid_argument(
        "--format bag writes a ROS 1 bag, for a ROS 1 .bag input; a ROS 2 drive (.mcap, .db3) "
        "takes --format mcap");
  if ((a.format == "mcap" || a.format == "bag") && args.Has("--chunks"))
    throw std::invalid_argument("--format " + a.format +
                                " writes the whole drive back: it takes no --chunks");
  a.report = args.Get("--report");
  if (args.Has("--report") && !FrameReport::IsReportName(a.report))
    throw std::invalid_argument("--report must name a .csv or .json file, not '" + a.report + "'");
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
  a.recursive = args.Has("--recursive");
  if (a.recursive && a.drive) throw std::invalid_argument("--recursive is for folders of clouds");
  CheckOutputFolder(a.out_dir);
  if (!a.drive) {
    a.files = ListInputs(a.inputs, a.recursive);
    std::vector<std::string> outputs;
    try {
      outputs = OutputPaths(a.files, a.out_dir, "." + a.format);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(std::string(e.what()) +
                                  "; nothing written (each output is named after its input's "
                                  "path below the folder given; --recursive keeps subfolders "
                                  "apart)");
    }
    for (size_t i = 0; i < a.files.size(); ++i) a.outputs[a.files[i].path] = outputs[i];
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

// The frames of a source through one segmenter, frames in flight: each read while the device
// works on the ones before, collected oldest first, its labels (and pictures, index line, report
// row, labelled message) written, a failure reported and counted. A failure first collects the
// frames before it, so that every output and message keeps the input's order.
class SegmentRun {
 public:
  SegmentRun(const SegmentArgs& a, Segmenter& segmenter, FrameSource& source, FrameReport* report,
             DriveIndex* index, LabelledDrive* drive_out)
      : a_(a),
        segmenter_(segmenter),
        source_(source),
        report_(report),
        index_(index),
        drive_out_(drive_out),
        progress_(source.count(), source.count() != 1 && !a.quiet),  // 0: unknown
        timings_(segmenter.backend() == Backend::kVulkan) {}

  // Reads, submits and collects every frame of the source; returns the frames that failed.
  size_t Run() {
    FrameInput in;
    std::string error;
    for (;;) {
      const SourceStep step = source_.Next(&in, &error);
      if (step == SourceStep::kEnd) break;
      Note(in.note);
      if (step == SourceStep::kFailed) {
        while (!jobs_.empty()) Finish();
        Fail(in, error);
        continue;
      }
      try {
        while (!segmenter_.CanSubmit()) Finish();
        segmenter_.Submit(in.cloud);
        jobs_.push_back(std::move(in));
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
    if (a_.timings) progress_.Print(stdout, timings_.Medians());
    return failures_;
  }

  // Prints a line above the progress.
  void Print(std::FILE* to, const std::string& text) { progress_.Print(to, text); }

  size_t frames() const { return frames_; }
  size_t invalid() const { return invalid_; }

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
    const char* once = source_.count() == 1 ? "" : " (said for the first such file only)";
    progress_.Print(stderr, "lpir-gseg segment: note: " + note + once + "\n");
  }

  // `error` (naming the frame) above the progress and in the report.
  void Fail(const FrameInput& in, const std::string& error) {
    ++failures_;
    progress_.Print(stderr, "lpir-gseg segment: error: " + error + "\n");
    if (report_) {
      FrameRecord r = Record(in);
      r.error = error;
      report_->Add(r);
    }
    if (in.has_message || !in.from_drive) progress_.Step();  // a damaged part is no message
  }

  // The damaged parts the whole-drive output met while copying, above the progress and counted.
  void CopyProblems() {
    for (const std::string& problem : drive_out_->TakeProblems()) {
      ++failures_;
      progress_.Print(stderr, "lpir-gseg segment: error: " + problem + "\n");
    }
  }

  // Collects the oldest frame in flight and writes what it gives.
  void Finish() {
    const FrameInput job = std::move(jobs_.front());
    jobs_.pop_front();
    try {
      FrameTimes times;
      const Frame& frame = segmenter_.Collect(&times);
      const std::string file = Write(job, frame);
      FrameRecord r = Record(job);
      r.points = job.cloud.size();
      for (uint32_t i = 0; i < frame.n; ++i) {
        r.ground += frame.label[i];
        r.invalid += frame.why[i] == kWhyInvalid;
      }
      r.ms = times.total_ms;
      if (r.invalid && (report_ || a_.verbose))
        r.reasons = CountInvalidReasons(job.cloud, segmenter_.params());
      ++frames_;
      invalid_ += r.invalid;
      if (index_) index_->Add(job, r.ground, r.ms, file);
      if (report_) report_->Add(r);
      std::string lines;
      if (a_.verbose) lines += FrameLine(job.stem, r);
      if (a_.timings) lines += timings_.Add(job.stem, times);
      if (!lines.empty()) progress_.Print(stdout, lines);
      progress_.Step(job.cloud.size(), r.ground);
    } catch (const std::exception& e) {
      if (dynamic_cast<const IoError*>(&e))  // names the file already
        Fail(job, e.what());
      else
        Fail(job, Where(job) + ": " + e.what());
    }
    if (drive_out_) CopyProblems();
  }

  // The labels as a .label file, a labelled cloud or a labelled message, and with --images the
  // pictures; returns the name written inside DIR ("" for a message). A file's output is its
  // OutputPath (a_.outputs), its folder made first; a message's is DIR/<stem>.
  std::string Write(const FrameInput& job, const Frame& frame) {
    const fs::path out(a_.out_dir);
    const auto planned = a_.outputs.find(job.input);
    const fs::path path = planned != a_.outputs.end() && !job.from_drive
                              ? fs::path(planned->second)
                              : out / (job.stem + "." + a_.format);
    const std::string name = path.lexically_relative(out).string();
    if (!drive_out_ && made_.insert(path.parent_path().string()).second)
      MakeOutputFolder(path.parent_path().string());
    if (drive_out_) {
      drive_out_->AddLabelled(job, frame.label);
    } else if (a_.format == "label") {
      std::vector<uint32_t> labels(frame.label.begin(), frame.label.end());
      WriteLabelFile(path.string(), labels);
    } else {
      WriteLabelledCloud(path.string(), job.cloud, frame.label,
                         a_.format == "pcd" ? CloudFormat::kPcd : CloudFormat::kPly);
    }
    if (!a_.images) return drive_out_ ? "" : name;
    std::vector<uint8_t> truth;
    if (a_.has_gt) truth = LoadTruth(a_.gt, job.stem, job.cloud.size());
    // beside the outputs' subfolders: DIR/images/<the output's folder below DIR>
    WriteImages((out / "images" / fs::path(name).parent_path()).string(), job.stem, job.cloud,
                frame, segmenter_.params(), truth.empty() ? nullptr : &truth);
    return drive_out_ ? "" : name;
  }

  // "<stem>: N points, G % ground, T ms", and the invalid points by reason when there are any:
  // " (K invalid: a NaN/Inf, b at the origin, c out of range, d bad ring)", naming those > 0.
  static std::string FrameLine(const std::string& stem, const FrameRecord& r) {
    char buf[160];
    std::snprintf(buf, sizeof(buf), "%s: %zu points, %.1f %% ground, %.2f ms", stem.c_str(),
                  r.points, r.points ? 100.0 * double(r.ground) / double(r.points) : 0.0, r.ms);
    std::string line = buf;
    if (r.invalid) {
      std::string why;
      const std::pair<size_t, const char*> reasons[] = {{r.reasons.not_finite, "NaN/Inf"},
                                                        {r.reasons.at_origin, "at the origin"},
                                                        {r.reasons.out_of_range, "out of range"},
                                                        {r.reasons.bad_ring, "bad ring"}};
      for (const auto& [count, name] : reasons)
        if (count) why += (why.empty() ? "" : ", ") + std::to_string(count) + " " + name;
      line += " (" + std::to_string(r.invalid) + " invalid: " + why + ")";
    }
    return line + "\n";
  }

  const SegmentArgs& a_;
  Segmenter& segmenter_;
  FrameSource& source_;
  FrameReport* report_;  // optional, not owned (also index_, drive_out_)
  DriveIndex* index_;
  LabelledDrive* drive_out_;
  Progress progress_;
  Timings timings_;
  std::deque<FrameInput> jobs_;
  std::set<std::string> made_;  // output folders made so far
  size_t failures_ = 0;
  size_t frames_ = 0;   // segmented and written
  size_t invalid_ = 0;  // points of those frames labelled invalid
  bool noted_ = false;  // a reader's note was printed
};

// The frames the inputs name, read one ahead (ReadAhead): the cloud files (folders expanded), or
// the drive's topic (chosen by ChooseCloudTopic; *topic set to it).
// A drive whose topics cannot be listed (damage where a .db3 keeps its counts) is still read
// up to the damage when --topic names the topic: a warning then, and no count for the progress.
std::unique_ptr<FrameSource> OpenSource(const SegmentArgs& a, std::string* topic) {
  if (!a.drive) {
    std::vector<std::string> files;
    for (const RunInput& f : a.files) files.push_back(f.path);
    return ReadAhead(OpenFileSource(std::move(files), a.read));
  }
  const std::string& drive = a.inputs[0];
  std::unique_ptr<DriveReader> reader = OpenDrive(drive, a.read_threads);
  std::vector<DriveTopic> topics;
  try {
    topics = reader->Topics();
    *topic = ChooseCloudTopic(drive, topics, a.topic);
  } catch (const IoError& e) {
    if (a.topic.empty())
      throw IoError(drive, std::string("its topics cannot be listed (") + e.what() +
                               "); --topic T reads T's messages up to the damage");
    if (!a.quiet)
      std::fprintf(stderr, "lpir-gseg segment: warning: %s; reading %s up to the damage\n",
                   e.what(), a.topic.c_str());
    *topic = a.topic;
  }
  size_t count = 0;  // a range's share is unknown
  for (const DriveTopic& t : topics)
    if (t.name == *topic && a.chunks.first == 0) count = size_t(t.messages);
  return ReadAhead(OpenDriveSource(drive, std::move(reader), *topic, a.chunks, count,
                                   a.format == "mcap" || a.format == "bag"));
}

}  // namespace

int RunSegment(int argc, char** argv) {
  const Args args(
      argc, argv,
      {"--images", "--nuscenes", "--quiet", "--verbose", "--timings", "--recursive", "--help"},
      {"--sensor", "--out", "--format", "--gt", "--max-points", "--backend", "--device", "--batch",
       "--topic", "--report", "--chunks", "--read-threads"},
      {"--set"});
  if (args.Has("--help")) {
    std::fputs(kHelp, stdout);
    std::fputs(kExitCodesLine, stdout);
    return kExitOk;
  }
  const SegmentArgs a = ParseSegmentArgs(args);
  const SensorProfile sensor = LoadProfileWithSettings(a.sensor, args);
  std::string topic;
  std::unique_ptr<FrameSource> source = OpenSource(a, &topic);
  Segmenter segmenter(sensor, a.options);
  if (!a.quiet && a.options.backend == Backend::kAuto && segmenter.backend() == Backend::kCpu)
    std::fprintf(stderr, "lpir-gseg segment: note: %s\n", segmenter.backend_note().c_str());
  const fs::path out(a.out_dir);
  if (a.drive) MakeOutputFolder(a.out_dir);  // a cloud file's folder: when its output is written
  std::unique_ptr<FrameReport> report;
  if (!a.report.empty())
    report = std::make_unique<FrameReport>(a.report, BackendName(segmenter), DeviceName(segmenter));
  std::unique_ptr<DriveIndex> index;
  std::unique_ptr<LabelledDrive> drive_out;
  if (a.drive) index = std::make_unique<DriveIndex>((out / "index.csv").string());
  if (a.format == "mcap" || a.format == "bag") {
    const fs::path path = out / (fs::path(a.inputs[0]).stem().string() + "." + a.format);
    std::error_code ec;
    if (fs::equivalent(path, a.inputs[0], ec))
      throw std::invalid_argument(path.string() + " is the drive being read: give --format " +
                                  a.format + " another --out");
    drive_out = std::make_unique<LabelledDrive>(
        a.inputs[0], path.string(), topic,
        a.format == "bag" ? LabelledDrive::Format::kBag : LabelledDrive::Format::kMcap);
  }
  const std::string on =
      segmenter.backend() == Backend::kVulkan ? segmenter.backend_note() : "the CPU reference";
  const size_t total = source->count();
  const std::string units = std::string(source->unit()) + (total == 1 ? "" : "s");
  const std::string what =
      a.drive ? units + " of " + topic + " in " + a.inputs[0] : units;  // "30 files"
  if (a.verbose)
    std::printf("segmenting %zu %s with sensor '%s' on %s\n", total, what.c_str(),
                segmenter.sensor().name.c_str(), on.c_str());
  const auto start = std::chrono::steady_clock::now();
  size_t failures = 0;
  std::string summary;
  {
    SegmentRun run(a, segmenter, *source, report.get(), index.get(), drive_out.get());
    failures = run.Run();
    if (index) index->Close();
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (report) report->Close(run.frames(), failures, seconds);
    if (!a.quiet) {
      // "segmented 30 of 30 files on X in 1.20 s, 25.0 frames/s, 2 failed, 12 invalid points
      // (non-ground); labels in OUT": short, so that beside the note above it fits 120 columns
      // with a folder of some 35 characters; the failures only when there are some (the last
      // line counts them too); the sensor, and the invalid points by reason, with --verbose
      char buf[128];
      std::snprintf(buf, sizeof(buf), " in %.2f s, %.1f frames/s", seconds,
                    seconds > 0 ? double(run.frames()) / seconds : 0.0);
      if (failures) std::snprintf(buf + std::strlen(buf), 32, ", %zu failed", failures);
      // a drive whose count is unknown (0): "segmented 2 messages of /points in D ..."
      const std::string of = total || !a.drive ? " of " + std::to_string(total) : "";
      std::string line =
          "segmented " + std::to_string(run.frames()) + of + " " + what + " on " + on + buf;
      if (run.invalid())
        line += ", " + std::to_string(run.invalid()) + " invalid points (non-ground)";
      const std::string outputs = a.format == "label"  ? "labels"
                                  : a.format == "mcap" ? "labelled MCAP"
                                  : a.format == "bag"  ? "labelled bag"
                                                       : a.format + " clouds";
      line += run.frames() || a.drive ? "; " + outputs + " in " + a.out_dir + "\n"
                                      : "; nothing written\n";
      summary = line;
    }
  }  // the progress line ends here, above the summary
  std::fputs(summary.c_str(), stdout);
  if (failures) {
    if (a.drive)  // a damaged part may hold any number of messages: counted apart from them
      std::fprintf(stderr,
                   "lpir-gseg segment: %s: %zu problem%s (damaged parts, or messages that do not "
                   "decode, each named above); every other message labelled\n",
                   a.inputs[0].c_str(), failures, failures == 1 ? "" : "s");
    else
      std::fprintf(stderr, "lpir-gseg segment: %zu of %zu files failed\n", failures, total);
    return kExitSomeFailed;
  }
  return kExitOk;
}

}  // namespace lpir
