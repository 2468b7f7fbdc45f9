// CpuPipeline: the CPU reference (RunReference) behind the slots of vk::FramePipeline. Stage
// copies the cloud into its slot, as the Vulkan twin copies it into the slot's staging buffer, or
// keeps a borrowed one where it is.
// With one thread every frame runs when it is collected, on the calling thread, straight into the
// caller's Frame: one set of frame buffers however many slots, reused from frame to frame (the
// reference as it always ran). With more, the frames pending share the threads out: a frame
// collected while it is the only one pending runs then, on the calling thread with every thread
// (Segment's case: one frame at a time, as soon as possible); frames in flight (a second frame
// submitted while one is pending) each run at once on their slot's own thread, side by side, with
// threads / slots threads each (at least one), and Collect hands the finished frame's buffers over
// by a swap. Either way the bytes are the reference's (reference_cpu/threads.h).
#pragma once
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <exception>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

#include "host/api/frame_backend.h"
#include "reference_cpu/params.h"

namespace lpir {

// The cores this process may run on (sched_getaffinity: what taskset, cgroups' cpusets and
// container limits leave it), at least 1: the default thread count of the CPU backend.
uint32_t AvailableCores();

class CpuPipeline final : public FrameBackend {
 public:
  // `threads` (at least 1): the threads the frames share.
  CpuPipeline(const Params& params, const Tables& tables, uint32_t slots, uint32_t threads);
  ~CpuPipeline() override;  // waits for the frames running

  void Stage(uint32_t slot, const Cloud& cloud, const Mount& mount, bool borrowed) override;
  void SubmitStaged(uint32_t first, uint32_t count) override;
  void Collect(uint32_t slot, Frame& out, bool all_buffers, FrameTimes* times) override;

  uint32_t batch() const override { return 1; }  // frames run one by one
  uint64_t device_bytes() const override { return 0; }
  bool on_cpu_driver() const override { return false; }

  uint32_t threads() const { return threads_; }

 private:
  // A slot's frame from Stage to Collect.
  struct Slot {
    Cloud copy;                    // the cloud staged, when it was not borrowed
    const Cloud* cloud = nullptr;  // the cloud staged: `copy`, or the caller's
    Params params;                 // the backend's Params seen from the cloud's mount (WithMount)
    // Set while the frame runs or has run on the slot's thread (under mutex_), and what it gave.
    bool started = false, done = false;
    Frame frame;
    FrameTimes times;
    std::exception_ptr error;
  };

  // Starts the frame of `slot` on the slot's thread (made the first time).
  void Start(uint32_t slot);
  // The slot's thread: runs its slot's frames as they are started, until stop_.
  void Run(uint32_t slot);

  Params params_;
  Tables tables_;
  uint32_t threads_;        // all frames together
  uint32_t frame_threads_;  // a frame that runs beside others
  std::vector<Slot> slots_;
  std::deque<uint32_t> pending_;  // submitted and not collected, oldest first
  std::mutex mutex_;
  std::condition_variable changed_;
  bool stop_ = false;
  std::vector<std::thread> runners_;  // per slot, made when it first runs a frame
};

}  // namespace lpir
