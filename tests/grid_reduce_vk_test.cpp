// grid_reduce, on Vulkan (shaders/grid_reduce.comp) against the CPU reference
// (reference_cpu/grid_reduce.cpp): point_cell, cell_zmin, cell_zmax and cell_count byte for byte.
// Inputs: the reference's prepare and project on random clouds of 1 to 200000 points (invalid
// points, reflection noise, points on and beyond the ring boundaries, dense clusters that put
// thousands of points in one cell), hand-made prepare and project buffers (every flag value, +-0
// and subnormal heights, r2 on every ring boundary), and the scenes of tests/stage_scenes.h
// (tests/stage_harness.h compares).
#include <gtest/gtest.h>

#include <algorithm>
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

// `in` holds the prepare and project buffers; runs grid_reduce on both sides from them and
// compares.
void ExpectSameGridReduce(const vk::Device& device, const Params& p, const Tables& t,
                          const Frame& in, const Cloud* cloud, const std::string& what) {
  EXPECT_EQ(test::ExpectSameStage<vk::GridReduceStage>(device, p, &t, cloud, in, what),
            test::StageBytes<vk::GridReduceStage>(in.n, p));
}

// prepare and project of the reference on `cloud`, then the comparison.
void ExpectSameOnCloud(const vk::Device& device, const Cloud& cloud, const Params& p,
                       const Tables& t, const std::string& what) {
  Frame f;
  Prepare(cloud, p, f);
  Project(cloud, p, t, f);
  ExpectSameGridReduce(device, p, t, f, &cloud, what);
}

// A 16-beam sensor seeing to 140 m, beyond the grid's last ring (120 m), slightly tilted.
SensorProfile WideSensor() {
  SensorProfile s = test::SmallSensor();
  s.max_range = 140.0f;
  s.k_xz = 0.03f;
  return s;
}

// A random cloud: a third scattered everywhere, a third in a few dense clusters (thousands of
// points in one cell), the rest special: invalid, noise, on the ring boundaries, past the grid.
Cloud RandomCloud(size_t n, bool with_ring, const Params& p, const Tables& t, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> xy(-145.0f, 145.0f), height(-4.0f, 4.0f), unit(0.0f, 1.0f);
  std::uniform_real_distribution<float> angle(0.0f, 6.2831853f);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  float cx[8], cy[8];
  for (int k = 0; k < 8; ++k) {
    const float r = 1.5f + unit(rng) * 120.0f, a = angle(rng);
    cx[k] = r * std::cos(a), cy[k] = r * std::sin(a);
  }
  Cloud cloud;
  cloud.xyzi.reserve(4 * n);
  for (size_t i = 0; i < n; ++i) {
    float x = xy(rng), y = xy(rng), z = height(rng), in = unit(rng) * 255.0f;
    const uint32_t kind = rng() % 30;
    if (kind < 10) {  // a dense cluster, 5 cm across, some exact repeats
      const int k = int(rng() % 8);
      x = cx[k] + 0.05f * unit(rng), y = cy[k] + 0.05f * unit(rng);
      if (rng() % 4 == 0) z = -1.5f;
    } else if (kind == 10) {
      x = nan;
    } else if (kind == 11) {
      y = inf;
    } else if (kind == 12) {
      x = 0.0f, y = 0.0f, z = 0.0f;
    } else if (kind == 13) {  // reflection noise
      z = p.h_noise - 0.5f * unit(rng), in = 0.0f;
    } else if (kind == 14 || kind == 15) {  // on a ring boundary: r2 == bound2 exactly, or just in
      const uint32_t ring = rng() % uint32_t(t.ring_bound2.size());
      const float r = std::sqrt(t.ring_bound2[ring]);
      x = (rng() & 1) ? r : -r, y = 0.0f;
      if (kind == 15) x = std::nextafter(x, 0.0f);
      if (rng() & 1) std::swap(x, y);
    } else if (kind == 16) {  // past the last ring, inside the sensor's range
      const float r = 121.0f + 18.0f * unit(rng), a = angle(rng);
      x = r * std::cos(a), y = r * std::sin(a);
    } else if (kind == 17) {  // on a column boundary
      x = -10.0f, y = 0.0f;
    }
    cloud.Push(x, y, z, in);
    if (with_ring) cloud.ring.push_back(int32_t(rng() % (p.beams + 2)) - 1);
  }
  return cloud;
}

struct CloudCase {
  size_t points;
  bool ring;
};

class GridReduceVk : public test::VkTest, public ::testing::WithParamInterface<CloudCase> {};

TEST_P(GridReduceVk, RandomCloudMatchesTheReference) {
  const CloudCase c = GetParam();
  const SensorProfile s = WideSensor();
  const Params p = ParamsForSensor(s);
  const Tables t = MakeTables(s, p);
  const Cloud cloud = RandomCloud(c.points, c.ring, p, t, uint32_t(c.points * 2 + c.ring + 7));
  ExpectSameOnCloud(device(), cloud, p, t, "random");
}

INSTANTIATE_TEST_SUITE_P(
    Sizes, GridReduceVk,
    ::testing::Values(CloudCase{1, false}, CloudCase{2, true}, CloudCase{63, false},
                      CloudCase{64, false}, CloudCase{65, true}, CloudCase{1000, false},
                      CloudCase{4099, true}, CloudCase{65536, false}, CloudCase{120001, true},
                      CloudCase{200000, false}, CloudCase{200000, true}),
    [](const ::testing::TestParamInfo<CloudCase>& info) {
      return std::to_string(info.param.points) + (info.param.ring ? "_ring" : "_xyzi");
    });

class GridReduceVkFrame : public test::VkTest {};

// prepare and project buffers made by hand: every flag value (only exactly kPointValid gets a
// cell), r2 on, just below and just above every ring boundary, heights with +-0, subnormals,
// infinities and huge values, every pixel of the image. The reference never sees most of these from
// prepare, but its grid_reduce is defined on them all.
TEST_F(GridReduceVkFrame, HandMadeBuffersMatchTheReference) {
  const SensorProfile s = WideSensor();
  const Params p = ParamsForSensor(s);
  const Tables t = MakeTables(s, p);
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  const float specials_z[] = {0.0f,
                              -0.0f,
                              exact::FromBits(1u),
                              exact::FromBits(0x80000001u),
                              -1e30f,
                              1e30f,
                              std::numeric_limits<float>::infinity(),
                              -std::numeric_limits<float>::infinity(),
                              -1.7f,
                              -1.7f,
                              2.0f};
  const uint32_t flag_values[] = {0u, 1u, 1u, 1u, 1u, 2u, 3u, 4u, 5u};
  const uint32_t pixels = p.width * p.beams;
  for (uint32_t n : {1u, 100u, 77777u, 150000u}) {
    Frame f;
    f.n = n;
    f.flags.resize(n), f.r2.resize(n), f.zt.resize(n), f.point_pixel.resize(n);
    for (uint32_t i = 0; i < n; ++i) {
      f.flags[i] = flag_values[rng() % 9];
      const uint32_t ring = rng() % uint32_t(t.ring_bound2.size());
      float r2 = t.ring_bound2[ring];
      switch (rng() % 6) {
        case 0:
          r2 = std::nextafter(r2, 0.0f);
          break;
        case 1:
          r2 = std::nextafter(r2, 1e30f);
          break;
        case 2:
          r2 = unit(rng) * 150.0f * 150.0f;
          break;  // also past the last ring
        case 3:
          r2 = (rng() & 1) ? 0.0f : exact::FromBits(0x00400000u);
          break;
        default:
          break;
      }
      f.r2[i] = r2;
      f.zt[i] = (rng() % 3 == 0) ? specials_z[rng() % 11] : (unit(rng) - 0.5f) * 8.0f;
      f.point_pixel[i] = i < pixels ? i : rng() % pixels;  // every pixel, so every column
    }
    ExpectSameGridReduce(device(), p, t, f, nullptr, "hand-made");
  }
}

class GridReduceVkScene : public test::StageScene {};

TEST_P(GridReduceVkScene, MatchesTheReference) {
  ExpectSameGridReduce(device(), p, t, frame, &cloud, what);
}

LPIR_STAGE_SCENES(GridReduceVkScene);

}  // namespace
}  // namespace lpir
