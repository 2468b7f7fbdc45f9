// The CPU backend (host/api/cpu_pipeline.h) through lpir::Segmenter: frames collected alone and
// frames in flight, at one thread and at several, clouds borrowed and copied, every buffer byte for
// byte equal to the reference on one thread (RunReference); the threads option resolved and
// checked; a segmenter destroyed with frames still running; AvailableCores under a narrowed
// affinity.
#include "host/api/cpu_pipeline.h"

#include <gtest/gtest.h>
#include <sched.h>

#include <stdexcept>
#include <string>
#include <vector>

#include "apps/sim/scene.h"
#include "host/api/segmenter.h"
#include "host/io/sensor_profile.h"
#include "reference_cpu/pipeline.h"
#include "tests/frame_compare.h"
#include "tests/test_util.h"

namespace lpir {
namespace {

SensorProfile Hdl64() { return LoadSensorProfile("hdl64e", test::SensorsDir()); }

// Simulated streets of seeds 1 .. n, alternately urban and with objects on a flat plane.
std::vector<Cloud> Streets(const SensorProfile& sensor, uint32_t n) {
  std::vector<Cloud> clouds;
  for (uint32_t seed = 1; seed <= n; ++seed) {
    SimOptions o;
    o.seed = seed;
    o.kind = seed % 2 ? kUrban : kFlatWithObjects;
    clouds.push_back(Simulate(sensor, o).cloud);
  }
  return clouds;
}

SegmenterOptions Cpu(uint32_t threads, uint32_t frames_in_flight) {
  SegmenterOptions o = SegmenterOptions::For(Backend::kCpu);
  o.threads = threads;
  o.frames_in_flight = frames_in_flight;
  return o;
}

// The reference's frame of `cloud` on one thread.
Frame Reference(const Segmenter& s, const Cloud& cloud) {
  Frame f;
  RunReference(cloud, s.params(), s.tables(), f);
  return f;
}

TEST(CpuPipeline, FramesInFlightEqualTheReference) {
  const SensorProfile sensor = Hdl64();
  const std::vector<Cloud> clouds = Streets(sensor, 7);
  for (uint32_t threads : {1u, 2u, 3u, 8u}) {
    for (uint32_t in_flight : {1u, 2u, 3u}) {
      Segmenter s(sensor, Cpu(threads, in_flight));
      EXPECT_EQ(s.threads(), threads);
      size_t submitted = 0, collected = 0;
      while (collected < clouds.size()) {
        while (submitted < clouds.size() && s.CanSubmit()) s.Submit(clouds[submitted++]);
        const Frame& f = s.Collect();
        const std::string what = "frame " + std::to_string(collected) + ", " +
                                 std::to_string(threads) + " threads, " +
                                 std::to_string(in_flight) + " in flight";
        test::ExpectSameFrame(s.params(), Reference(s, clouds[collected]), f, &clouds[collected],
                              what, {"reference", "segmenter"});
        ++collected;
      }
      EXPECT_EQ(s.pending(), 0u);
    }
  }
}

// A frame collected alone, then frames in flight, then alone again: the buffers handed back and
// forth between the slots and the segmenter's frame stay the reference's.
TEST(CpuPipeline, AloneAndInFlightInTurns) {
  const SensorProfile sensor = Hdl64();
  const std::vector<Cloud> clouds = Streets(sensor, 5);
  Segmenter s(sensor, Cpu(4, 2));
  auto check = [&](const Frame& f, size_t k, const std::string& what) {
    test::ExpectSameFrame(s.params(), Reference(s, clouds[k]), f, &clouds[k], what,
                          {"reference", "segmenter"});
  };
  check(s.Segment(clouds[0]), 0, "alone");
  s.Submit(clouds[1]);
  s.Submit(clouds[2]);
  check(s.Collect(), 1, "first in flight");
  s.Submit(clouds[3]);
  check(s.Collect(), 2, "second in flight");
  check(s.Collect(), 3, "third in flight");
  check(s.Segment(clouds[4]), 4, "alone again");
  check(s.Segment(clouds[0]), 0, "alone, the first again");
}

// SubmitBorrowed reads the caller's cloud in place and Submit copies it: borrowed clouds in flight
// give the reference's frames, and a cloud its caller overwrites right after Submit still gives its
// own frame (with one thread the frames run only when collected, after the overwrite).
TEST(CpuPipeline, BorrowedCloudsAndCopiedOnes) {
  const SensorProfile sensor = Hdl64();
  const std::vector<Cloud> clouds = Streets(sensor, 4);
  for (uint32_t threads : {1u, 2u}) {
    Segmenter s(sensor, Cpu(threads, 2));
    auto check = [&](size_t k, const std::string& what) {
      test::ExpectSameFrame(s.params(), Reference(s, clouds[k]), s.Collect(), &clouds[k],
                            what + ", " + std::to_string(threads) + " threads",
                            {"reference", "segmenter"});
    };
    s.SubmitBorrowed(clouds[0]);
    Cloud reused = clouds[1];
    s.Submit(reused);
    reused = clouds[2];
    check(0, "borrowed");
    check(1, "copied, then overwritten by its caller");
    s.SubmitBorrowed(clouds[2]);
    s.SubmitBorrowed(clouds[3]);
    check(2, "borrowed, two in flight");
    check(3, "borrowed, the second");
  }
}

TEST(CpuPipeline, DestroyedWithFramesRunning) {
  const SensorProfile sensor = Hdl64();
  const std::vector<Cloud> clouds = Streets(sensor, 3);
  for (int k = 0; k < 3; ++k) {
    Segmenter s(sensor, Cpu(2, 3));
    for (const Cloud& c : clouds) s.Submit(c);
    if (k == 1) s.Collect();
  }  // the destructor waits for the frames running
}

TEST(CpuPipeline, ThreadsOption) {
  const SensorProfile sensor = Hdl64();
  EXPECT_EQ(Segmenter(sensor, Cpu(0, 2)).threads(), AvailableCores());
  EXPECT_EQ(Segmenter(sensor, Cpu(1024, 2)).threads(), 1024u);
  EXPECT_THROW(Segmenter(sensor, Cpu(1025, 2)), std::invalid_argument);
  EXPECT_GE(AvailableCores(), 1u);
}

TEST(CpuPipeline, AvailableCoresFollowsTheAffinity) {
  cpu_set_t before;
  ASSERT_EQ(sched_getaffinity(0, sizeof(before), &before), 0);
  int first = 0;
  while (!CPU_ISSET(first, &before)) ++first;
  cpu_set_t one;
  CPU_ZERO(&one);
  CPU_SET(first, &one);
  ASSERT_EQ(sched_setaffinity(0, sizeof(one), &one), 0);
  const uint32_t cores = AvailableCores();
  ASSERT_EQ(sched_setaffinity(0, sizeof(before), &before), 0);
  EXPECT_EQ(cores, 1u);
  EXPECT_EQ(AvailableCores(), uint32_t(CPU_COUNT(&before)));
}

}  // namespace
}  // namespace lpir
