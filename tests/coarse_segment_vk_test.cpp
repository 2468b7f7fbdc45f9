// coarse_segment, on Vulkan (shaders/coarse_segment.comp) against the CPU reference
// (reference_cpu/coarse_segment.cpp): cell_seed_mode, cell_plane and coarse byte for byte.
// Inputs: the reference's prepare, project and grid_reduce (RunReference) on random clouds (flat
// and sloped ground with noise, objects, walls, dense clusters) and the scenes of
// tests/stage_scenes.h, and hand-made prepare, project and grid_reduce buffers for the degenerate
// cases of tests/coarse_segment_test.cpp (collinear seeds, fewer than 16 seeds, walls, raised
// cells, cells above the slope prior, a sloped line of seeds). tests/stage_harness.h runs and
// compares.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "reference_cpu/exact.h"
#include "tests/coarse_segment_inputs.h"
#include "tests/stage_harness.h"
#include "tests/stage_scenes.h"
#include "tests/stage_test_util.h"

namespace lpir {
namespace {

// `in` holds prepare, project and grid_reduce (anything of coarse_segment in it is ignored); runs
// coarse_segment on both sides.
void ExpectSameCoarse(const vk::Device& device, const Cloud& cloud, const Params& p,
                      const Tables& t, const Frame& in, const std::string& what) {
  test::ExpectSameStage<vk::CoarseSegmentStage>(device, p, &t, &cloud, in, what);
}

using test::AddPlane;

// A random scene: ground with a random grade and noise over the whole grid, boxes and walls on
// it, scattered clutter, dense clusters, a few invalid points.
Cloud RandomScene(size_t n, float height, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f), angle(0.0f, 6.2831853f);
  const float gx = 0.06f * (unit(rng) - 0.5f), gy = 0.06f * (unit(rng) - 0.5f);
  const float amp = 0.02f + 0.1f * unit(rng);
  float bx[6], by[6], bh[6];
  for (int k = 0; k < 6; ++k) {
    const float r = 3.0f + unit(rng) * 60.0f, a = angle(rng);
    bx[k] = r * std::cos(a), by[k] = r * std::sin(a), bh[k] = 0.3f + 3.0f * unit(rng);
  }
  Cloud cloud;
  for (size_t i = 0; i < n; ++i) {
    const float r = 2.0f + 118.0f * unit(rng) * unit(rng), a = angle(rng);
    float x = r * std::cos(a), y = r * std::sin(a);
    float z = -height + gx * x + gy * y + amp * (unit(rng) - 0.5f);
    const uint32_t kind = rng() % 20;
    if (kind < 4) {  // a box or wall
      const int k = int(rng() % 6);
      x = bx[k] + 2.0f * (unit(rng) - 0.5f), y = by[k] + (k < 3 ? 0.1f : 2.0f) * (unit(rng) - 0.5f);
      z = -height + gx * x + gy * y + bh[k] * unit(rng);
    } else if (kind == 4) {  // clutter
      z = -height + 4.0f * unit(rng);
    } else if (kind == 5) {  // dense cluster, repeated points
      const int k = int(rng() % 6);
      x = bx[k] + 0.02f * unit(rng), y = by[k] + 0.02f * unit(rng);
      z = -height + gx * x + gy * y + 0.01f * float(rng() % 3);
    } else if (kind == 6) {  // low noise, below the road
      z -= 0.5f * unit(rng);
    }
    cloud.Push(x, y, z, unit(rng));
  }
  return cloud;
}

class CoarseSegmentVk : public test::VkTest {};

TEST_F(CoarseSegmentVk, RandomScenesMatchTheReference) {
  const SensorProfile s = LoadSensorProfile("hdl64e", test::SensorsDir());
  for (uint32_t seed = 1; seed <= 6; ++seed) {
    const size_t n = seed == 1 ? 1 : seed == 2 ? 100 : seed == 3 ? 5000 : 60000 * (seed - 3);
    const Cloud cloud = RandomScene(n, s.sensor_height, seed);
    Params p = ParamsForSensor(s);
    const Tables t = MakeTables(s, p);
    Frame f;
    RunReference(cloud, p, t, f);
    ExpectSameCoarse(device(), cloud, p, t, f, "random " + std::to_string(n));
    p.rise_carry = 1;  // pass 0 ring by ring in one workgroup
    ExpectSameCoarse(device(), cloud, p, t, f, "random, rise_carry, " + std::to_string(n));
  }
}

TEST_F(CoarseSegmentVk, RandomHandMadeInputsMatchTheReference) {
  // The small sensor and grid_reduce by hand: z_t = z, no noise filtering, every point in a cell.
  const SensorProfile s = test::SmallSensor();
  const Params p = ParamsForSensor(s);
  const Tables t = MakeTables(s, p);
  for (uint32_t seed = 11; seed <= 14; ++seed) {
    const Cloud cloud = RandomScene(40000, p.sensor_height, seed);
    ExpectSameCoarse(device(), cloud, p, t, test::CoarseInputs(cloud, p, t), "random hand-made");
    Params q = p;
    q.rise_carry = 1;
    ExpectSameCoarse(device(), cloud, q, t, test::CoarseInputs(cloud, q, t),
                     "random hand-made, rise_carry");
  }
}

class CoarseSegmentVkScene : public test::StageScene {};

TEST_P(CoarseSegmentVkScene, MatchesTheReference) {
  ExpectSameCoarse(device(), cloud, p, t, frame, what);
  size_t lowest = 0, ground = 0;
  for (size_t c = 0; c < frame.cell_seed_mode.size(); ++c)
    lowest += frame.cell_count[c] && frame.cell_seed_mode[c] == 1;
  for (uint32_t l : frame.coarse) ground += l;
  EXPECT_GT(lowest, 0u) << "no cell seeded from its lowest points";
  EXPECT_GT(ground, 0u) << "no coarse ground";
}

LPIR_STAGE_SCENES(CoarseSegmentVkScene);

// The degenerate cases of tests/coarse_segment_test.cpp, in one frame each.
class CoarseSegmentVkDegenerate : public test::VkTest {
 protected:
  SensorProfile s = test::SmallSensor();
  Params p = ParamsForSensor(s);
  Tables t = MakeTables(s, p);
  void Check(const Cloud& c, const char* what) {
    ExpectSameCoarse(device(), c, p, t, test::CoarseInputs(c, p, t), what);
  }
};

TEST_F(CoarseSegmentVkDegenerate, PointsExactlyOnTheSeedThresholds) {
  Check(test::SeedThresholdCloud(&p), "points on the seed thresholds");
}

TEST_F(CoarseSegmentVkDegenerate, EmptyCloud) { Check(Cloud(), "empty"); }

TEST_F(CoarseSegmentVkDegenerate, CollinearAndFewSeeds) {
  const float road = -p.sensor_height;
  Cloud c;
  for (float y = 0.02f; y <= 0.45f; y += 0.02f) c.Push(5.0f, y, road, 0.3f);
  for (float r = 6.1f; r <= 7.9f; r += 0.1f) c.Push(r, 0.1f, road + 0.01f, 0.3f);
  c.Push(-5.0f, 0.1f, road, 0.3f);  // two seeds
  c.Push(-5.5f, 0.1f, road + 0.02f, 0.3f);
  for (int k = 0; k < 15; ++k)
    c.Push(-3.0f + 0.03f * k, 2.0f + 0.07f * (k % 4), road + 0.2f * (k % 2), 0.3f);  // 15
  for (int k = 0; k < 16; ++k)
    c.Push(3.0f + 0.03f * k, -2.0f - 0.07f * (k % 4), road + 0.03f * (k % 3), 0.3f);  // 16
  c.Push(-8.0f, -8.0f, road, 0.3f);  // a lone point
  Check(c, "collinear and few seeds");
}

TEST_F(CoarseSegmentVkDegenerate, CollinearSlopedSeeds) {
  const float road = -p.sensor_height;
  for (float grade : {0.01f, 0.04f, 0.07f}) {
    Cloud c;
    for (float x = 4.05f; x <= 5.95f; x += 0.01f) c.Push(x, 0.1f, road + grade * (x - 4.0f), 0.3f);
    for (float x = 6.05f; x <= 7.95f; x += 0.013f)
      c.Push(x, 0.1f + 0.3f * (x - 6.0f), road + grade * (x - 6.0f), 0.3f);
    Check(c, "collinear sloped seeds");
  }
}

TEST_F(CoarseSegmentVkDegenerate, WallsBoxesAndRaisedCells) {
  const float road = -p.sensor_height;
  const float lambda = p.ring_res_near * p.slope_max + p.seed_margin;
  Cloud c;
  for (float y = -1.2f; y <= 1.2f; y += 0.05f)  // a wall across the view
    for (float z = road; z <= 1.0f; z += 0.05f) c.Push(5.0f, y, z, 0.3f);
  for (float x = 4.2f; x <= 15.8f; x += 0.05f)  // road with a box on it, behind on the left
    for (float y = 2.0f; y <= 6.5f; y += 0.1f)
      if (!(x >= 8.0f && x <= 12.0f && y <= 3.8f)) c.Push(x, y, road, 0.2f);
  for (float y = 2.0f; y <= 3.8f; y += 0.05f)
    for (float z = road + std::max(0.3f, lambda + 0.05f); z <= road + 1.5f; z += 0.05f)
      c.Push(8.0f, y, z, 0.5f);
  for (float x = 8.05f; x <= 12.0f; x += 0.05f)
    for (float y = 2.0f; y <= 3.8f; y += 0.05f) c.Push(x, y, road + 1.5f, 0.5f);
  const float raised = road + lambda + p.rise_margin + 0.1f;  // a platform filling a ring
  for (float x = -9.9f; x <= -4.1f; x += 0.1f)
    for (float y = -0.5f; y <= 0.5f; y += 0.1f) {
      const float r = std::hypot(x, y);
      c.Push(x, y, r >= 6.0f && r < 8.0f ? raised : road, 0.3f);
    }
  const float inner = t.ring_inner[2];  // just above and below the slope prior
  const float prior = -p.sensor_height + p.ground_max_above + p.slope_max * inner;
  AddPlane(&c, 4.2f, 5.8f, -4.2f, -3.8f, 0.1f, prior + 0.1f, 0, 0, 0, 3);
  AddPlane(&c, 4.2f, 5.8f, -6.0f, -5.6f, 0.1f, prior - 0.1f, 0, 0, 0, 3);
  AddPlane(&c, -17.8f, -4.2f, -9.0f, -3.0f, 0.1f, road, 0.02f, -0.01f, 0.02f, 4);  // sloped noisy
  Check(c, "walls, boxes, raised cells");
  p.rise_carry = 1;
  Check(c, "walls, boxes, raised cells, rise_carry");
}

}  // namespace
}  // namespace lpir
