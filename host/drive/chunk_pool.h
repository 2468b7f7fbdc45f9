// The drive readers' decompression ahead: jobs 0, 1, ..., count - 1 (a job: read one chunk,
// decompress it, walk its records) run on a few worker threads while the reader hands out the
// results of the earlier ones, in job order. The readers stay single-threaded in what they show:
// every job is a function of the file and of state fixed before the pool starts, and its result
// is taken in the order a one-thread reader would have made it.
#pragma once
#include <algorithm>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <exception>
#include <functional>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <utility>
#include <vector>

namespace lpir {

// The worker count a reader uses when none is asked for: std::thread::hardware_concurrency(),
// at least 1, at most kDefaultReadThreadsCap (each worker may hold a decompressed chunk); the
// environment variable LPIR_READ_THREADS (a whole number from 1 to kMaxReadThreads) replaces it.
constexpr unsigned kDefaultReadThreadsCap = 8;
constexpr unsigned kMaxReadThreads = 64;
unsigned DefaultReadThreads();
// `threads` when it is 1..kMaxReadThreads, DefaultReadThreads() otherwise (0: none asked for).
unsigned ReadThreads(unsigned threads);

// SelectChunks' range check, one text for every reader: IoError naming `path` unless 1 <= first
// <= last <= count; `kind` names the file in the message ("drive", "bag").
void CheckChunkRange(const std::string& path, const char* kind, uint64_t first, uint64_t last,
                     uint64_t count);

// Runs work(0) ... work(count - 1) and hands their results out in index order.
//   - workers <= 1: no thread; Next runs work(i) itself (a one-thread reader, exactly).
//   - workers > 1: that many threads, each taking the lowest index not yet taken, while at most
//     `workers` results are computed or waiting ahead of the one Next is to hand out (memory: that
//     many jobs' results at a time).
// An exception thrown by work(i) is rethrown by the Next that would have returned result i; the
// jobs after it still run. The destructor stops the workers: each finishes the job it is in and
// leaves, no job starts after it; results never taken are dropped.
// `work` must be safe to call from several threads at once for different indexes.
template <typename T>
class ChunkPool {
 public:
  ChunkPool(size_t count, std::function<T(size_t)> work, unsigned workers)
      : count_(count), work_(std::move(work)), ahead_(workers) {
    if (workers <= 1) return;
    const size_t threads = std::min<size_t>(workers, count);
    threads_.reserve(threads);
    try {
      for (size_t k = 0; k < threads; ++k) threads_.emplace_back([this] { Work(); });
    } catch (...) {  // a thread that could not start: the started ones stopped, the error passed on
      Stop();
      throw;
    }
  }
  ~ChunkPool() { Stop(); }
  ChunkPool(const ChunkPool&) = delete;
  ChunkPool& operator=(const ChunkPool&) = delete;

  size_t count() const { return count_; }
  // The jobs handed out so far.
  size_t taken() const { return taken_; }

  // Result `taken()` into *out, and true; false when all `count` have been handed out.
  bool Next(T* out) {
    if (taken_ == count_) return false;
    if (threads_.empty()) {
      const size_t i = taken_++;
      *out = work_(i);
      return true;
    }
    std::unique_lock<std::mutex> lock(mutex_);
    changed_.wait(lock, [this] { return !slots_.empty() && slots_.front().done; });
    Slot slot = std::move(slots_.front());
    slots_.pop_front();
    ++taken_;
    lock.unlock();
    changed_.notify_all();
    if (slot.error) std::rethrow_exception(slot.error);
    *out = std::move(*slot.result);
    return true;
  }

 private:
  struct Slot {
    bool done = false;
    std::optional<T> result;
    std::exception_ptr error;
  };

  void Stop() {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      stop_ = true;
    }
    changed_.notify_all();
    for (std::thread& t : threads_) t.join();
    threads_.clear();
  }

  // A worker: claims the next index while fewer than ahead_ jobs are in flight or waiting, runs
  // it unlocked, stores its result in the index's slot.
  void Work() {
    std::unique_lock<std::mutex> lock(mutex_);
    for (;;) {
      changed_.wait(lock,
                    [this] { return stop_ || claimed_ == count_ || claimed_ < taken_ + ahead_; });
      if (stop_ || claimed_ == count_) return;
      const size_t i = claimed_++;
      slots_.emplace_back();  // slots_[k] holds index taken_ + k
      lock.unlock();
      std::optional<T> result;
      std::exception_ptr error;
      try {
        result.emplace(work_(i));
      } catch (...) {
        error = std::current_exception();
      }
      lock.lock();
      Slot& slot = slots_[i - taken_];
      slot.result = std::move(result);
      slot.error = error;
      slot.done = true;
      changed_.notify_all();
    }
  }

  const size_t count_;
  const std::function<T(size_t)> work_;
  const size_t ahead_;
  std::mutex mutex_;
  std::condition_variable changed_;
  std::deque<Slot> slots_;  // the indexes taken_ .. claimed_ - 1, computed or in flight
  size_t claimed_ = 0;      // the next index a worker takes
  size_t taken_ = 0;        // the next index Next hands out
  bool stop_ = false;
  std::vector<std::thread> threads_;  // last: started once everything they use is built
};

}  // namespace lpir
