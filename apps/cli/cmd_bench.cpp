// lpir-gseg bench [options]: the benchmark suite in one command, one table (or --json). For the
// CPU reference (single-threaded) and the Vulkan device: each stage's median time and spread
// (reference: wall time; Vulkan: GPU timestamps) and their ratio; the whole frame end to end
// (upload, stages, download: wall time of Segmenter::Segment); sustained frames per second over
// a sequence with 1, 2 and 4 frames in flight; the CPU backend's thread scaling (1, 2 and every
// core this process may use: a frame's latency alone and frames per second with two frames in
// flight, and the parallel efficiency); peak host memory and device memory allocated; and the
// scaling of cost with points and image size from 16 to 256 beams (simulated streets: VLP-16,
// then OS1-128's field of view with 32, 64, 128 and 256 beams). The per-stage table, the CPU's
// throughput and the scaling table run the reference on one thread.
// Every timed configuration first checks that its labels equal the CPU reference's byte for byte.
// The counted GPU cost: for each shape (LPIR_VK_SHAPE=gpu and cpu, set before its pipeline is
// made) every scan once through a FramePipeline of its own, the commands of each frame counted
// as they are recorded (host/vk/command_buffer.h, RecordCounts), and its labels compared with
// the reference's: exit code kExitRefused (apps/cli/exit_codes.h), after the report, when they
// differ.
// The CPU and the device are timed in turns, a round of the scans each, so drifts of the
// machine's speed fall on both alike.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "apps/cli/args.h"
#include "apps/cli/commands.h"
#include "apps/cli/exit_codes.h"
#include "apps/cli/timing.h"
#include "apps/sim/scene.h"
#include "host/api/cpu_pipeline.h"
#include "host/api/segmenter.h"
#include "host/gpu/frame_pipeline.h"
#include "host/io/kitti_bin.h"
#include "host/io/sensor_profile.h"
#include "host/vk/context.h"
#include "reference_cpu/wide.h"

namespace fs = std::filesystem;

namespace lpir {
namespace {

const char kHelp[] =
    "usage: lpir-gseg bench [--data DIR] [--runs N] [--scaling-runs N] [--frames N]\n"
    "                       [--device D] [--json]\n"
    "  --data DIR         real scans (default ../shared/data beside the repository, or\n"
    "                     $LPIR_DATA_DIR): kitti/00/velodyne/*.bin; absent: simulated HDL-64E\n"
    "                     streets instead\n"
    "  --runs N           timed frames per scan and backend (default 20)\n"
    "  --scaling-runs N   timed frames per sensor in the scaling table (default 15)\n"
    "  --frames N         frames per throughput measurement (default 24)\n"
    "  --device D         Vulkan device (index or name part; none such: exit code 4); without\n"
    "                     --device and without a usable device, CPU rows only\n"
    "  --json             one JSON object instead of the table\n";

constexpr int kThreadRounds = 5;  // rounds of the thread table

struct Spread {
  double median = 0, p25 = 0, p75 = 0;
};
Spread SpreadOf(std::vector<double> v) {
  Spread s;
  if (v.empty()) return s;
  std::sort(v.begin(), v.end());
  auto at = [&](double q) {  // linear interpolation between order statistics
    const double x = q * double(v.size() - 1);
    const size_t i = size_t(x);
    const double f = x - double(i);
    return i + 1 < v.size() ? v[i] * (1 - f) + v[i + 1] * f : v[i];
  };
  s.median = at(0.5), s.p25 = at(0.25), s.p75 = at(0.75);
  return s;
}

// What one backend's timed frames gave.
struct Timed {
  std::vector<double> wall, stage[kStageCount], upload, download, gpu_total;
};

// Labels of every cloud on `s` equal to the reference's, or RefusedError.
void CheckAgainstReference(Segmenter& s, Segmenter& reference, const std::vector<Cloud>& clouds,
                           const std::vector<std::string>& names) {
  for (size_t k = 0; k < clouds.size(); ++k) {
    const Labels got = s.Segment(clouds[k]).label;
    if (got != reference.Segment(clouds[k]).label)
      throw RefusedError(names[k] + ": the labels of " + s.backend_note() +
                         " differ from the CPU reference's; nothing timed");
  }
}

// One frame of `cloud` on `s`, its times appended to `t`.
void TimeFrame(Segmenter& s, const Cloud& cloud, Timed& t) {
  FrameTimes ft;
  const auto t0 = Clock::now();
  s.Segment(cloud, &ft);
  t.wall.push_back(Ms(t0, Clock::now()));
  for (int k = 0; k < kStageCount; ++k) t.stage[k].push_back(ft.stage_ms[k]);
  t.upload.push_back(ft.upload_ms), t.download.push_back(ft.download_ms);
  t.gpu_total.push_back(ft.total_ms);
}

// `runs` rounds of every cloud on the CPU, then (when there is one) on the device: on a machine
// whose speed drifts (a shared host) both see the same spells, and each backend still runs a
// sequence, its buffers and caches warm as in use (rather than frame by frame in turns).
void TimeFramesInTurns(Segmenter& cpu, Segmenter* gpu, const std::vector<Cloud>& clouds, int runs,
                       Timed& c, Timed& g) {
  for (int r = 0; r < runs; ++r) {
    for (const Cloud& cloud : clouds) TimeFrame(cpu, cloud, c);
    if (gpu)
      for (const Cloud& cloud : clouds) TimeFrame(*gpu, cloud, g);
  }
}

// Frames per second over `frames` frames (the clouds in turn) with `in_flight` frames (batches
// of `batch` frames when batch > 1) in flight.
double Throughput(const SensorProfile& sensor, SegmenterOptions options,
                  const std::vector<Cloud>& clouds, uint32_t in_flight, int frames,
                  uint32_t batch = 1) {
  options.frames_in_flight = in_flight;
  options.batch = batch;
  Segmenter s(sensor, options);
  s.Segment(clouds[0]);  // warm
  const auto t0 = Clock::now();
  for (int submitted = 0, collected = 0; collected < frames;) {
    while (submitted < frames && s.CanSubmit())
      s.Submit(clouds[size_t(submitted++) % clouds.size()]);
    s.Collect();
    ++collected;
  }
  return 1000.0 * frames / Ms(t0, Clock::now());
}

double PeakRssMiB() {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line))
    if (line.rfind("VmHWM:", 0) == 0) return std::atof(line.c_str() + 6) / 1024.0;
  return -1;
}

std::string CpuName() {
  std::ifstream info("/proc/cpuinfo");
  std::string line;
  while (std::getline(info, line))
    if (line.rfind("model name", 0) == 0) {
      const size_t colon = line.find(':');
      if (colon != std::string::npos) return line.substr(colon + 2);
    }
  return "CPU";
}

// os1-128's field of view and width with `beams` beams spread evenly over it: the 32, 64 and
// 256-beam rows of the scaling table, so that from row to row only the beam count changes and the
// points double.
SensorProfile Os1With(const SensorProfile& os1_128, uint32_t beams) {
  SensorProfile s = os1_128;
  s.name = "os1-" + std::to_string(beams);
  s.beams = beams;
  s.elevation_deg.clear();
  const float top = os1_128.elevation_deg.front(), bottom = os1_128.elevation_deg.back();
  for (uint32_t b = 0; b < beams; ++b)
    s.elevation_deg.push_back(top + (bottom - top) * float(b) / float(beams - 1));
  return s;
}

struct ScalingRow {
  std::string sensor;
  uint32_t beams = 0, width = 0;
  size_t points = 0;
  double cpu_ms = 0, vulkan_ms = -1;
};

// What one shape's frames cost, counted at record time (RecordCounts), over every frame. Indirect
// dispatches are in the dispatch counts but not in `workgroups` (their counts are read on the
// GPU). Reported per frame: dispatches min and max, barriers the most of any frame (the test
// holds both constant), workgroups the mean, bytes per point over all frames.
struct GpuCost {
  std::string shape;
  uint32_t dispatches_min = UINT32_MAX, dispatches_max = 0, indirect_max = 0;
  uint32_t barriers_min = UINT32_MAX, barriers_max = 0;
  uint64_t workgroups = 0, upload_bytes = 0, download_bytes = 0, points = 0, device_bytes = 0;
  size_t frames = 0;
  bool labels_equal_reference = true;
  std::string error;  // the pipeline could not be made or a frame failed: nothing counted
};

// Sets LPIR_VK_SHAPE to `shape` for the pipeline's creation (where it is read), then puts the
// variable back as it was. Every cloud once, slot 0, labels compared with `reference_labels`.
GpuCost MeasureGpuCost(const std::string& shape, const vk::Context& context,
                       const Segmenter& reference, const std::vector<Cloud>& clouds,
                       const std::vector<Labels>& reference_labels, size_t max_points) {
  GpuCost cost;
  cost.shape = shape;
  const char* before = std::getenv("LPIR_VK_SHAPE");
  const std::string saved = before ? before : "";
  ::setenv("LPIR_VK_SHAPE", shape.c_str(), 1);
  vk::Result<vk::FramePipeline> made = vk::FramePipeline::Create(
      context, reference.params(), reference.tables(), uint32_t(max_points), 1);
  if (before)
    ::setenv("LPIR_VK_SHAPE", saved.c_str(), 1);
  else
    ::unsetenv("LPIR_VK_SHAPE");
  if (!made.ok()) {
    cost.error = made.error().message;
    cost.labels_equal_reference = false;
    return cost;
  }
  vk::FramePipeline pipeline = std::move(made).value();
  cost.device_bytes = pipeline.device_bytes();
  Frame frame;
  for (size_t k = 0; k < clouds.size(); ++k) {
    vk::Status status = pipeline.Submit(0, clouds[k]);
    const vk::RecordCounts counts = pipeline.last_counts();
    if (status.ok()) status = pipeline.Collect(0, frame);
    if (!status.ok()) {
      cost.error = status.message();
      cost.labels_equal_reference = false;
      return cost;
    }
    cost.dispatches_min = std::min(cost.dispatches_min, counts.dispatches);
    cost.dispatches_max = std::max(cost.dispatches_max, counts.dispatches);
    cost.indirect_max = std::max(cost.indirect_max, counts.indirect_dispatches);
    cost.barriers_min = std::min(cost.barriers_min, counts.barriers);
    cost.barriers_max = std::max(cost.barriers_max, counts.barriers);
    cost.workgroups += counts.workgroups;
    cost.upload_bytes += counts.upload_bytes;
    cost.download_bytes += counts.download_bytes;
    cost.points += clouds[k].size();
    ++cost.frames;
    if (frame.label != reference_labels[k]) cost.labels_equal_reference = false;
  }
  return cost;
}

// Every shape counted labelled every frame as the reference did (exit code 1 otherwise).
bool AllEqual(const std::vector<GpuCost>& costs) {
  for (const GpuCost& gc : costs)
    if (!gc.labels_equal_reference) return false;
  return true;
}

std::string JsonString(const std::string& s) {
  std::string out = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out + "\"";
}

// What the command line asks for.
struct BenchArgs {
  int runs = 20, scaling_runs = 15, frames = 24;
  std::string data, device;
  bool json = false;
};

// The command line's options, checked; std::invalid_argument names the bad one.
BenchArgs ParseBenchArgs(const Args& args) {
  BenchArgs a;
  a.runs = int(args.GetNumber("--runs", 20));
  a.scaling_runs = int(args.GetNumber("--scaling-runs", 15));
  a.frames = int(args.GetNumber("--frames", 24));
  if (a.runs < 1 || a.scaling_runs < 1 || a.frames < 1)
    throw std::invalid_argument("--runs, --scaling-runs and --frames must be at least 1");
  const char* env_data = std::getenv("LPIR_DATA_DIR");
  // ../shared/data beside the repository, whose sensors/ folder SensorsDir() is.
  const std::string beside =
      (fs::path(SensorsDir()).parent_path().parent_path() / "shared" / "data").string();
  a.data = args.Get("--data", env_data && *env_data ? env_data : beside);
  a.device = args.Get("--device");
  a.json = args.Has("--json");
  return a;
}

// The timed frames and their names.
struct Scans {
  std::vector<Cloud> clouds;
  std::vector<std::string> names;
  size_t points = 0;  // over all clouds
};

// The six consecutive kitti/00 scans under `data`, or simulated HDL-64E streets without them.
Scans LoadScans(const std::string& data, const SensorProfile& hdl64e) {
  Scans s;
  const fs::path kitti = fs::path(data) / "kitti" / "00" / "velodyne";
  std::error_code ec;
  if (fs::is_directory(kitti, ec)) {
    for (const auto& entry : fs::directory_iterator(kitti, ec))
      if (entry.path().extension() == ".bin") s.names.push_back(entry.path().string());
    std::sort(s.names.begin(), s.names.end());
    for (const std::string& n : s.names) s.clouds.push_back(ReadKittiBin(n));
    for (std::string& n : s.names) n = "kitti/00/" + fs::path(n).stem().string();
  }
  if (s.clouds.empty()) {
    for (uint32_t seed = 1; seed <= 6; ++seed) {
      SimOptions o;
      o.seed = seed;
      s.clouds.push_back(Simulate(hdl64e, o).cloud);
      s.names.push_back("simulated hdl64e street " + std::to_string(seed));
    }
  }
  for (const Cloud& c : s.clouds) s.points += c.size();
  return s;
}

// The CPU backend at one thread count: a frame's median latency alone (Segment) and the median
// frames per second with two frames in flight over rounds; efficiency: fps / (threads * fps of
// one thread), 1 for perfect scaling.
struct ThreadRow {
  uint32_t threads = 0;
  double frame_ms = 0, fps = 0, efficiency = 0;
};

// Everything the report shows.
struct BenchReport {
  std::string device, cpu_name, first_scan;
  size_t frames = 0, mean_points = 0;
  int runs = 0, throughput_frames = 0, scaling_runs = 0;
  bool has_gpu = false;
  Timed c, g;                                     // the CPU's and the device's timed frames
  double cpu_fps = 0, fps[4] = {-1, -1, -1, -1};  // 1, 2, 4 in flight, batches of 8
  double rss = 0;
  uint64_t device_bytes = 0;
  std::vector<GpuCost> costs;
  std::vector<ScalingRow> scaling;
  uint32_t cores = 0;              // AvailableCores()
  std::vector<ThreadRow> threads;  // 1, 2 and `cores` threads (each once)
};

// Both shapes' counted GPU cost of every scan on the device `device`.
std::vector<GpuCost> MeasureGpuCosts(const std::string& device, Segmenter& reference,
                                     const std::vector<Cloud>& clouds, size_t max_points) {
  vk::ContextOptions context_options;
  context_options.device = device;
  vk::Result<vk::Context> context = vk::Context::Create(context_options);
  if (!context.ok()) throw std::runtime_error("Vulkan: " + context.error().message);
  std::vector<Labels> reference_labels;
  for (const Cloud& cloud : clouds) reference_labels.push_back(reference.Segment(cloud).label);
  std::vector<GpuCost> costs;
  for (const char* shape : {"gpu", "cpu"})
    costs.push_back(
        MeasureGpuCost(shape, context.value(), reference, clouds, reference_labels, max_points));
  return costs;
}

// Frames per second of the CPU, and with a device of 1, 2 and 4 frames in flight and of two
// batches of 8 in flight.
void MeasureThroughput(const SensorProfile& sensor, const SegmenterOptions& cpu_options,
                       const SegmenterOptions& vk_options, const std::vector<Cloud>& clouds,
                       BenchReport& r) {
  r.cpu_fps = Throughput(sensor, cpu_options, clouds, 1, r.throughput_frames);
  if (!r.has_gpu) return;
  const uint32_t in_flight[3] = {1, 2, 4};
  constexpr uint32_t kBatch = 8;  // frames a batch, two batches in flight
  for (int k = 0; k < 3; ++k)
    r.fps[k] = Throughput(sensor, vk_options, clouds, in_flight[k], r.throughput_frames);
  r.fps[3] = Throughput(sensor, vk_options, clouds, 2, r.throughput_frames, kBatch);
}

// The CPU backend's thread scaling over 1, 2 and every available core (each count once):
// `rounds` rounds, each timing every count in turn (so that a spell of load on a shared machine
// falls on all alike), a round being one Segment of every cloud (latency) and `frames` frames
// with two in flight (throughput). Every count's labels are checked against `reference` first.
std::vector<ThreadRow> MeasureThreads(const SensorProfile& sensor, SegmenterOptions options,
                                      Segmenter& reference, const Scans& scans, uint32_t cores,
                                      int frames, int rounds) {
  std::vector<uint32_t> counts = {1, 2, cores};
  std::sort(counts.begin(), counts.end());
  counts.erase(std::unique(counts.begin(), counts.end()), counts.end());
  std::vector<std::unique_ptr<Segmenter>> alone;
  for (uint32_t n : counts) {
    options.threads = n;
    alone.push_back(std::make_unique<Segmenter>(sensor, options));
    CheckAgainstReference(*alone.back(), reference, scans.clouds, scans.names);
  }
  std::vector<std::vector<double>> latency(counts.size()), fps(counts.size());
  for (int round = 0; round < rounds; ++round)
    for (size_t k = 0; k < counts.size(); ++k) {
      for (const Cloud& cloud : scans.clouds) {
        const auto t0 = Clock::now();
        alone[k]->Segment(cloud);
        latency[k].push_back(Ms(t0, Clock::now()));
      }
      options.threads = counts[k];
      fps[k].push_back(Throughput(sensor, options, scans.clouds, 2, frames));
    }
  std::vector<ThreadRow> rows;
  for (size_t k = 0; k < counts.size(); ++k)
    rows.push_back({counts[k], SpreadOf(latency[k]).median, SpreadOf(fps[k]).median, 0});
  for (ThreadRow& row : rows) row.efficiency = row.fps / (row.threads * rows[0].fps);
  return rows;
}

// The scaling table: a simulated street for VLP-16 and OS1-128's field of view with 32 to 256
// beams, every row's labels checked, then `runs` end-to-end frames of each row round-robin, so
// that a burst of load on the machine slows all rows alike instead of one row's whole block.
std::vector<ScalingRow> MeasureScaling(const SegmenterOptions& cpu_options,
                                       const SegmenterOptions& vk_options, bool has_gpu, int runs) {
  const SensorProfile os1_128 = LoadSensorProfile("os1-128", SensorsDir());
  std::vector<SensorProfile> sensors = {LoadSensorProfile("vlp16", SensorsDir())};
  for (uint32_t beams : {32u, 64u, 128u, 256u}) sensors.push_back(Os1With(os1_128, beams));
  std::vector<ScalingRow> scaling;
  std::vector<std::vector<Cloud>> scenes;
  std::vector<std::unique_ptr<Segmenter>> cpus, gpus;
  for (const SensorProfile& sensor : sensors) {
    SimOptions o;
    o.seed = 1;
    scenes.push_back({Simulate(sensor, o).cloud});
    const std::vector<std::string> scene_name = {sensor.name + " simulated street"};
    SegmenterOptions co = cpu_options, vo = vk_options;
    co.max_points = vo.max_points = std::max<size_t>(scenes.back()[0].size(), 1);
    Segmenter sref(sensor, co);
    cpus.push_back(std::make_unique<Segmenter>(sensor, co));
    CheckAgainstReference(*cpus.back(), sref, scenes.back(), scene_name);
    if (has_gpu) {
      gpus.push_back(std::make_unique<Segmenter>(sensor, vo));
      CheckAgainstReference(*gpus.back(), sref, scenes.back(), scene_name);
    }
    scaling.push_back({sensor.name, sensor.beams, sensor.width, scenes.back()[0].size(), 0, -1});
  }
  std::vector<Timed> cpu_t(sensors.size()), gpu_t(sensors.size());
  for (int r = 0; r < runs; ++r)
    for (size_t k = 0; k < sensors.size(); ++k)
      TimeFramesInTurns(*cpus[k], has_gpu ? gpus[k].get() : nullptr, scenes[k], 1, cpu_t[k],
                        gpu_t[k]);
  for (size_t k = 0; k < sensors.size(); ++k) {
    scaling[k].cpu_ms = SpreadOf(cpu_t[k].wall).median;
    if (has_gpu) scaling[k].vulkan_ms = SpreadOf(gpu_t[k].wall).median;
  }
  return scaling;
}

// The device's segmenter, its name in `device`; or none, and "none (why)".
std::unique_ptr<Segmenter> VulkanOrNone(const SensorProfile& sensor,
                                        const SegmenterOptions& options, std::string& device) {
  try {
    auto gpu = std::make_unique<Segmenter>(sensor, options);
    device = gpu->backend_note().substr(std::string("Vulkan on ").size());
    return gpu;
  } catch (const std::exception& e) {
    device = std::string("none (") + e.what() + ")";
    return nullptr;
  }
}

// Checks, times and measures everything the report shows.
BenchReport Measure(const BenchArgs& a) {
  auto say = [&](const char* what) {
    if (!a.json) std::fprintf(stderr, "bench: %s\n", what);
  };
  const SensorProfile hdl64e = LoadSensorProfile("hdl64e", SensorsDir());
  const Scans scans = LoadScans(a.data, hdl64e);
  BenchReport r;
  r.frames = scans.clouds.size();
  r.mean_points = scans.points / scans.clouds.size();
  r.first_scan = scans.names[0];
  r.runs = a.runs, r.throughput_frames = a.frames, r.scaling_runs = a.scaling_runs;

  SegmenterOptions cpu_options = SegmenterOptions::For(Backend::kCpu);
  cpu_options.threads = 1;
  SegmenterOptions vk_options = SegmenterOptions::For(Backend::kVulkan);
  vk_options.device = a.device;
  vk_options.frames_in_flight = 1;
  Segmenter reference(hdl64e, cpu_options);
  std::unique_ptr<Segmenter> gpu = VulkanOrNone(hdl64e, vk_options, r.device);
  r.has_gpu = gpu != nullptr;
  if (!r.has_gpu && !a.device.empty())  // asked for by name: no CPU-only report instead
    throw std::runtime_error("--device " + a.device + ": " + r.device);
  r.cpu_name = CpuName() + ", 1 thread" + (WideKernels() ? ", AVX2 kernels" : "");

  say("checking the labels of both backends against the reference");
  Segmenter cpu(hdl64e, cpu_options);
  CheckAgainstReference(cpu, reference, scans.clouds, scans.names);
  if (gpu) CheckAgainstReference(*gpu, reference, scans.clouds, scans.names);
  if (gpu) {
    say("counting the commands of a frame in each shape");
    r.costs = MeasureGpuCosts(vk_options.device, reference, scans.clouds, gpu->max_points());
  }
  say("timing frames");
  TimeFramesInTurns(cpu, gpu.get(), scans.clouds, a.runs, r.c, r.g);
  r.device_bytes = gpu ? gpu->device_bytes() : 0;
  say("throughput");
  MeasureThroughput(hdl64e, cpu_options, vk_options, scans.clouds, r);
  // Peak host memory of the KITTI frames and the throughput runs, before the scaling table keeps
  // ten segmenters of its own alive.
  r.rss = PeakRssMiB();
  say("scaling");
  r.scaling = MeasureScaling(cpu_options, vk_options, r.has_gpu, a.scaling_runs);
  say("threads");
  r.cores = AvailableCores();
  r.threads =
      MeasureThreads(hdl64e, cpu_options, reference, scans, r.cores, a.frames, kThreadRounds);
  return r;
}

std::string JsonSpread(const Spread& s) {
  char b[128];
  std::snprintf(b, sizeof b, "{\"median_ms\": %.4f, \"p25_ms\": %.4f, \"p75_ms\": %.4f}", s.median,
                s.p25, s.p75);
  return b;
}

// The "stages" array's entries: every stage's spreads on both backends (-1 without a device).
std::string JsonStages(const BenchReport& r) {
  std::string j;
  for (int k = 0; k < kStageCount; ++k) {
    char b[256];
    const Spread cs = SpreadOf(r.c.stage[k]), gs = SpreadOf(r.g.stage[k]);
    const bool gpu = r.has_gpu;
    std::snprintf(b, sizeof b,
                  "%s{\"name\": \"%s\", \"cpu_ms\": %.4f, \"vulkan_ms\": %.4f, "
                  "\"cpu_p25_ms\": %.4f, \"cpu_p75_ms\": %.4f, \"vulkan_p25_ms\": %.4f, "
                  "\"vulkan_p75_ms\": %.4f}",
                  k ? ", " : "", kStageNames[k], cs.median, gpu ? gs.median : -1.0, cs.p25, cs.p75,
                  gpu ? gs.p25 : -1.0, gpu ? gs.p75 : -1.0);
    j += b;
  }
  return j;
}

// The "scaling" array's entries.
std::string JsonScaling(const std::vector<ScalingRow>& scaling) {
  std::string j;
  for (size_t k = 0; k < scaling.size(); ++k) {
    const ScalingRow& r = scaling[k];
    char b[512];
    std::snprintf(b, sizeof b,
                  "%s{\"sensor\": \"%s\", \"beams\": %u, \"width\": %u, \"points\": %zu, "
                  "\"cpu_ms\": %.4f, \"vulkan_ms\": %.4f}",
                  k ? ", " : "", r.sensor.c_str(), r.beams, r.width, r.points, r.cpu_ms,
                  r.vulkan_ms);
    j += b;
  }
  return j;
}

// The "threads" object: the cores, and one entry per thread count.
std::string JsonThreads(const BenchReport& r) {
  std::string j = "{\"cores\": " + std::to_string(r.cores) + ", \"rows\": [";
  for (size_t k = 0; k < r.threads.size(); ++k) {
    const ThreadRow& t = r.threads[k];
    char b[256];
    std::snprintf(b, sizeof b,
                  "%s{\"threads\": %u, \"frame_ms\": %.4f, \"fps\": %.2f, "
                  "\"efficiency\": %.3f}",
                  k ? ", " : "", t.threads, t.frame_ms, t.fps, t.efficiency);
    j += b;
  }
  return j + "]}";
}

// The "gpu_cost" object: one entry per shape, null without a device.
std::string JsonCosts(const std::vector<GpuCost>& costs) {
  if (costs.empty()) return "null";
  std::string j;
  for (size_t k = 0; k < costs.size(); ++k) {
    const GpuCost& gc = costs[k];
    j += (k ? ", " : "{") + JsonString(gc.shape) + ": ";
    if (!gc.error.empty()) {
      j += "{\"error\": " + JsonString(gc.error) + ", \"labels_equal_reference\": false}";
    } else {
      char b[512];
      const double frames_d = double(gc.frames);
      const double points_d = double(std::max<uint64_t>(gc.points, 1));
      std::snprintf(b, sizeof b,
                    "{\"frames\": %zu, \"dispatches_per_frame_min\": %u, "
                    "\"dispatches_per_frame_max\": %u, \"indirect_dispatches_per_frame\": %u, "
                    "\"barriers_per_frame\": %u, \"workgroups_per_frame\": %.1f, "
                    "\"upload_bytes_per_point\": %.3f, \"download_bytes_per_point\": %.3f, "
                    "\"device_mib\": %.1f, \"labels_equal_reference\": %s}",
                    gc.frames, gc.dispatches_min, gc.dispatches_max, gc.indirect_max,
                    gc.barriers_max, double(gc.workgroups) / frames_d,
                    double(gc.upload_bytes) / points_d, double(gc.download_bytes) / points_d,
                    double(gc.device_bytes) / (1 << 20),
                    gc.labels_equal_reference ? "true" : "false");
      j += b;
    }
  }
  return j + "}";
}

// The report as one JSON object.
std::string ReportJson(const BenchReport& r) {
  std::string j = "{\"device\": " + JsonString(r.device) + ", \"cpu\": " + JsonString(r.cpu_name) +
                  ", \"frames\": " + std::to_string(r.frames) +
                  ", \"mean_points\": " + std::to_string(r.mean_points) +
                  ", \"runs\": " + std::to_string(r.runs);
  j += ", \"end_to_end\": {\"cpu\": " + JsonSpread(SpreadOf(r.c.wall)) +
       (r.has_gpu ? ", \"vulkan\": " + JsonSpread(SpreadOf(r.g.wall))
                  : std::string(", \"vulkan\": null"));
  if (r.has_gpu) j += ", \"vulkan_gpu_total\": " + JsonSpread(SpreadOf(r.g.gpu_total));
  j += "}, \"stages\": [" + JsonStages(r);
  char b[512];
  std::snprintf(b, sizeof b,
                "], \"throughput_fps\": {\"cpu\": %.2f, \"1\": %.2f, \"2\": %.2f, \"4\": %.2f, "
                "\"batch_8\": %.2f}, "
                "\"peak_host_mib\": %.1f, \"device_mib\": %.1f, \"scaling\": [",
                r.cpu_fps, r.fps[0], r.fps[1], r.fps[2], r.fps[3], r.rss,
                double(r.device_bytes) / (1 << 20));
  j += b + JsonScaling(r.scaling) + "], \"threads\": " + JsonThreads(r) +
       ", \"gpu_cost\": " + JsonCosts(r.costs);
  return j + "}";
}

// The stage table: upload, every stage, download, GPU total and end to end, CPU beside device.
void PrintStages(const BenchReport& r) {
  std::printf("%-16s %-26s %-26s %8s   %s\n", "stage", "cpu ms median (p25-p75)",
              "vulkan ms median (p25-p75)", "vk/cpu", "device");
  auto row = [&](const char* name, const std::vector<double>& cv, const std::vector<double>& gv) {
    const Spread cs = SpreadOf(cv), gs = SpreadOf(gv);
    char cpu_text[64] = "-", gpu_text[64] = "-", ratio[32] = "-";
    if (!cv.empty())
      std::snprintf(cpu_text, sizeof cpu_text, "%.3f (%.3f-%.3f)", cs.median, cs.p25, cs.p75);
    if (r.has_gpu && !gv.empty()) {
      std::snprintf(gpu_text, sizeof gpu_text, "%.3f (%.3f-%.3f)", gs.median, gs.p25, gs.p75);
      if (!cv.empty() && cs.median > 0)
        std::snprintf(ratio, sizeof ratio, "%.1fx", gs.median / cs.median);
    }
    std::printf("%-16s %-26s %-26s %8s   %s\n", name, cpu_text, gpu_text, ratio, r.device.c_str());
  };
  const std::vector<double> none;
  row("upload", none, r.g.upload);
  for (int k = 0; k < kStageCount; ++k) row(kStageNames[k], r.c.stage[k], r.g.stage[k]);
  row("download", none, r.g.download);
  row("gpu total", none, r.g.gpu_total);
  row("end to end", r.c.wall, r.g.wall);
}

// One line per shape's counted GPU cost.
void PrintCosts(const BenchReport& r) {
  for (const GpuCost& gc : r.costs) {
    if (!gc.error.empty()) {
      std::printf("gpu cost, shape %s: %s   %s\n", gc.shape.c_str(), gc.error.c_str(),
                  r.device.c_str());
      continue;
    }
    const double points_d = double(std::max<uint64_t>(gc.points, 1));
    std::printf(
        "gpu cost, shape %s, per frame: %u-%u dispatches (%u indirect), %u barriers, "
        "%.0f workgroups (direct dispatches), %.2f B/point up, %.2f B/point down, "
        "%.1f MiB device; labels %s the reference's   %s\n",
        gc.shape.c_str(), gc.dispatches_min, gc.dispatches_max, gc.indirect_max, gc.barriers_max,
        double(gc.workgroups) / double(gc.frames), double(gc.upload_bytes) / points_d,
        double(gc.download_bytes) / points_d, double(gc.device_bytes) / (1 << 20),
        gc.labels_equal_reference ? "equal" : "DIFFER from", r.device.c_str());
  }
}

// The scaling table, each row's growth from the row above.
void PrintScaling(const BenchReport& r) {
  std::printf("\nscaling (simulated street, seed 1, median of %d end-to-end frames):\n",
              r.scaling_runs);
  std::printf("(x: growth from the row above; linear cost: time x equal to points x)\n");
  std::printf("%-10s %6s %6s %9s %9s %10s %10s %12s %14s   %s\n", "sensor", "beams", "width",
              "points", "points x", "cpu ms", "cpu x", "vulkan ms", "vulkan x", "device");
  for (size_t k = 0; k < r.scaling.size(); ++k) {
    const ScalingRow& s = r.scaling[k];
    char px[32] = "-", cr[32] = "-", gr[32] = "-", gms[32] = "-";
    if (k > 0) {
      const ScalingRow& q = r.scaling[k - 1];
      std::snprintf(px, sizeof px, "%.2f", double(s.points) / double(q.points));
      std::snprintf(cr, sizeof cr, "%.2f", s.cpu_ms / q.cpu_ms);
      if (r.has_gpu) std::snprintf(gr, sizeof gr, "%.2f", s.vulkan_ms / q.vulkan_ms);
    }
    if (r.has_gpu) std::snprintf(gms, sizeof gms, "%.2f", s.vulkan_ms);
    std::printf("%-10s %6u %6u %9zu %9s %10.2f %10s %12s %14s   %s\n", s.sensor.c_str(), s.beams,
                s.width, s.points, px, s.cpu_ms, cr, gms, gr, r.device.c_str());
  }
}

// The thread table.
void PrintThreads(const BenchReport& r) {
  std::printf(
      "\nthreads (CPU backend, %u cores available; medians of %d rounds: a frame alone, "
      "and frames/s with 2 in flight over %d frames):\n",
      r.cores, kThreadRounds, r.throughput_frames);
  std::printf("%8s %12s %10s %11s\n", "threads", "frame ms", "frames/s", "efficiency");
  for (const ThreadRow& t : r.threads)
    std::printf("%8u %12.2f %10.1f %11.2f\n", t.threads, t.frame_ms, t.fps, t.efficiency);
}

// The report as tables.
void PrintReport(const BenchReport& r) {
  std::printf("lpir-gseg bench: %zu frames (%s..., %zu points on average), %d runs each\n",
              r.frames, r.first_scan.c_str(), r.mean_points, r.runs);
  std::printf("CPU: %s | Vulkan device: %s\n\n", r.cpu_name.c_str(), r.device.c_str());
  PrintStages(r);
  std::printf(
      "\nthroughput (frames/s over %d frames): cpu %.1f | vulkan, frames in flight 1: "
      "%.1f, 2: %.1f, 4: %.1f, batches of 8: %.1f   %s\n",
      r.throughput_frames, r.cpu_fps, r.fps[0], r.fps[1], r.fps[2], r.fps[3], r.device.c_str());
  std::printf("memory: peak host RSS %.1f MiB | device memory allocated %.1f MiB   %s\n", r.rss,
              double(r.device_bytes) / (1 << 20), r.device.c_str());
  PrintCosts(r);
  PrintScaling(r);
  PrintThreads(r);
}

}  // namespace

int RunBench(int argc, char** argv) {
  const Args args(argc, argv, {"--json", "--help"},
                  {"--data", "--runs", "--scaling-runs", "--frames", "--device"});
  if (args.Has("--help")) {
    std::fputs(kHelp, stdout);
    std::fputs(kExitCodesLine, stdout);
    return kExitOk;
  }
  const BenchArgs a = ParseBenchArgs(args);
  const BenchReport r = Measure(a);
  if (a.json)
    std::printf("%s\n", ReportJson(r).c_str());
  else
    PrintReport(r);
  if (AllEqual(r.costs)) return kExitOk;
  std::fprintf(stderr,
               "lpir-gseg bench: refused: a shape's labels differ from the CPU reference's, or "
               "its pipeline failed (see the counted GPU cost)\n");
  return kExitRefused;
}

}  // namespace lpir
