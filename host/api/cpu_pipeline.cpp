#include "host/api/cpu_pipeline.h"

#include <sched.h>

#include <algorithm>
#include <utility>

namespace lpir {

uint32_t AvailableCores() {
  cpu_set_t set;
  CPU_ZERO(&set);
  if (sched_getaffinity(0, sizeof(set), &set) == 0 && CPU_COUNT(&set) > 0)
    return uint32_t(CPU_COUNT(&set));
  return std::max(std::thread::hardware_concurrency(), 1u);
}

CpuPipeline::CpuPipeline(const Params& params, const Tables& tables, uint32_t slots,
                         uint32_t threads)
    : params_(params),
      tables_(tables),
      threads_(std::max(threads, 1u)),
      frame_threads_(std::max(threads_ / std::max(slots, 1u), 1u)),
      slots_(slots),
      runners_(slots) {}

CpuPipeline::~CpuPipeline() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  changed_.notify_all();
  for (std::thread& runner : runners_)
    if (runner.joinable()) runner.join();
}

void CpuPipeline::Stage(uint32_t slot, const Cloud& cloud, const Mount& mount, bool borrowed) {
  Slot& s = slots_[slot];
  if (borrowed) {
    s.cloud = &cloud;
  } else {
    s.copy = cloud;  // into the slot's vectors: no allocation once they have grown
    s.cloud = &s.copy;
  }
  s.params = WithMount(params_, mount);
}

void CpuPipeline::SubmitStaged(uint32_t first, uint32_t count) {
  for (uint32_t slot = first; slot < first + count; ++slot) pending_.push_back(slot);
  // One thread, or one frame pending: it runs when collected. A second frame makes them frames
  // in flight: every pending frame not yet running starts now.
  if (threads_ == 1 || pending_.size() < 2) return;
  for (uint32_t slot : pending_)
    if (!slots_[slot].started) Start(slot);
}

void CpuPipeline::Start(uint32_t slot) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    slots_[slot].started = true;
    slots_[slot].done = false;
  }
  if (!runners_[slot].joinable()) runners_[slot] = std::thread([this, slot] { Run(slot); });
  changed_.notify_all();
}

void CpuPipeline::Run(uint32_t slot) {
  Slot& s = slots_[slot];
  std::unique_lock<std::mutex> lock(mutex_);
  for (;;) {
    changed_.wait(lock, [&] { return stop_ || (s.started && !s.done); });
    if (stop_) return;
    lock.unlock();
    std::exception_ptr error;
    try {
      RunReference(*s.cloud, s.params, tables_, s.frame, &s.times, Threads{frame_threads_});
    } catch (...) {
      error = std::current_exception();
    }
    lock.lock();
    s.error = error;
    s.done = true;
    changed_.notify_all();
  }
}

void CpuPipeline::Collect(uint32_t slot, Frame& out, bool, FrameTimes* times) {
  pending_.erase(std::find(pending_.begin(), pending_.end(), slot));
  Slot& s = slots_[slot];
  if (!s.started) {  // alone: now, on this thread, with every thread
    RunReference(*s.cloud, s.params, tables_, out, times, Threads{threads_});
    return;
  }
  std::unique_lock<std::mutex> lock(mutex_);
  changed_.wait(lock, [&] { return s.done; });
  s.started = false;
  const std::exception_ptr error = std::move(s.error);
  s.error = nullptr;
  lock.unlock();
  if (error) std::rethrow_exception(error);
  std::swap(out, s.frame);  // the finished buffers out, the caller's old ones to the slot
  if (times) *times = s.times;
}

}  // namespace lpir
