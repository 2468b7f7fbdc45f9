// ChunkPool (host/drive/chunk_pool.h), the drive readers' decompression ahead: results in index
// order whatever order the workers finish in, at most `workers` jobs ahead of the one taken, an
// exception at its job's place, one worker running in the caller's thread, a pool destroyed with
// jobs left that stops at once; and the worker count's default and LPIR_READ_THREADS.
#include <gtest/gtest.h>
#include <stdlib.h>

#include <atomic>
#include <chrono>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "host/drive/chunk_pool.h"

namespace lpir {
namespace {

// A few hundred microseconds that differ from job to job, so that later jobs often finish first.
void Busy(size_t i) { std::this_thread::sleep_for(std::chrono::microseconds((i * 37) % 400)); }

TEST(ChunkPool, ResultsComeInIndexOrderAndNeverMoreThanTheWorkersAhead) {
  for (unsigned workers : {2u, 3u, 8u}) {
    SCOPED_TRACE(workers);
    std::atomic<size_t> consumed{0};
    std::atomic<size_t> worst_lead{0};  // the largest index - consumed seen as a job starts
    std::atomic<int> running{0}, most_running{0};
    const size_t n = 300;
    ChunkPool<std::string> pool(
        n,
        [&](size_t i) {
          const size_t lead = i - consumed.load();
          for (size_t w = worst_lead.load();
               lead > w && !worst_lead.compare_exchange_weak(w, lead);) {
          }
          const int now = ++running;
          for (int m = most_running.load();
               now > m && !most_running.compare_exchange_weak(m, now);) {
          }
          Busy(i);
          --running;
          return "job " + std::to_string(i);
        },
        workers);
    std::string got;
    for (size_t i = 0; i < n; ++i) {
      ASSERT_EQ(pool.taken(), i);
      ASSERT_TRUE(pool.Next(&got));
      EXPECT_EQ(got, "job " + std::to_string(i));
      ++consumed;
    }
    EXPECT_FALSE(pool.Next(&got));
    EXPECT_FALSE(pool.Next(&got));
    EXPECT_LE(worst_lead.load(), size_t(workers));
    EXPECT_LE(most_running.load(), int(workers));
    EXPECT_GE(most_running.load(), 2) << "the jobs never overlapped";
  }
}

TEST(ChunkPool, AnExceptionComesAtItsJobsPlaceAndTheJobsAfterItStillRun) {
  for (unsigned workers : {1u, 4u}) {
    SCOPED_TRACE(workers);
    ChunkPool<size_t> pool(
        12,
        [](size_t i) {
          Busy(i);
          if (i == 5) throw std::runtime_error("job 5 failed");
          return i * 10;
        },
        workers);
    size_t got = 0;
    for (size_t i = 0; i < 5; ++i) {
      ASSERT_TRUE(pool.Next(&got));
      EXPECT_EQ(got, i * 10);
    }
    try {
      pool.Next(&got);
      ADD_FAILURE() << "job 5's exception did not come";
    } catch (const std::runtime_error& e) {
      EXPECT_STREQ(e.what(), "job 5 failed");
    }
    for (size_t i = 6; i < 12; ++i) {
      ASSERT_TRUE(pool.Next(&got));
      EXPECT_EQ(got, i * 10);
    }
    EXPECT_FALSE(pool.Next(&got));
  }
}

TEST(ChunkPool, OneWorkerRunsEachJobInTheCallersThreadWhenItIsTaken) {
  std::vector<std::thread::id> where;
  std::vector<size_t> order;
  ChunkPool<int> pool(
      4,
      [&](size_t i) {
        where.push_back(std::this_thread::get_id());
        order.push_back(i);
        return int(i);
      },
      1);
  EXPECT_TRUE(order.empty()) << "a job ran before it was asked for";
  int got = 0;
  ASSERT_TRUE(pool.Next(&got));
  EXPECT_EQ(order, std::vector<size_t>{0});
  while (pool.Next(&got)) {
  }
  EXPECT_EQ(order, (std::vector<size_t>{0, 1, 2, 3}));
  for (const std::thread::id& id : where) EXPECT_EQ(id, std::this_thread::get_id());
}

TEST(ChunkPool, DestroyedWithJobsLeftItStopsAfterTheJobsInFlight) {
  std::atomic<size_t> started{0};
  const auto begin = std::chrono::steady_clock::now();
  {
    ChunkPool<std::vector<int>> pool(
        100000,
        [&](size_t i) {
          ++started;
          std::this_thread::sleep_for(std::chrono::milliseconds(2));
          return std::vector<int>(1000, int(i));
        },
        4);
    std::vector<int> got;
    for (int k = 0; k < 3; ++k) ASSERT_TRUE(pool.Next(&got));
    EXPECT_EQ(got[0], 2);
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
  EXPECT_LE(started.load(), 3u + 4u + 4u);  // the taken, those ahead, those in flight
  EXPECT_LT(seconds, 10.0);
}

TEST(ChunkPool, NoJobsAndMoreWorkersThanJobs) {
  int got = 0;
  ChunkPool<int> none(
      0, [](size_t) { return 1; }, 4);
  EXPECT_FALSE(none.Next(&got));
  ChunkPool<int> two(
      2, [](size_t i) { return int(i) + 1; }, 8);
  ASSERT_TRUE(two.Next(&got));
  EXPECT_EQ(got, 1);
  ASSERT_TRUE(two.Next(&got));
  EXPECT_EQ(got, 2);
  EXPECT_FALSE(two.Next(&got));
}

TEST(ChunkPool, WorkerCountFromTheMachineOrLpirReadThreads) {
  const char* saved = std::getenv("LPIR_READ_THREADS");
  const std::string keep = saved ? saved : "";
  unsetenv("LPIR_READ_THREADS");
  const unsigned hw = std::thread::hardware_concurrency();
  const unsigned expected = hw < 1 ? 1 : hw > kDefaultReadThreadsCap ? kDefaultReadThreadsCap : hw;
  EXPECT_EQ(DefaultReadThreads(), expected);
  EXPECT_EQ(ReadThreads(0), expected);
  EXPECT_EQ(ReadThreads(3), 3u);
  EXPECT_EQ(ReadThreads(kMaxReadThreads + 1), expected);
  setenv("LPIR_READ_THREADS", "5", 1);
  EXPECT_EQ(DefaultReadThreads(), 5u);
  setenv("LPIR_READ_THREADS", "64", 1);
  EXPECT_EQ(DefaultReadThreads(), 64u);
  EXPECT_EQ(ReadThreads(2), 2u);  // asked for: the variable does not override it
  for (const char* bad : {"0", "65", "two", "3x", ""}) {
    setenv("LPIR_READ_THREADS", bad, 1);
    EXPECT_EQ(DefaultReadThreads(), expected) << bad;
  }
  if (saved)
    setenv("LPIR_READ_THREADS", keep.c_str(), 1);
  else
    unsetenv("LPIR_READ_THREADS");
}

}  // namespace
}  // namespace lpir
