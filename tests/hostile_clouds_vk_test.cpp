// Whole clouds no sensor should send, through the full pipeline on both backends (Segmenter with
// Backend::kVulkan and Backend::kCpu, every buffer read back): 0 points, 1 point, all points
// identical, all at the origin, all NaN, Inf mixed in, coordinates of 1e30, every point on one
// pixel, intensities no sensor writes (negative, huge, NaN, Inf, subnormal: never read), rings past
// the last beam, and a cloud larger than the configured maximum. Each must give a defined result,
// the same bytes in all 28 buffers on both backends (tests/frame_compare.h): a label for every
// point, ground (1) exactly when why is kWhyGround, and non-ground with why kWhyInvalid exactly
// for the points prepare must reject (a non-finite coordinate, the origin, a ring past the beams, a
// planar range or |z| outside the profile's range), decided here independently of the pipeline.
// The subnormal cases (heights of about 1e-38 m, heights whose differences are subnormal,
// subnormal coordinates) put the float arithmetic of every stage in the range where a device may
// flush (Vulkan allows it): the bytes must still be the reference's, and the cloud must really
// make the stages subtract heights into that range (SubnormalHeightsReachTheStages).
// FlushingLavapipe runs clouds on lavapipe made to flush fp32 subnormals as such a device would
// (MXCSR's FTZ and DAZ bits on the thread that creates its instance and device: its worker
// threads inherit them, pthread_create's floating-point environment rule) against the reference
// on the test thread: ordinary scans and every subnormal case give the same bytes in every buffer
// there and on the ordinary lavapipe, the reference holds no subnormal in any float buffer (the
// stages flush every result that can be one: docs/decisions/denormals.md), and each case checks
// that its cloud still drives the reference's arithmetic into the subnormal range.
#include <gtest/gtest.h>
#if defined(__SSE__)
#include <xmmintrin.h>
#endif

#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "apps/sim/scene.h"
#include "host/api/segmenter.h"
#include "host/io/kitti_bin.h"
#include "host/io/sensor_profile.h"
#include "host/vk/buffer.h"
#include "host/vk/command_buffer.h"
#include "host/vk/context.h"
#include "host/vk/fence.h"
#include "host/vk/kernel.h"
#include "reference_cpu/exact.h"
#include "reference_cpu/frame.h"
#include "shaders/common/test_exact.h"
#include "tests/frame_compare.h"
#include "tests/stage_test_util.h"
#include "tests/test_util.h"
#include "tests/vk_exact_run.h"
#include "tests/vk_test_util.h"

namespace lpir {
namespace {

constexpr size_t kMaxPoints = 4096;  // the small sensor's 16 x 256 pixels
const float kNan = std::numeric_limits<float>::quiet_NaN();
const float kInf = std::numeric_limits<float>::infinity();
const float kMaxFloat = std::numeric_limits<float>::max();

// A simulated street seen by the small sensor (16 beams x 256 columns): the base of the mixed
// cases, so that hostile points sit among ground and obstacles.
Cloud Street() {
  SimOptions options;
  options.seed = 6;
  return Simulate(test::SmallSensor(), options).cloud;
}

Cloud Repeat(size_t n, float x, float y, float z, float intensity) {
  Cloud cloud;
  for (size_t i = 0; i < n; ++i) cloud.Push(x, y, z, intensity);
  return cloud;
}

// Every point on one pixel: along the ray through the centre of row 7 (-5 degrees) and column 40,
// from 2 m to 60 m, each range twice (exact duplicates tie on the nearest-point rule).
Cloud OnePixel() {
  const double kPi = 3.14159265358979323846;
  const double azimuth = kPi - 2.0 * kPi * 40.5 / 256.0, elevation = -5.0 * kPi / 180.0;
  Cloud cloud;
  for (int k = 0; k < 600; ++k) {
    const double r = 2.0 + 0.1 * (k / 2);
    cloud.Push(float(r * std::cos(azimuth)), float(r * std::sin(azimuth)),
               float(r * std::tan(elevation)), 0.25f + 0.001f * float(k));
  }
  return cloud;
}

// The street with every 7th point given an infinite coordinate or intensity (which is not read).
Cloud InfMixedIn() {
  Cloud cloud = Street();
  for (size_t i = 0; i < cloud.size(); i += 7)
    cloud.xyzi[4 * i + (i / 7) % 4] = (i % 2) ? kInf : -kInf;
  return cloud;
}

// The street with every 5th point's coordinates scaled to 1e30 (or one of them set to it).
Cloud HugeCoordinates() {
  Cloud cloud = Street();
  for (size_t i = 0; i < cloud.size(); i += 5) {
    switch ((i / 5) % 4) {
      case 0:
        cloud.xyzi[4 * i + 0] = 1e30f;
        break;
      case 1:
        cloud.xyzi[4 * i + 1] = -1e30f;
        break;
      case 2:
        cloud.xyzi[4 * i + 2] = 1e30f;
        break;
      default:
        for (int k = 0; k < 3; ++k) cloud.xyzi[4 * i + k] *= 1e30f;
    }
  }
  return cloud;
}

// The street with intensities no sensor writes: negative, huge, the largest float, NaN, infinite,
// subnormal, negative zero. prepare does not read them, so no point becomes invalid.
Cloud WildIntensities() {
  const float wild[] = {-1.0f, 1e30f, kMaxFloat, kNan, -kInf, 1e-40f, 256.0f, -0.0f, -kMaxFloat};
  Cloud cloud = Street();
  for (size_t i = 0; i < cloud.size(); ++i) cloud.xyzi[4 * i + 3] = wild[i % 9];
  return cloud;
}

// The street with a ring field, every `every`-th ring past (or under) the small sensor's 16
// beams: below 1 % of the points (every >= 101) invalid points, above it a refused cloud
// (host/api/sensor_fit.h).
Cloud RingsPastTheBeams(size_t every) {
  Cloud cloud = Street();
  for (size_t i = 0; i < cloud.size(); ++i)
    cloud.ring.push_back(int32_t(i % every ? i % 16 : (i / every) % 2 ? 16 + i : -1));
  return cloud;
}
Cloud AFewRingsPastTheBeams() { return RingsPastTheBeams(128); }

bool Subnormal(float f) { return f != 0.0f && std::fabs(f) < std::numeric_limits<float>::min(); }

// The street with rings (rows from the ring index, not from the elevation, which heights of
// 1e-38 m would make 0 everywhere) and every height scaled by 1e-38: ground at about -1.7e-38,
// obstacles up to about 3e-38, normal floats, and those below 1.18e-38 in magnitude subnormal
// (prepare flushes them). Neighbouring heights differ by subnormal amounts.
Cloud TinyHeights() {
  SimOptions options;
  options.seed = 6;
  options.emit_rings = true;
  Cloud cloud = Simulate(test::SmallSensor(), options).cloud;
  for (size_t i = 0; i < cloud.size(); ++i)
    cloud.xyzi[4 * i + 2] = float(double(cloud.z(i)) * 1e-38);
  return cloud;
}

// The street with rings, every height the smallest normal float (2^-126) plus (i % 61) steps of
// the smallest subnormal (2^-149), negated on every third point: all normal, and every
// difference of two neighbours' heights an exact subnormal (or 0, or about 2^-125).
Cloud SubnormalHeightSteps() {
  SimOptions options;
  options.seed = 6;
  options.emit_rings = true;
  Cloud cloud = Simulate(test::SmallSensor(), options).cloud;
  for (size_t i = 0; i < cloud.size(); ++i) {
    const uint32_t bits = 0x00800000u + uint32_t(i % 61) + (i % 3 == 0 ? 0x80000000u : 0u);
    std::memcpy(&cloud.xyzi[4 * i + 2], &bits, 4);
  }
  return cloud;
}

// The street with a subnormal or tiny coordinate in every 23rd point: x or y of +-1e-40 or
// +-3e-39 (subnormal: prepare flushes it, project reads it raw for the column), x or y of
// +-1e-20 (its square, 1e-40, is subnormal inside r2 = x*x + y*y); and every 50th point's z
// +-1e-40 (flushed: a height of 0, 1.7 m above the road, so only a few). It labels no ground: the
// street's ground (about 320 pixels) breaks up below min_component (300); pixel_grown still holds
// the grown set.
Cloud SubnormalCoordinates() {
  const float tiny[] = {1e-40f, -3e-39f, 1e-20f, -1e-40f, 3e-39f, -1e-20f};
  Cloud cloud = Street();
  for (size_t i = 0; i < cloud.size(); i += 23)
    cloud.xyzi[4 * i + (i / 138) % 2] = tiny[(i / 23) % 6];
  for (size_t i = 1; i < cloud.size(); i += 50)
    cloud.xyzi[4 * i + 2] = i % 100 == 1 ? 1e-40f : -1e-40f;
  return cloud;
}

// The street with rings, holes in every column u with u % 4 == 2, and heights of
// +1.3e-38 where (u / 2) % 2, else -1.25e-38: a hole's two neighbours have opposite signs, and
// the filled value, their sum times 0.5, is subnormal (feature_maps's hole filling).
Cloud FillOppositeSigns() {
  SimOptions options;
  options.seed = 6;
  options.emit_rings = true;
  const Cloud street = Simulate(test::SmallSensor(), options).cloud;
  const double kPi = 3.14159265358979323846;
  Cloud cloud;
  for (size_t i = 0; i < street.size(); ++i) {
    const double theta = std::atan2(double(street.y(i)), double(street.x(i)));
    const int u = int(std::floor((kPi - theta) / (2.0 * kPi) * 256.0));  // eq. 1, about
    if (u % 4 == 2) continue;
    const float value = (u / 2) % 2 ? 1.3e-38f : -1.25e-38f;
    cloud.Push(street.x(i), street.y(i), value, value);
    cloud.ring.push_back(street.ring[i]);
  }
  return cloud;
}

// TinyHeights with every 3rd point's x 1e-37 (y moved to 5 m where it was nearer than 2 m): with
// a tilt k_xz of 0.01 (TiltedSensor), prepare's k_xz * x is subnormal, and so z minus it.
Cloud TinyXTinyHeights() {
  Cloud cloud = TinyHeights();
  for (size_t i = 0; i < cloud.size(); i += 3) {
    cloud.xyzi[4 * i + 0] = 1e-37f;
    if (std::fabs(cloud.y(i)) < 2.0f) cloud.xyzi[4 * i + 1] = 5.0f;
  }
  return cloud;
}

SensorProfile TiltedSensor() {
  SensorProfile s = test::SmallSensor();
  s.k_xz = 0.01f;
  return s;
}

// Thresholds of 0 (allowed values), against which a subnormal difference and a flushed one
// compare differently, with TinyHeights' heights of about 1.3e-38.
SensorProfile ZeroThresholdsSensor() {
  SensorProfile s = test::SmallSensor();
  for (const char* name :
       {"grow_dz", "grow_grade", "bp_height_gate", "t_edge", "h_athr", "rise_margin"})
    s.overrides.push_back({name, 0.0f});
  return s;
}

// Whether prepare must reject the point, decided in double precision from the contract of
// reference_cpu/prepare.cpp (the cases keep clear of the range limits, where float and double
// could disagree).
bool MustBeInvalid(const Cloud& cloud, size_t i, const SensorProfile& s) {
  const double x = cloud.x(i), y = cloud.y(i), z = cloud.z(i);
  if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(z)) return true;
  if (x == 0 && y == 0 && z == 0) return true;
  if (!cloud.ring.empty() && (cloud.ring[i] < 0 || uint32_t(cloud.ring[i]) >= s.beams)) return true;
  const double r2 = x * x + y * y, max2 = double(s.max_range) * s.max_range;
  return r2 < double(s.min_range) * s.min_range || r2 > max2 || z * z > max2;
}

struct HostileCase {
  const char* name;
  Cloud (*make)();
};

class HostileVk : public test::VkTest {
 public:
  static void TearDownTestSuite() { gpu_.reset(), cpu_.reset(); }

 protected:
  static SegmenterOptions Options(Backend backend) {
    SegmenterOptions o = SegmenterOptions::For(backend);
    o.all_buffers = true;
    o.validation = true;
    o.max_points = kMaxPoints;
    return o;
  }
  // One segmenter per backend for the whole suite (made after the fixture found a device).
  static Segmenter& Gpu() {
    if (!gpu_) gpu_ = std::make_unique<Segmenter>(test::SmallSensor(), Options(Backend::kVulkan));
    return *gpu_;
  }
  static Segmenter& Cpu() {
    if (!cpu_) cpu_ = std::make_unique<Segmenter>(test::SmallSensor(), Options(Backend::kCpu));
    return *cpu_;
  }

  // Segments `cloud` on both backends, compares every buffer and checks the labels' contract.
  // Returns the CPU frame (a copy).
  Frame ExpectDefinedAndSame(const Cloud& cloud, const std::string& what) {
    const Frame gpu = Gpu().Segment(cloud);
    const Frame cpu = Cpu().Segment(cloud);
    EXPECT_EQ(Gpu().backend(), Backend::kVulkan);
    test::ExpectSameFrame(Cpu().params(), cpu, gpu, &cloud, what);
    const SensorProfile sensor = test::SmallSensor();
    EXPECT_EQ(cpu.n, cloud.size()) << what;
    EXPECT_EQ(cpu.label.size(), cloud.size()) << what;
    EXPECT_EQ(cpu.why.size(), cloud.size()) << what;
    size_t wrong = 0, invalid = 0, ground = 0;
    for (size_t i = 0; i < cloud.size() && i < cpu.label.size() && i < cpu.why.size(); ++i) {
      const bool must_be_invalid = MustBeInvalid(cloud, i, sensor);
      const bool ok = cpu.label[i] <= 1 && cpu.why[i] <= kWhyNoise &&
                      (cpu.label[i] == 1) == (cpu.why[i] == kWhyGround) &&
                      (cpu.why[i] == kWhyInvalid) == must_be_invalid;
      if (!ok && wrong++ < 5)
        ADD_FAILURE() << what << ": point " << i << " (" << cloud.x(i) << ", " << cloud.y(i) << ", "
                      << cloud.z(i) << ", intensity " << cloud.intensity(i) << ") has label "
                      << int(cpu.label[i]) << ", why " << int(cpu.why[i])
                      << "; must be invalid: " << must_be_invalid;
      invalid += must_be_invalid;
      ground += cpu.label[i];
    }
    std::printf("[hostile] %s: %zu points, %zu invalid, %zu ground; %s\n", what.c_str(),
                cloud.size(), invalid, ground,
                HasFailure() ? "FAILED (see above)" : "identical on both backends");
    return cpu;
  }

 private:
  static std::unique_ptr<Segmenter> gpu_, cpu_;
};
std::unique_ptr<Segmenter> HostileVk::gpu_, HostileVk::cpu_;

class HostileCloudsVk : public HostileVk, public ::testing::WithParamInterface<HostileCase> {};

TEST_P(HostileCloudsVk, DefinedResultIdenticalOnBothBackends) {
  const Cloud cloud = GetParam().make();
  ASSERT_LE(cloud.size(), kMaxPoints);
  ExpectDefinedAndSame(cloud, GetParam().name);
}

INSTANTIATE_TEST_SUITE_P(
    Clouds, HostileCloudsVk,
    ::testing::Values(
        HostileCase{"empty", [] { return Cloud{}; }},
        HostileCase{"one_point", [] { return Repeat(1, 10.0f, 0.5f, -1.7f, 0.3f); }},
        HostileCase{"all_identical", [] { return Repeat(3000, 7.0f, -2.0f, -1.7f, 0.3f); }},
        HostileCase{"all_at_origin", [] { return Repeat(3000, 0.0f, 0.0f, 0.0f, 0.5f); }},
        HostileCase{"all_nan", [] { return Repeat(3000, kNan, kNan, kNan, kNan); }},
        HostileCase{"all_1e30", [] { return Repeat(3000, 1e30f, 1e30f, 1e30f, 1e30f); }},
        HostileCase{"street", Street}, HostileCase{"inf_mixed_in", InfMixedIn},
        HostileCase{"coordinates_of_1e30", HugeCoordinates},
        HostileCase{"every_point_on_one_pixel", OnePixel},
        HostileCase{"wild_intensities", WildIntensities},
        HostileCase{"a_few_rings_past_the_beams", AFewRingsPastTheBeams},
        HostileCase{"tiny_heights", TinyHeights},
        HostileCase{"subnormal_height_steps", SubnormalHeightSteps},
        HostileCase{"subnormal_coordinates", SubnormalCoordinates}),
    [](const ::testing::TestParamInfo<HostileCase>& info) { return std::string(info.param.name); });

// The cases are what they claim to be: the hostile points are there, and valid points remain.
TEST(HostileClouds, CasesHoldWhatTheyClaim) {
  const SensorProfile s = test::SmallSensor();
  auto invalid = [&](const Cloud& c) {
    size_t n = 0;
    for (size_t i = 0; i < c.size(); ++i) n += MustBeInvalid(c, i, s);
    return n;
  };
  const Cloud street = Street();
  EXPECT_GT(street.size(), 2000u);
  EXPECT_LE(street.size(), kMaxPoints);
  EXPECT_EQ(invalid(street), 0u);
  for (Cloud (*make)() : {InfMixedIn, HugeCoordinates}) {
    const Cloud c = make();
    EXPECT_GT(invalid(c), c.size() / 10);
    EXPECT_LT(invalid(c), c.size() / 2);
  }
  const Cloud few = AFewRingsPastTheBeams();
  EXPECT_GT(invalid(few), few.size() / 200);
  EXPECT_LT(invalid(few), few.size() / 100);
  EXPECT_EQ(invalid(WildIntensities()), 0u);
  EXPECT_EQ(invalid(OnePixel()), 0u);
  EXPECT_EQ(invalid(TinyHeights()), 0u);
  EXPECT_EQ(invalid(SubnormalHeightSteps()), 0u);
  const Cloud coordinates = SubnormalCoordinates();
  size_t subnormal_inputs = 0;
  for (float f : coordinates.xyzi) subnormal_inputs += Subnormal(f);
  EXPECT_GT(subnormal_inputs, coordinates.size() / 40);
  EXPECT_LT(invalid(coordinates), coordinates.size() / 2);
}

// The subnormal cases exercise what they claim: in the reference's frame, horizontally
// neighbouring measured pixels whose heights (f_height) differ by a subnormal amount, the
// difference that the edge features compute (feature_maps). Prints how many subnormal values each
// float buffer of the reference holds.
TEST_F(HostileVk, SubnormalHeightsReachTheStages) {
  for (Cloud (*make)() : {TinyHeights, SubnormalHeightSteps}) {
    const Cloud cloud = make();
    const Frame f = ExpectDefinedAndSame(cloud, make == TinyHeights ? "tiny heights" : "steps");
    const Params& p = Cpu().params();
    size_t subnormal_steps = 0;
    for (uint32_t v = 0; v < p.beams; ++v)
      for (uint32_t u = 0; u + 1 < p.width; ++u) {
        const size_t a = v * p.width + u, b = a + 1;
        if (f.pixel_filled[a] == 1 && f.pixel_filled[b] == 1)
          subnormal_steps += Subnormal(f.f_height[b] - f.f_height[a]);
      }
    EXPECT_GT(subnormal_steps, 50u) << "the cloud no longer makes subnormal height differences";
    std::string counts;
    auto count = [&](const char* name, const std::vector<float>& buffer) {
      size_t n = 0;
      for (float x : buffer) n += Subnormal(x);
      counts += std::string(" ") + name + " " + std::to_string(n);
    };
    count("zt", f.zt), count("r2", f.r2), count("f_range", f.f_range);
    count("f_height", f.f_height), count("f_slope", f.f_slope), count("f_edge_l", f.f_edge_l);
    count("f_edge_r", f.f_edge_r), count("f_varz", f.f_varz);
    std::printf("[hostile] %zu subnormal height steps; subnormal values in the reference:%s\n",
                subnormal_steps, counts.c_str());
  }
}

// How many subnormal intermediate results the reference meets on a cloud (its frame at hand),
// and the least a case must show.
struct Probe {
  size_t count;
  size_t at_least;
};

// One case for FlushingLavapipe: the cloud, its sensor, and what shows that the cloud reaches the
// subnormal range.
struct FlushCase {
  const char* name;
  Cloud (*make)();
  SensorProfile (*sensor)();
  Probe (*probe)(const Params& p, const Cloud& cloud, const Frame& f);
};

// Horizontally neighbouring measured pixels whose heights differ by a subnormal amount: the edges
// (feature_maps) and growing steps (grow) subtract them.
size_t SubnormalNeighbourSteps(const Params& p, const Frame& f) {
  size_t n = 0;
  for (uint32_t v = 0; v < p.beams; ++v)
    for (uint32_t u = 0; u + 1 < p.width; ++u) {
      const size_t a = v * p.width + u, b = a + 1;
      if (f.pixel_filled[a] != 1 || f.pixel_filled[b] != 1) continue;
      n += Subnormal(f.f_height[b] - f.f_height[a]);
    }
  return n;
}

Probe CoordinatesProbe(const Params&, const Cloud& cloud, const Frame& f) {
  size_t n = 0;  // valid points with a subnormal coordinate, or a subnormal square of one
  for (size_t i = 0; i < cloud.size(); ++i) {
    if (!(f.flags[i] & kPointValid)) continue;
    for (int k = 0; k < 3; ++k) {
      const float c = cloud.xyzi[4 * i + k];
      n += Subnormal(c) || Subnormal(c * c);
    }
  }
  return {n, 50};
}
Probe StepsProbe(const Params& p, const Cloud&, const Frame& f) {
  return {SubnormalNeighbourSteps(p, f), 50};
}
// Filled pixels (2) whose neighbours' heights sum to a subnormal value.
Probe FillProbe(const Params& p, const Cloud&, const Frame& f) {
  size_t n = 0;
  for (uint32_t v = 0; v < p.beams; ++v)
    for (uint32_t u = 0; u < p.width; ++u) {
      const size_t at = v * p.width + u;
      if (f.pixel_filled[at] != 2) continue;
      const size_t l = v * p.width + (u == 0 ? p.width - 1 : u - 1);
      const size_t r = v * p.width + (u + 1 == p.width ? 0 : u + 1);
      n += Subnormal(f.f_height[l] + f.f_height[r]);
    }
  return {n, 50};
}
// Valid points whose tilt term k_xz * x is subnormal.
Probe TiltProbe(const Params& p, const Cloud& cloud, const Frame& f) {
  size_t n = 0;
  for (size_t i = 0; i < cloud.size(); ++i)
    n += (f.flags[i] & kPointValid) && Subnormal(p.k_xz * cloud.x(i));
  return {n, 100};
}

// The reference's float buffers that hold a subnormal value, with their counts ("" when none).
std::string SubnormalValues(const Frame& f) {
  std::string found;
  auto count = [&](const char* name, const std::vector<float>& buffer) {
    size_t n = 0;
    for (float x : buffer) n += Subnormal(x);
    if (n) found += std::string(found.empty() ? "" : ", ") + name + " " + std::to_string(n);
  };
  count("zt", f.zt), count("r2", f.r2), count("f_range", f.f_range);
  count("f_height", f.f_height), count("f_slope", f.f_slope), count("f_edge_l", f.f_edge_l);
  count("f_edge_r", f.f_edge_r), count("f_varz", f.f_varz);
  return found;
}

// Sets the MXCSR bits in `or_bits` for its lifetime (none without SSE).
class ScopedMxcsr {
 public:
#if defined(__SSE__)
  explicit ScopedMxcsr(unsigned or_bits) : saved_(_mm_getcsr()) { _mm_setcsr(saved_ | or_bits); }
  ~ScopedMxcsr() { _mm_setcsr(saved_); }
#else
  explicit ScopedMxcsr(unsigned) {}
#endif
  ScopedMxcsr(const ScopedMxcsr&) = delete;
  ScopedMxcsr& operator=(const ScopedMxcsr&) = delete;

 private:
  unsigned saved_ = 0;
};
constexpr unsigned kFtzDaz = 0x8040u;  // FTZ (bit 15) | DAZ (bit 6)

class FlushingLavapipe : public test::VkTest {
 protected:
  void SetUp() override {
    test::VkTest::SetUp();
    if (IsSkipped() || HasFatalFailure()) return;
#if defined(__SSE__)
    if (Lower(context().device().name()).find("llvmpipe") == std::string::npos)
      GTEST_SKIP() << "flushing is emulated on lavapipe only, not on " << context().device().name();
#else
    GTEST_SKIP() << "flushing is emulated through x86's MXCSR only";
#endif
  }
  static std::string Lower(std::string s) {
    for (char& c : s) c = char(std::tolower(static_cast<unsigned char>(c)));
    return s;
  }
  // A Vulkan segmenter whose lavapipe flushes subnormals when `flush` (see the top of the file).
  static std::unique_ptr<Segmenter> Vulkan(const SensorProfile& sensor, size_t max_points,
                                           bool flush) {
    SegmenterOptions o = SegmenterOptions::For(Backend::kVulkan);
    o.all_buffers = true;
    o.max_points = max_points;
    ScopedMxcsr mode(flush ? kFtzDaz : 0u);
    return std::make_unique<Segmenter>(sensor, o);
  }
  static std::unique_ptr<Segmenter> Flushing(const SensorProfile& sensor, size_t max_points) {
    return Vulkan(sensor, max_points, true);
  }
  static std::unique_ptr<Segmenter> Reference(const SensorProfile& sensor, size_t max_points) {
    SegmenterOptions o = SegmenterOptions::For(Backend::kCpu);
    o.all_buffers = true;
    o.max_points = max_points;
    return std::make_unique<Segmenter>(sensor, o);
  }
};

// The emulation works: lavapipe set up as Flushing() sets it up flushes a subnormal product and a
// subnormal operand (test_exact.comp's own a * b, which no stage computes unflushed), where the
// ordinary lavapipe keeps them; Ftz0 gives the reference's bits on both.
TEST_F(FlushingLavapipe, TheDeviceFlushes) {
  std::vector<ExactCase> cases(2, ExactCase{});
  cases[0].a = 0x0D800000u, cases[0].b = 0x30800000u;  // 2^-100 * 2^-30 = 2^-130: subnormal
  cases[1].a = 0x00400000u, cases[1].b = 0x4B000000u;  // 2^-127 (subnormal) * 2^23 = 2^-104
  for (ExactCase& c : cases) c.s = 0x3F800000u, c.u_lo = 1u;
  std::vector<uint32_t> flushed, kept;
  {
    ScopedMxcsr mode(kFtzDaz);
    vk::Result<vk::Context> flushing = vk::Context::Create(vk::ContextOptions::FromEnvironment());
    ASSERT_TRUE(flushing.ok()) << flushing.message();
    ASSERT_NO_FATAL_FAILURE(test::RunTestExact(flushing->device(), cases, 64, &flushed, nullptr));
  }
  ASSERT_NO_FATAL_FAILURE(test::RunTestExact(device(), cases, 64, &kept, nullptr));
  for (size_t k = 0; k < cases.size(); ++k) {
    const float a = exact::FromBits(cases[k].a), b = exact::FromBits(cases[k].b);
    const uint32_t cpu = exact::Bits(a * b);
    const uint32_t* f = &flushed[k * kExactOutputs];
    const uint32_t* o = &kept[k * kExactOutputs];
    EXPECT_EQ(f[kExactOutMul] & 0x7FFFFFFFu, 0u)
        << "case " << k << ": lavapipe's threads kept a subnormal (" << f[kExactOutMul]
        << "): the MXCSR bits did not reach them, so FlushingLavapipe tests nothing";
    EXPECT_EQ(o[kExactOutMul], cpu) << "case " << k << ": the ordinary lavapipe flushed";
    EXPECT_EQ(f[kExactOutFtz0], exact::Bits(exact::Ftz0(a))) << "case " << k;
    EXPECT_EQ(o[kExactOutFtz0], exact::Bits(exact::Ftz0(a))) << "case " << k;
  }
  EXPECT_TRUE(Subnormal(exact::FromBits(cases[0].a) * exact::FromBits(cases[0].b)));
  EXPECT_TRUE(Subnormal(exact::FromBits(cases[1].a)));
}

// Ordinary scans do not reach the subnormal range: the same bytes on a flushing device.
TEST_F(FlushingLavapipe, OrdinaryScansGiveTheSameBytes) {
  {
    const Cloud cloud = Street();
    const std::unique_ptr<Segmenter> cpu = Reference(test::SmallSensor(), kMaxPoints);
    const Frame gpu = Flushing(test::SmallSensor(), kMaxPoints)->Segment(cloud);
    test::ExpectSameFrame(cpu->params(), cpu->Segment(cloud), gpu, &cloud, "street, flushing");
  }
  const char* scans[] = {"kitti/07/velodyne/000964.bin", "kitti/unknown/velodyne/000056.bin"};
  if (test::DataFile(scans[0]).empty()) {
    std::printf("[hostile] real scans absent under %s: only the street\n", LPIR_DATA_DIR);
    return;
  }
  const SensorProfile hdl64e = LoadSensorProfile("hdl64e", test::SensorsDir());
  const std::unique_ptr<Segmenter> gpu = Flushing(hdl64e, 200000);
  const std::unique_ptr<Segmenter> cpu = Reference(hdl64e, 200000);
  for (const char* scan : scans) {
    if (test::DataFile(scan).empty()) continue;
    const Cloud cloud = ReadKittiBin(test::DataFile(scan));
    const uint64_t bytes = test::ExpectSameFrame(cpu->params(), cpu->Segment(cloud),
                                                 gpu->Segment(cloud), &cloud, scan);
    std::printf("[hostile] %s, flushing device: %llu bytes compared\n", scan,
                static_cast<unsigned long long>(bytes));
  }
}

// The subnormal cases: every buffer is byte for byte the reference's on a flushing lavapipe and on
// the ordinary one, the reference holds no subnormal value in any float buffer, and the cloud
// still drives the reference's arithmetic into the subnormal range (the probe).
class FlushingLavapipeCases : public FlushingLavapipe,
                              public ::testing::WithParamInterface<FlushCase> {};

TEST_P(FlushingLavapipeCases, EveryBufferIsTheReferences) {
  const FlushCase& c = GetParam();
  const Cloud cloud = c.make();
  const SensorProfile sensor = c.sensor();
  const std::unique_ptr<Segmenter> cpu = Reference(sensor, kMaxPoints);
  const Frame ref = cpu->Segment(cloud);
  const Probe probe = c.probe(cpu->params(), cloud, ref);
  EXPECT_GE(probe.count, probe.at_least)
      << c.name << ": the cloud no longer reaches the subnormal range";
  EXPECT_EQ(SubnormalValues(ref), "") << c.name << ": subnormal values left in the reference";
  for (bool flush : {true, false}) {
    const std::string what = std::string(c.name) + (flush ? ", flushing lavapipe" : ", lavapipe");
    const std::unique_ptr<Segmenter> gpu = Vulkan(sensor, kMaxPoints, flush);
    const uint64_t bytes =
        test::ExpectSameFrame(cpu->params(), ref, gpu->Segment(cloud), &cloud, what);
    std::printf("[hostile] %s: %zu subnormal intermediates in the reference, %llu bytes %s\n",
                what.c_str(), probe.count, static_cast<unsigned long long>(bytes),
                HasFailure() ? "compared, FAILED (see above)" : "equal");
  }
}

INSTANTIATE_TEST_SUITE_P(
    Clouds, FlushingLavapipeCases,
    ::testing::Values(
        FlushCase{"subnormal_coordinates", SubnormalCoordinates, test::SmallSensor,
                  CoordinatesProbe},
        FlushCase{"tiny_heights", TinyHeights, test::SmallSensor, StepsProbe},
        FlushCase{"subnormal_height_steps", SubnormalHeightSteps, test::SmallSensor, StepsProbe},
        FlushCase{"fill_opposite_signs", FillOppositeSigns, test::SmallSensor, FillProbe},
        FlushCase{"tilt_tiny_x", TinyXTinyHeights, TiltedSensor, TiltProbe},
        FlushCase{"zero_thresholds", TinyHeights, ZeroThresholdsSensor, StepsProbe}),
    [](const ::testing::TestParamInfo<FlushCase>& info) { return std::string(info.param.name); });

// Every point of OnePixel lands on one pixel, so the nearest-point rule and its ties decide.
TEST_F(HostileVk, OnePixelReallyIsOnePixel) {
  const Cloud cloud = OnePixel();
  const Frame frame = ExpectDefinedAndSame(cloud, "one pixel");
  ASSERT_EQ(frame.point_pixel.size(), cloud.size());
  for (size_t i = 0; i < cloud.size(); ++i)
    ASSERT_EQ(frame.point_pixel[i], 7u * 256u + 40u) << "point " << i;
  size_t filled = 0;
  for (uint32_t p : frame.pixel_point) filled += p != kNone;
  EXPECT_EQ(filled, 1u);
}

// A cloud over the configured maximum is a clear std::length_error on both backends, nothing is
// left pending, and the segmenter labels the next clouds as if nothing had happened.
TEST_F(HostileVk, MoreThanTheMaximumIsALengthErrorAndTheSegmenterGoesOn) {
  Cloud big = Street();
  while (big.size() <= kMaxPoints) big.Push(5.0f, float(big.size() % 50), -1.7f, 0.3f);
  for (Segmenter* s : {&Gpu(), &Cpu()}) {
    const std::string backend = s == &Cpu() ? "cpu" : "vulkan";
    try {
      s->Segment(big);
      ADD_FAILURE() << backend << ": no error for " << big.size() << " points";
    } catch (const std::length_error& e) {
      const std::string message = e.what();
      EXPECT_NE(message.find(std::to_string(big.size()) + " points"), std::string::npos)
          << backend << ": " << message;
      EXPECT_NE(message.find("more than the 4096 this segmenter takes"), std::string::npos)
          << backend << ": " << message;
    }
    EXPECT_EQ(s->pending(), 0u) << backend;
  }
  ExpectDefinedAndSame(Street(), "street after the error");
  big.xyzi.resize(4 * kMaxPoints);
  ExpectDefinedAndSame(big, "exactly the maximum after the error");
}

// Rings past the beams on a third of the points: a refusal naming the rings and the profile on
// both backends (host/api/sensor_fit.h), nothing pending, the next cloud labelled as usual.
TEST_F(HostileVk, RingsPastTheBeamsOnManyPointsAreRefused) {
  const Cloud cloud = RingsPastTheBeams(3);
  for (Segmenter* s : {&Gpu(), &Cpu()}) {
    const std::string backend = s == &Cpu() ? "cpu" : "vulkan";
    try {
      s->Segment(cloud);
      ADD_FAILURE() << backend << ": no error for rings past the beams";
    } catch (const std::invalid_argument& e) {
      const std::string message = e.what();
      EXPECT_NE(message.find("ring values up to "), std::string::npos)
          << backend << ": " << message;
      EXPECT_NE(message.find("has 16 beams: wrong --sensor?"), std::string::npos)
          << backend << ": " << message;
    }
    EXPECT_EQ(s->pending(), 0u) << backend;
  }
  ExpectDefinedAndSame(Street(), "street after the refusal");
}

}  // namespace
}  // namespace lpir
