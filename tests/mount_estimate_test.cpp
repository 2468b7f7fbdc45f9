// EstimateMount (host/api/mount_estimate.h) and the Segmenter's use of it: the ground plane found
// under a tilted simulated sensor, the fallback where a cloud shows too little ground, frames
// segmented with the mount they were estimated with, and non-spinning profiles ignoring rings.
#include "host/api/mount_estimate.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "apps/sim/scene.h"
#include "host/api/segmenter.h"
#include "host/io/sensor_profile.h"
#include "reference_cpu/pipeline.h"
#include "test_util.h"

namespace lpir {
namespace {

constexpr double kDeg = 3.14159265358979323846 / 180.0;

SimScan Scan(const SensorProfile& sensor, float pitch_deg, float roll_deg, uint32_t seed) {
  SimOptions options;
  options.seed = seed;
  options.pitch_deg = pitch_deg;
  options.roll_deg = roll_deg;
  return Simulate(sensor, options);
}

TEST(MountEstimate, FindsTheRoadUnderATiltedSensor) {
  SensorProfile hdl64e = LoadSensorProfile("hdl64e", test::SensorsDir());
  const Mount fallback{0.3f, -0.3f, 9.0f};
  struct Case {
    float pitch, roll, height;
  };
  for (const Case c :
       {Case{0, 0, 1.73f}, Case{3, -2, 1.73f}, Case{-5, 4, 2.4f}, Case{1, 1, 0.9f}}) {
    SCOPED_TRACE(testing::Message()
                 << "pitch " << c.pitch << " roll " << c.roll << " height " << c.height);
    hdl64e.sensor_height = c.height;
    const SimScan scan = Scan(hdl64e, c.pitch, c.roll, 7);
    const MountEstimate e = EstimateMount(scan.cloud, hdl64e, fallback);
    ASSERT_TRUE(e.estimated) << e.cells << " cells, " << e.kept << " kept";
    EXPECT_NEAR(e.mount.k_xz, std::tan(c.pitch * kDeg), 0.01);
    EXPECT_NEAR(e.mount.k_yz, std::tan(c.roll * kDeg), 0.01);
    // Pavements 0.15 m above the road lie inside the inlier band and lift the plane by up to
    // 0.1 m; the labels do not change (docs/decisions/mount.md).
    EXPECT_NEAR(e.mount.sensor_height, c.height, 0.12);
    EXPECT_GE(e.kept, kMountMinCells);
  }
}

TEST(MountEstimate, TooLittleGroundGivesTheFallback) {
  const SensorProfile hdl64e = LoadSensorProfile("hdl64e", test::SensorsDir());
  const Mount fallback{0.01f, -0.02f, 1.5f};
  auto expect_fallback = [&](const Cloud& cloud, const char* what) {
    SCOPED_TRACE(what);
    const MountEstimate e = EstimateMount(cloud, hdl64e, fallback);
    EXPECT_FALSE(e.estimated);
    EXPECT_EQ(std::memcmp(&e.mount, &fallback, sizeof(Mount)), 0);
  };
  expect_fallback(Cloud{}, "empty");
  Cloud few;  // seven cells of ground: one short of kMountMinCells
  for (int k = 0; k < 7; ++k) few.Push(5.0f + 2.0f * float(k), 0.5f, -1.7f, 0.0f);
  expect_fallback(few, "seven cells");
  Cloud wall;  // a vertical wall: no plane within the tilts allowed
  for (int k = 0; k < 400; ++k) wall.Push(6.0f, -20.0f + 0.1f * float(k), -1.0f + 0.01f * k, 0);
  expect_fallback(wall, "a wall");
  Cloud odd;  // NaN, Inf and the origin only
  odd.Push(NAN, 1, 1, 0), odd.Push(INFINITY, 1, 1, 0), odd.Push(0, 0, 0, 0);
  expect_fallback(odd, "non-finite points");
}

TEST(MountEstimate, WithTheParamsOwnMountChangesNoByte) {
  for (const std::string& name : KnownSensorProfiles(test::SensorsDir())) {
    const Params p = ParamsForSensor(LoadSensorProfile(name, test::SensorsDir()));
    const Params q = WithMount(p, MountOf(p));
    EXPECT_EQ(std::memcmp(&p, &q, sizeof(Params)), 0) << name;
  }
  SensorProfile s = LoadSensorProfile("hdl64e", test::SensorsDir());
  s.overrides.emplace_back("h_noise", -4.5f);  // 2.77 m under the ground
  const Params p = WithMount(ParamsForSensor(s), Mount{0.02f, -0.01f, 2.0f});
  EXPECT_EQ(p.k_xz, 0.02f);
  EXPECT_EQ(p.k_yz, -0.01f);
  EXPECT_EQ(p.sensor_height, 2.0f);
  EXPECT_FLOAT_EQ(p.h_noise, -4.77f);  // keeps its depth under the ground
}

// With `mount per_frame` a frame's labels are those of the profile set to the frame's estimate,
// and the segmenter reports that estimate (segmenter_vk_test: the same bytes on Vulkan).
TEST(MountEstimate, SegmenterRunsEachFrameWithItsOwnEstimate) {
  SensorProfile s = LoadSensorProfile("hdl32e", test::SensorsDir());
  s.sensor_height = 1.0f;  // wrong: the scans below are taken from 1.84 m
  const SensorProfile truth_height = [&] {
    SensorProfile t = s;
    t.sensor_height = 1.84f;
    return t;
  }();
  s.mount = MountSource::kPerFrame;
  {
    Segmenter per_frame(s, SegmenterOptions::For(Backend::kCpu));
    for (uint32_t seed : {3u, 4u}) {
      const SimScan scan = Scan(truth_height, seed == 3 ? 2.0f : -1.0f, 0.0f, seed);
      const std::vector<uint8_t> labels = per_frame.Segment(scan.cloud).label;
      const MountEstimate e = per_frame.mount();
      ASSERT_TRUE(e.estimated);
      EXPECT_NEAR(e.mount.sensor_height, 1.84, 0.12);
      SensorProfile fixed = s;
      fixed.mount = MountSource::kFixed;
      fixed.k_xz = e.mount.k_xz, fixed.k_yz = e.mount.k_yz;
      fixed.sensor_height = e.mount.sensor_height;
      Frame reference;
      const Params p = ParamsForSensor(fixed);
      RunReference(scan.cloud, p, MakeTables(fixed, p), reference);
      EXPECT_EQ(labels, reference.label) << "seed " << seed;
    }
  }
}

// A non-repetitive profile reads no ring: the labels of a cloud with a ring field (here one that
// a spinning profile would refuse) are those of the same points without it.
TEST(MountEstimate, NonSpinningProfilesIgnoreRings) {
  const SensorProfile mid70 = LoadSensorProfile("mid70", test::SensorsDir());
  const SensorProfile spinning = LoadSensorProfile("hdl64e", test::SensorsDir());
  const SimScan scan = Scan(LoadSensorProfile("vlp16", test::SensorsDir()), 0, 0, 5);
  Cloud with_rings = scan.cloud;
  with_rings.ring.assign(with_rings.size(), 0);
  for (size_t i = 0; i < with_rings.size(); ++i) with_rings.ring[i] = int32_t(i % 300);
  Segmenter segmenter(mid70, SegmenterOptions::For(Backend::kCpu));
  const std::vector<uint8_t> plain = segmenter.Segment(scan.cloud).label;
  EXPECT_EQ(segmenter.Segment(with_rings).label, plain);
  Segmenter refuses(spinning, SegmenterOptions::For(Backend::kCpu));
  EXPECT_THROW(refuses.Segment(with_rings), std::invalid_argument);
}

}  // namespace
}  // namespace lpir
