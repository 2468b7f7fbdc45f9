// prepare: validity, eq. 3 height correction, reflection-noise flag, r^2.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "reference_cpu/exact.h"
#include "reference_cpu/stages.h"
#include "tests/stage_test_util.h"

namespace lpir {
namespace {

Frame RunPrepare(const Cloud& cloud, const Params& p) {
  Frame f;
  Prepare(cloud, p, f);
  return f;
}

TEST(Prepare, InvalidPointsAreMarkedAndZeroed) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  Cloud c;
  c.Push(5, 0, -1.7f, 0.3f);     // 0 valid
  c.Push(nan, 0, -1.7f, 0.3f);   // 1 NaN
  c.Push(5, inf, -1.7f, 0.3f);   // 2 Inf
  c.Push(0, 0, 0, 0.3f);         // 3 origin
  c.Push(0.5f, 0, -1.7f, 0.3f);  // 4 closer than min_range
  c.Push(200, 0, -1.7f, 0.3f);   // 5 beyond max_range
  c.Push(5, 0, 1e30f, 0.3f);     // 6 absurd height
  c.Push(5, 0, -1.7f, nan);      // 7 NaN intensity: valid, intensity is not read
  const Params p = ParamsForSensor(test::SmallSensor());
  const Frame f = RunPrepare(c, p);
  EXPECT_EQ(f.flags[0], kPointValid);
  EXPECT_EQ(f.flags[7], kPointValid);
  for (uint32_t i = 1; i < 7; ++i) {
    EXPECT_EQ(f.flags[i], 0u) << "point " << i;
    EXPECT_EQ(f.zt[i], 0.0f);
    EXPECT_EQ(f.r2[i], 0.0f);
  }
}

TEST(Prepare, RingOutsideTheBeamsIsInvalid) {
  Cloud c;
  c.Push(5, 0, -1.7f, 0.3f);
  c.Push(5, 1, -1.7f, 0.3f);
  c.Push(5, 2, -1.7f, 0.3f);
  c.ring = {0, 16, -1};
  const Frame f = RunPrepare(c, ParamsForSensor(test::SmallSensor()));
  EXPECT_EQ(f.flags[0], kPointValid);
  EXPECT_EQ(f.flags[1], 0u);
  EXPECT_EQ(f.flags[2], 0u);
}

TEST(Prepare, CorrectsHeightByTheTiltOfEq3) {
  SensorProfile s = test::SmallSensor();
  s.k_xz = 0.05f;
  s.k_yz = -0.02f;
  const Params p = ParamsForSensor(s);
  Cloud c;
  c.Push(10.0f, 4.0f, -1.0f, 0.5f);
  const Frame f = RunPrepare(c, p);
  const float tx = p.k_xz * 10.0f, ty = p.k_yz * 4.0f;
  const float expected = -1.0f - (tx + ty);
  EXPECT_EQ(exact::Bits(f.zt[0]), exact::Bits(expected));
  EXPECT_NEAR(f.zt[0], -1.0f - (0.5f - 0.08f), 1e-6f);
  EXPECT_EQ(f.r2[0], 116.0f);
}

TEST(Prepare, SubnormalInputsAndOutputsAreFlushed) {
  const Params p = ParamsForSensor(test::SmallSensor());
  const float sub = exact::FromBits(0x00012345u);
  Cloud c;
  c.Push(10.0f, 0.0f, sub, sub);    // subnormal height (and intensity)
  c.Push(sub, 10.0f, -1.0f, 0.3f);  // subnormal x: x * x underflows
  const Frame f = RunPrepare(c, p);
  EXPECT_EQ(f.flags[0] & kPointValid, kPointValid);
  EXPECT_EQ(exact::Bits(f.zt[0]), 0u);
  EXPECT_EQ(f.flags[1] & kPointValid, kPointValid);
  EXPECT_EQ(exact::Bits(f.r2[1]), exact::Bits(100.0f));
}

TEST(Prepare, PointsFarBelowTheGroundAreReflectionNoise) {
  const SensorProfile s = test::SmallSensor();
  const Params p = ParamsForSensor(s);
  EXPECT_EQ(p.h_noise, -s.sensor_height - 2.0f);  // 2 m under the road
  Cloud c;
  c.Push(10, 0, p.h_noise - 0.1f, 0.0f);  // low: noise, whatever its intensity
  c.Push(10, 0, p.h_noise - 0.1f, 0.9f);
  c.Push(10, 0, p.h_noise + 0.1f, 0.0f);  // not low
  const Frame f = RunPrepare(c, p);
  EXPECT_EQ(f.flags[0], kPointValid | kPointNoise);
  EXPECT_EQ(f.flags[1], kPointValid | kPointNoise);
  EXPECT_EQ(f.flags[2], kPointValid);
}

}  // namespace
}  // namespace lpir
