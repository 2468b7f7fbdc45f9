// prepare, on Vulkan (shaders/prepare.comp) against the CPU reference
// (reference_cpu/prepare.cpp): every output buffer byte for byte (tests/stage_harness.h), on
// random clouds of 1 to 200000 points full of invalid points (NaN, Inf, origin, out of range, bad
// rings, subnormals) and on the scenes of tests/stage_scenes.h.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "reference_cpu/exact.h"
#include "tests/stage_harness.h"
#include "tests/stage_scenes.h"
#include "tests/stage_test_util.h"

namespace lpir {
namespace {

bool Subnormal(float f) { return (exact::Bits(f) & 0x7F800000u) == 0 && (exact::Bits(f) << 1); }

// Compares prepare's buffers on `cloud`; returns the reference's subnormal zt outputs.
size_t ExpectSamePrepare(const vk::Device& device, const Cloud& cloud, const Params& p,
                         const std::string& what) {
  EXPECT_EQ(test::ExpectSameStage<vk::PrepareStage>(device, p, nullptr, &cloud, Frame(), what),
            test::StageBytes<vk::PrepareStage>(uint32_t(cloud.size()), p));
  Frame cpu;
  Prepare(cloud, p, cpu);
  size_t tiny = 0;
  for (float z : cpu.zt) tiny += Subnormal(z);
  return tiny;
}

// A random cloud: mostly ordinary points, and about a third of every kind of point prepare must
// reject or treat with care.
Cloud RandomCloud(size_t n, bool with_ring, const Params& p, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> xy(-130.0f, 130.0f), height(-4.0f, 4.0f), unit(0.0f, 1.0f);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  const float sub = exact::FromBits(0x00012345u);  // a subnormal
  const float min_range = std::sqrt(p.min_range2), max_range = std::sqrt(p.max_range2);
  Cloud cloud;
  cloud.xyzi.reserve(4 * n);
  for (size_t i = 0; i < n; ++i) {
    float x = xy(rng), y = xy(rng), z = height(rng), in = unit(rng) * 255.0f;
    // clang-format off
    switch (rng() % 40) {
      case 0: x = nan; break;
      case 1: y = -inf; break;
      case 2: z = inf; break;
      case 3: in = nan; break;
      case 4: x = 0.0f, y = -0.0f, z = 0.0f; break;           // the origin (no return)
      case 5: x = -0.0f, y = 0.0f, z = -0.0f, in = 0.0f; break;
      case 6: x = min_range, y = 0.0f; break;                 // on the range limits
      case 7: x = 0.0f, y = -max_range; break;
      case 8: x = std::nextafter(max_range, 1e9f), y = 0.0f; break;
      case 9: z = 1e30f; break;                               // absurd height
      case 10: x = 1e20f; break;                              // r2 overflows to Inf
      case 11: z = p.h_noise - unit(rng), in = unit(rng) * 2.0f; break;  // reflection noise
      case 12: z = -max_range; break;                         // z^2 on the limit
      case 13: x = sub, y = 10.0f, z = sub; break;            // subnormal coordinates
      case 14: in = sub; break;                               // subnormal intensity
      case 15: x = 1e-20f, y = 10.0f; break;                  // x * x underflows
      case 16: z = -0.0f; break;
      case 17: x = 0.5f * min_range, y = 0.0f, z = 0.0f; break;  // too near
      case 18: in = -inf; break;
      case 19: x = std::round(x), y = std::round(y), z = std::round(z); break;
      default: break;
    }
    // clang-format on
    cloud.Push(x, y, z, in);
    if (with_ring) cloud.ring.push_back(int32_t(rng() % (p.beams + 4)) - 2);
  }
  return cloud;
}

Params TiltedParams() {
  SensorProfile s = test::SmallSensor();
  s.k_xz = 0.05f;
  s.k_yz = -0.02f;
  return ParamsForSensor(s);
}

struct CloudCase {
  size_t points;
  bool ring;
};

class PrepareVk : public test::VkTest, public ::testing::WithParamInterface<CloudCase> {};

TEST_P(PrepareVk, RandomCloudMatchesTheReference) {
  const CloudCase c = GetParam();
  const Params p = TiltedParams();
  const Cloud cloud = RandomCloud(c.points, c.ring, p, uint32_t(c.points * 2 + c.ring));
  const size_t subnormals = ExpectSamePrepare(device(), cloud, p, "random");
  if (c.points >= 4000) {
    EXPECT_EQ(subnormals, 0u) << "prepare flushes subnormal outputs (cases 13-15 feed them)";
  }
}

INSTANTIATE_TEST_SUITE_P(
    Sizes, PrepareVk,
    ::testing::Values(CloudCase{1, false}, CloudCase{2, true}, CloudCase{63, false},
                      CloudCase{64, true}, CloudCase{65, false}, CloudCase{1000, true},
                      CloudCase{4099, false}, CloudCase{65536, true}, CloudCase{120001, false},
                      CloudCase{200000, true}, CloudCase{200000, false}),
    [](const ::testing::TestParamInfo<CloudCase>& info) {
      return std::to_string(info.param.points) + (info.param.ring ? "_ring" : "_xyzi");
    });

class PrepareVkScan : public test::VkTest {};

TEST_F(PrepareVkScan, UntiltedDefaultsMatchTheReference) {
  const Params p = DefaultParams();
  const Cloud cloud = RandomCloud(100000, false, p, 99);
  // Untilted: zt = z - 0 with a subnormal z is flushed on both sides.
  EXPECT_EQ(ExpectSamePrepare(device(), cloud, p, "untilted"), 0u);
}

class PrepareVkScene : public test::StageScene {};

TEST_P(PrepareVkScene, MatchesTheReference) { ExpectSamePrepare(device(), cloud, p, what); }

LPIR_STAGE_SCENES(PrepareVkScene);

}  // namespace
}  // namespace lpir
