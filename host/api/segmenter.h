// The library's entry point: a Segmenter is made once per sensor and labels clouds one by one,
// on a Vulkan device (host/api/vulkan_pipeline.h) or on the CPU reference
// (host/api/cpu_pipeline.h), with the same bytes either way. Its buffers are allocated once, for
// options.max_points points; a frame allocates nothing on the device (and nothing on the host once
// its vectors have grown).
#pragma once
#include <cstddef>
#include <cstdint>
#include <deque>
#include <memory>
#include <string>
#include <vector>

#include "host/api/mount_estimate.h"
#include "reference_cpu/cloud.h"
#include "reference_cpu/frame.h"
#include "reference_cpu/params.h"
#include "reference_cpu/pipeline.h"
#include "reference_cpu/sensor.h"

namespace lpir {

class FrameBackend;  // host/api/frame_backend.h

// The largest cloud a segmenter takes unless told: the profile's max_points, else one point per
// pixel of the sensor's image and as many again for second returns (beams x width x 2).
size_t DefaultMaxPoints(const SensorProfile& sensor);

enum class Backend {
  kAuto,    // Vulkan on a GPU (no CPU driver such as lavapipe: the reference is faster on the
            // same cores) when one can be set up, else the CPU reference (backend_note says
            // why); with SegmenterOptions::device named, as kVulkan
  kCpu,     // the CPU reference
  kVulkan,  // Vulkan on any usable device, CPU drivers included, or an error
};
// "auto", "cpu" or "vulkan" (std::invalid_argument otherwise).
Backend ParseBackend(const std::string& name);

struct SegmenterOptions {
  Backend backend = Backend::kAuto;
  std::string device;     // Vulkan device: "" the first usable (discrete first; kAuto: no CPU
                          // driver), digits an index, else a part of its name (`lpir-gseg devices`
                          // lists them; a named device may be a CPU driver)
  size_t max_points = 0;  // a larger cloud is an error; 0: DefaultMaxPoints(sensor)
  // Submit may run this many frames (batch > 1: batches) ahead of Collect.
  uint32_t frames_in_flight = 2;
  // Vulkan: frames recorded in one command buffer, interleaved pass by pass (offline relabelling:
  // the batch pays for one frame's barriers). Submit queues clouds until `batch` wait, or until
  // Collect asks for one of them. 1: each frame on its own.
  uint32_t batch = 1;
  // Every buffer of every stage in the returned Frame (pictures, debugging), not only label and
  // why; on Vulkan read back from the frame's slot when it is collected.
  bool all_buffers = false;
  bool validation = false;  // Vulkan validation layer (messages go to stderr)
  // CPU backend: the threads its frames share (host/api/cpu_pipeline.h); 0: every core this process
  // may run on (AvailableCores()), 1: each frame on the calling thread when it is collected, as
  // the reference always ran. A frame collected alone runs on all of them; frames in flight run
  // side by side, threads / (frames_in_flight * batch) each. Never changes a byte of the result.
  uint32_t threads = 0;

  static SegmenterOptions For(Backend backend) {
    SegmenterOptions options;
    options.backend = backend;
    return options;
  }
};

class Segmenter {
 public:
  // Throws std::invalid_argument for an inconsistent profile or options, std::runtime_error when
  // Backend::kVulkan was asked for and no device could be set up (a device limit that max_points
  // exceeds included: the message names it); kAuto falls back to the CPU reference then.
  explicit Segmenter(const SensorProfile& sensor, const SegmenterOptions& options = {});
  ~Segmenter();
  Segmenter(Segmenter&&) noexcept;
  Segmenter& operator=(Segmenter&&) noexcept;

  // Labels one cloud: Submit then Collect. A non-spinning profile (pattern rosette or band) sets
  // every point's row by its elevation: a ring field is ignored. With `mount per_frame` each
  // cloud's mount is estimated (EstimateMount) before it is staged. The frame stays valid until the
  // next Segment or Collect. Throws std::length_error when the cloud holds more than max_points
  // points, std::invalid_argument when its ring field does not match its size or does not fit the
  // profile (SensorFitError: rings past the beams on more than 1 % of the points),
  // std::runtime_error when the device fails.
  const Frame& Segment(const Cloud& cloud, FrameTimes* times = nullptr);

  // Frames in flight: Submit queues a cloud (copied; it need not outlive the call) while
  // CanSubmit(), Collect returns the oldest pending one (in submission order), valid until the
  // next Collect or Segment. Same errors as Segment; Submit when !CanSubmit() is a logic_error.
  // The slots form frames_in_flight blocks of `batch` slots; a batch fills one block (a partial
  // one, submitted by Collect, leaves the rest of its block unused) and may start only in a
  // block with no frame pending: with batch 1, CanSubmit() is pending() < frames_in_flight.
  void Submit(const Cloud& cloud);
  // Submit without the copy: the CPU backend reads `cloud` in place, so the caller keeps it alive
  // and unchanged until Collect has returned its frame (segment's jobs hold their clouds so).
  void SubmitBorrowed(const Cloud& cloud);
  const Frame& Collect(FrameTimes* times = nullptr);
  bool CanSubmit() const;
  size_t pending() const { return pending_.size(); }
  // The most frames pending at once: options.frames_in_flight * options.batch.
  size_t frames_in_flight() const { return slots_; }

  // The backend in use (never kAuto), and one line saying which and why: "Vulkan on <device>",
  // "CPU reference (asked for)", "CPU reference: the only Vulkan device is a CPU driver (<name>);
  // --backend vulkan uses it", "CPU reference, no Vulkan device: <reason>", "CPU reference, the
  // Vulkan set-up failed: <reason>".
  Backend backend() const { return backend_; }
  const std::string& backend_note() const { return backend_note_; }
  // The Vulkan device is a CPU driver (lavapipe; only kVulkan or a named device takes one: the
  // CPU reference is faster there, docs/speed.md). False on the CPU backend.
  bool on_cpu_driver() const;
  // Device memory allocated for the frame buffers, in bytes: constant for the segmenter's life
  // (everything is allocated at construction); 0 on the CPU.
  uint64_t device_bytes() const;

  // The mount the last collected frame was segmented with: the profile's (mount fixed), or
  // EstimateMount's for that cloud, with whether the estimate held (mount per_frame).
  const MountEstimate& mount() const { return mount_; }

  const Params& params() const { return params_; }
  const Tables& tables() const { return tables_; }
  const SensorProfile& sensor() const { return sensor_; }
  size_t max_points() const { return options_.max_points; }  // DefaultMaxPoints resolved
  // The CPU backend's threads, 0 resolved to AvailableCores() (1 on Vulkan).
  uint32_t threads() const { return options_.threads; }

 private:
  void CheckCloud(const Cloud& cloud) const;       // the one check of every cloud, before Stage
  void SubmitStaged();                             // the staged frames, as one batch
  void Submit(const Cloud& cloud, bool borrowed);  // Submit and SubmitBorrowed

  SensorProfile sensor_;
  SegmenterOptions options_;
  Params params_;
  Tables tables_;
  Backend backend_ = Backend::kCpu;
  std::string backend_note_;
  std::unique_ptr<FrameBackend> pipeline_;  // the backend's twin: CpuPipeline or VulkanPipeline
  uint32_t slots_ = 1;                      // frames_in_flight * batch
  uint32_t batch_ = 1;                      // slots a block: pipeline_->batch() (1 on the CPU)
  uint32_t staged_ = 0;           // the newest pending frames, staged but not yet submitted
  uint32_t next_block_ = 0;       // where the next batch starts
  std::deque<uint32_t> pending_;  // slots submitted, oldest first
  uint32_t next_slot_ = 0;
  Frame frame_;                             // what Segment and Collect return
  std::vector<MountEstimate> slot_mounts_;  // per slot: its frame's mount
  MountEstimate mount_;                     // the last collected frame's
  Cloud unringed_;  // scratch: a cloud without its ring field, for non-spinning profiles
};

}  // namespace lpir
