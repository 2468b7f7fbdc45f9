// lpir::Segmenter's backends: the choice (auto a GPU, else the reference; vulkan any device, a
// CPU driver included; cpu the reference; a device that is not there an error), frames in flight
// in submission order, every buffer when asked, and the misuse errors; each frame's bytes against
// the CPU backend's.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "apps/sim/scene.h"
#include "host/api/segmenter.h"
#include "host/io/sensor_profile.h"
#include "tests/frame_compare.h"
#include "tests/test_util.h"
#include "tests/vk_test_util.h"

namespace lpir {
namespace {

SensorProfile Vlp16() { return LoadSensorProfile("vlp16", test::SensorsDir()); }

Cloud Street(const SensorProfile& sensor, uint32_t seed) {
  SimOptions o;
  o.seed = seed;
  o.emit_rings = seed % 2 == 0;
  return Simulate(sensor, o).cloud;
}

SegmenterOptions Options(Backend backend, uint32_t in_flight = 2, bool all = false) {
  SegmenterOptions o = SegmenterOptions::For(backend);
  o.frames_in_flight = in_flight;
  o.all_buffers = all;
  o.validation = true;
  o.max_points = 200000;
  return o;
}

// The fixture makes the shared context first, so a machine without Vulkan skips these tests.
class SegmenterVk : public test::VkTest {};

// Auto takes a GPU when there is one, else the reference with a note naming the CPU driver;
// kVulkan and a named device take the CPU driver too.
TEST_F(SegmenterVk, AutoTakesAGpuElseTheReferenceVulkanTakesAnyDevice) {
  const vk::Result<vk::Device> gpu = vk::Device::Create(context().instance(), "", true);
  Segmenter s(Vlp16(), Options(Backend::kAuto));
  if (gpu.ok()) {
    EXPECT_EQ(s.backend(), Backend::kVulkan);
    EXPECT_EQ(s.backend_note(), "Vulkan on " + gpu.value().name());
    EXPECT_FALSE(s.on_cpu_driver());
  } else {
    EXPECT_TRUE(gpu.error().cpu_driver_only) << gpu.error().message;
    EXPECT_EQ(s.backend(), Backend::kCpu);
    EXPECT_EQ(s.device_bytes(), 0u);
    const std::string& note = s.backend_note();
    EXPECT_EQ(note.rfind("CPU reference: the only ", 0), 0u) << note;
    const std::string name = device().name();  // without its details: "llvmpipe"
    EXPECT_NE(note.find(" a CPU driver (" + name.substr(0, name.find(" (")) + ")"),
              std::string::npos)
        << note;
    EXPECT_EQ(note.substr(note.size() - 26), "; --backend vulkan uses it") << note;
  }
  Segmenter vulkan(Vlp16(), Options(Backend::kVulkan));
  EXPECT_EQ(vulkan.backend(), Backend::kVulkan);
  EXPECT_EQ(vulkan.backend_note(), "Vulkan on " + device().name());
  SegmenterOptions named = Options(Backend::kAuto);
  named.device = device().name();
  Segmenter by_name(Vlp16(), named);
  EXPECT_EQ(by_name.backend(), Backend::kVulkan);
  EXPECT_EQ(by_name.backend_note(), "Vulkan on " + device().name());
  Segmenter cpu(Vlp16(), Options(Backend::kCpu));
  EXPECT_EQ(cpu.backend(), Backend::kCpu);
  EXPECT_EQ(cpu.backend_note(), "CPU reference (asked for)");
}

TEST_F(SegmenterVk, AllBuffersEqualTheReferencesOnBothBackends) {
  const SensorProfile sensor = Vlp16();
  Segmenter gpu(sensor, Options(Backend::kVulkan, 2, true));
  Segmenter cpu(sensor, Options(Backend::kCpu));
  EXPECT_EQ(gpu.frames_in_flight(), 2u) << "each slot's buffers are read back when collected";
  for (uint32_t seed : {1u, 2u}) {
    const Cloud cloud = Street(sensor, seed);
    FrameTimes times;
    const Frame& g = gpu.Segment(cloud, &times);
    const Frame& c = cpu.Segment(cloud);
    EXPECT_GT(test::ExpectSameFrame(gpu.params(), c, g, &cloud, "seed " + std::to_string(seed)),
              0u);
    EXPECT_GT(times.total_ms, 0.0);
    for (double stage_ms : times.stage_ms) EXPECT_GE(times.total_ms, stage_ms);
  }
}

// `mount per_frame`: each slot's frame runs with its own cloud's estimate (four tilts, three
// frames in flight), and a non-repetitive profile (mid70: no rings, 1 degree elevation bins):
// every buffer as the reference's.
TEST_F(SegmenterVk, PerFrameMountsAndNonRepetitiveProfilesEqualTheReferences) {
  SensorProfile vlp16 = Vlp16();
  vlp16.mount = MountSource::kPerFrame;
  const SensorProfile mid70 = LoadSensorProfile("mid70", test::SensorsDir());
  for (const SensorProfile* sensor : {const_cast<const SensorProfile*>(&vlp16), &mid70}) {
    SCOPED_TRACE(sensor->name);
    Segmenter gpu(*sensor, Options(Backend::kVulkan, 3, true));
    Segmenter cpu(*sensor, Options(Backend::kCpu));
    std::vector<Cloud> clouds;
    for (float pitch : {-3.0f, 0.0f, 2.0f, 4.0f}) {
      SimOptions o;
      o.seed = uint32_t(clouds.size() + 1);
      o.pitch_deg = pitch;
      o.emit_rings = true;
      clouds.push_back(Simulate(vlp16, o).cloud);
    }
    size_t submitted = 0, collected = 0;
    while (collected < clouds.size()) {
      while (submitted < clouds.size() && gpu.CanSubmit()) gpu.Submit(clouds[submitted++]);
      const Frame& g = gpu.Collect();
      const Frame& c = cpu.Segment(clouds[collected]);
      EXPECT_EQ(std::memcmp(&gpu.mount().mount, &cpu.mount().mount, sizeof(Mount)), 0);
      EXPECT_TRUE(gpu.mount().estimated);
      EXPECT_GT(test::ExpectSameFrame(WithMount(gpu.params(), gpu.mount().mount), c, g,
                                      &clouds[collected], "frame " + std::to_string(collected)),
                0u);
      ++collected;
    }
  }
}

TEST_F(SegmenterVk, FramesInFlightComeBackInSubmissionOrder) {
  const SensorProfile sensor = Vlp16();
  Segmenter gpu(sensor, Options(Backend::kVulkan, 3));
  Segmenter cpu(sensor, Options(Backend::kCpu, 3));
  std::vector<Cloud> clouds;
  for (uint32_t k = 0; k < 7; ++k) clouds.push_back(Street(sensor, 20 + k));
  clouds[4].xyzi.resize(4 * 10);  // a tiny frame among the big ones
  if (!clouds[4].ring.empty()) clouds[4].ring.resize(10);
  std::vector<Frame> reference;
  for (const Cloud& c : clouds) reference.push_back(cpu.Segment(c));

  for (Segmenter* s : {&gpu, &cpu}) {
    SCOPED_TRACE(s->backend_note());
    size_t submitted = 0, collected = 0;
    while (collected < clouds.size()) {
      while (submitted < clouds.size() && s->pending() < s->frames_in_flight())
        s->Submit(clouds[submitted++]);
      if (s->pending() == s->frames_in_flight()) {
        EXPECT_THROW(s->Submit(clouds[0]), std::logic_error);
      }
      EXPECT_THROW(s->Segment(clouds[0]), std::logic_error);
      const Frame& f = s->Collect();
      EXPECT_EQ(f.label, reference[collected].label) << "frame " << collected;
      EXPECT_EQ(f.why, reference[collected].why) << "frame " << collected;
      ++collected;
      if (collected == clouds.size()) break;
    }
    EXPECT_EQ(s->pending(), 0u);
    EXPECT_THROW(s->Collect(), std::logic_error);
  }
}

// Batches of 3 with 2 in flight: 13 frames (so the last batch is partial, and Segment's frame of
// one is a batch of its own) come back in submission order with the reference's labels; a batch
// waits in its block until every frame of the block before it is collected.
TEST_F(SegmenterVk, BatchesComeBackInSubmissionOrder) {
  const SensorProfile sensor = Vlp16();
  SegmenterOptions o = Options(Backend::kVulkan, 2);
  o.batch = 3;
  Segmenter gpu(sensor, o);
  Segmenter cpu(sensor, Options(Backend::kCpu));
  EXPECT_EQ(gpu.frames_in_flight(), 6u);
  std::vector<Cloud> clouds;
  for (uint32_t k = 0; k < 5; ++k) clouds.push_back(Street(sensor, 40 + k));
  clouds[3].xyzi.resize(4 * 10);
  if (!clouds[3].ring.empty()) clouds[3].ring.resize(10);
  std::vector<Labels> reference;
  for (const Cloud& c : clouds) reference.push_back(cpu.Segment(c).label);
  EXPECT_EQ(gpu.Segment(clouds[1]).label, reference[1]) << "a batch of one";
  size_t submitted = 0, collected = 0, most_pending = 0;
  const size_t frames = 13;
  while (collected < frames) {
    while (submitted < frames && gpu.CanSubmit()) gpu.Submit(clouds[submitted++ % 5]);
    most_pending = std::max(most_pending, gpu.pending());
    if (!gpu.CanSubmit()) {
      EXPECT_THROW(gpu.Submit(clouds[0]), std::logic_error);
    }
    const Frame& f = gpu.Collect();
    EXPECT_EQ(f.label, reference[collected % 5]) << "frame " << collected;
    ++collected;
  }
  EXPECT_EQ(most_pending, 6u);
  EXPECT_EQ(gpu.pending(), 0u);
  SegmenterOptions zero = o;
  zero.batch = 0;
  EXPECT_THROW(Segmenter(sensor, zero), std::invalid_argument);
}

TEST_F(SegmenterVk, OversizedCloudIsAnErrorOnBothBackends) {
  for (Backend b : {Backend::kVulkan, Backend::kCpu}) {
    SegmenterOptions o = Options(b);
    o.max_points = 1000;
    Segmenter s(Vlp16(), o);
    Cloud cloud = Street(Vlp16(), 1);
    try {
      s.Segment(cloud);
      ADD_FAILURE() << "no error for " << cloud.size() << " points";
    } catch (const std::length_error& e) {
      EXPECT_NE(std::string(e.what()).find("more than the 1000 this segmenter takes"),
                std::string::npos)
          << e.what();
    }
    cloud.xyzi.resize(4 * 1000);
    EXPECT_EQ(s.Segment(cloud).n, 1000u) << "the segmenter still works after the error";
  }
}

// The Segmenter checks every cloud once, before either backend sees it: a ring field of another
// length than the cloud is an invalid_argument on both, and nothing is left pending.
TEST_F(SegmenterVk, RingsOfAnotherLengthAreAnErrorOnBothBackends) {
  for (Backend b : {Backend::kVulkan, Backend::kCpu}) {
    Segmenter s(Vlp16(), Options(b));
    Cloud cloud = Street(Vlp16(), 2);
    ASSERT_EQ(cloud.ring.size(), cloud.size());
    cloud.ring.pop_back();
    try {
      s.Submit(cloud);
      ADD_FAILURE() << "no error for " << cloud.ring.size() << " rings";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(
          std::string(e.what()).find(std::to_string(cloud.ring.size()) + " ring entries for " +
                                     std::to_string(cloud.size()) + " points"),
          std::string::npos)
          << e.what();
    }
    EXPECT_EQ(s.pending(), 0u);
    cloud.ring.clear();
    EXPECT_EQ(s.Segment(cloud).n, cloud.size()) << "the segmenter still works after the error";
  }
}

TEST_F(SegmenterVk, ANamedDeviceThatIsNotThereIsAnError) {
  SegmenterOptions o = Options(Backend::kAuto);
  o.device = "no-such-gpu";
  try {
    Segmenter s(Vlp16(), o);
    ADD_FAILURE() << "made a segmenter on " << s.backend_note();
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("no-such-gpu"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find(device().name()), std::string::npos)
        << "the message lists the devices there are: " << e.what();
  }
}

TEST(Segmenter, BackendNames) {
  EXPECT_EQ(ParseBackend("auto"), Backend::kAuto);
  EXPECT_EQ(ParseBackend("cpu"), Backend::kCpu);
  EXPECT_EQ(ParseBackend("vulkan"), Backend::kVulkan);
  EXPECT_THROW(ParseBackend("cuda"), std::invalid_argument);
}

TEST(Segmenter, BadOptionsAreErrors) {
  SegmenterOptions o = SegmenterOptions::For(Backend::kCpu);
  o.frames_in_flight = 0;
  EXPECT_THROW(Segmenter(Vlp16(), o), std::invalid_argument);
  o.frames_in_flight = 1;
  o.max_points = size_t(UINT32_MAX / 16) + 1;
  EXPECT_THROW(Segmenter(Vlp16(), o), std::invalid_argument);
}

// Without max_points, the profile's max_points, else the sensor's beams x width x 2 (a point a
// pixel, as many second returns); max_points given overrides it; a cloud over it is a
// length_error that names both numbers.
TEST(Segmenter, MaxPointsFollowsTheSensorProfile) {
  for (const char* name : {"vlp16", "hdl64e", "os1-128"}) {
    const SensorProfile sensor = LoadSensorProfile(name, test::SensorsDir());
    Segmenter s(sensor, SegmenterOptions::For(Backend::kCpu));
    EXPECT_EQ(s.max_points(), size_t(sensor.beams) * sensor.width * 2) << name;
    EXPECT_EQ(DefaultMaxPoints(sensor), s.max_points()) << name;
  }
  EXPECT_EQ(DefaultMaxPoints(LoadSensorProfile("hdl64e", test::SensorsDir())), 262144u);
  // The profile's own max_points where it has one (the 10 Hz HDL-32E PLY fires 2181 times a
  // turn into 1024 columns: 69,792 points over 32 x 1024 x 2 = 65,536).
  const SensorProfile hdl32e = LoadSensorProfile("hdl32e", test::SensorsDir());
  ASSERT_NE(hdl32e.max_points, 0u);
  EXPECT_GT(hdl32e.max_points, 69792u);
  EXPECT_EQ(Segmenter(hdl32e, SegmenterOptions::For(Backend::kCpu)).max_points(),
            hdl32e.max_points);
  SegmenterOptions o = SegmenterOptions::For(Backend::kCpu);
  o.max_points = 1000;
  Segmenter small(Vlp16(), o);
  EXPECT_EQ(small.max_points(), 1000u);
  const SensorProfile sensor = Vlp16();
  Segmenter s(sensor, SegmenterOptions::For(Backend::kCpu));
  Cloud big;
  while (big.size() <= s.max_points()) big.Push(5.0f, float(big.size() % 50), -1.7f, 0.3f);
  try {
    s.Segment(big);
    ADD_FAILURE() << "no error for " << big.size() << " points";
  } catch (const std::length_error& e) {
    EXPECT_NE(std::string(e.what()).find(std::to_string(big.size()) + " points, more than the " +
                                         std::to_string(s.max_points()) + " this segmenter takes"),
              std::string::npos)
        << e.what();
  }
}

// A max_points over a device limit: --backend vulkan is an error naming the limit (lavapipe's
// storage buffers hold 128 MiB, 8,388,608 points of 16 bytes).
TEST_F(SegmenterVk, MaxPointsOverADeviceLimitIsAnErrorNamingIt) {
  const uint64_t range = device().limits().maxStorageBufferRange;
  if (range / 16 + 1 > UINT32_MAX / 16) GTEST_SKIP() << "maxStorageBufferRange " << range;
  SegmenterOptions o = Options(Backend::kVulkan);
  o.max_points = range / 16 + 1;
  try {
    Segmenter s(Vlp16(), o);
    ADD_FAILURE() << "made a segmenter on " << s.backend_note();
  } catch (const std::runtime_error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("the Vulkan backend could not be set up: frame pipeline: max_points " +
                        std::to_string(o.max_points) + " needs a "),
              std::string::npos)
        << what;
    EXPECT_NE(what.find(" points buffer; this device's maxStorageBufferRange is " +
                        std::to_string(range)),
              std::string::npos)
        << what;
  }
}

// Segment on the CPU writes into the frame it returns, so a sequence reuses one set of buffers: a
// frame that reallocated them would pay the page faults of ~25 MB again (the benchmarks time
// Segment's second frame).
TEST(Segmenter, CpuSegmentReusesTheFramesBuffers) {
  const SensorProfile sensor = Vlp16();
  Segmenter cpu(sensor, SegmenterOptions::For(Backend::kCpu));
  const Cloud a = Street(sensor, 1), b = Street(sensor, 3);
  const Frame& first = cpu.Segment(a);
  const Labels first_label = first.label;
  const uint8_t* label = first.label.data();
  const float* zt = first.zt.data();
  const Frame& second = cpu.Segment(a);
  EXPECT_EQ(&second, &first);
  EXPECT_EQ(second.label.data(), label);
  EXPECT_EQ(second.zt.data(), zt);
  EXPECT_EQ(second.label, first_label);
  const Frame& third = cpu.Segment(b);  // a different cloud: different labels, same buffers
  EXPECT_EQ(third.f_range.data(), first.f_range.data());
  EXPECT_EQ(third.label.size(), b.size());
}

}  // namespace
}  // namespace lpir
