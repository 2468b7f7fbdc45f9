// project, on Vulkan (shaders/project.comp) against the CPU reference
// (reference_cpu/project.cpp): point_pixel, pixel_key and pixel_point byte for byte, both sides
// fed the reference's prepare outputs, on random clouds of 1 to 200000 points (invalid and noise
// points, duplicates, points on column boundary directions and on the axes, subnormal
// coordinates, with and without rings) and on the scenes of tests/stage_scenes.h
// (tests/stage_harness.h compares).
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

// Runs the CPU Prepare, then both Projects on its outputs, and compares the three buffers.
void ExpectSameProject(const vk::Device& device, const Cloud& cloud, const Params& p,
                       const Tables& t, const std::string& what) {
  Frame f;
  Prepare(cloud, p, f);
  EXPECT_EQ(test::ExpectSameStage<vk::ProjectStage>(device, p, &t, &cloud, f, what),
            test::StageBytes<vk::ProjectStage>(uint32_t(cloud.size()), p));
}

// A random cloud: ordinary points, invalid and noise points, exact duplicates of earlier points
// (ties on r2), points on column boundary directions and on the axes, subnormal coordinates.
Cloud RandomCloud(size_t n, bool with_ring, const Params& p, const Tables& t, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> xy(-110.0f, 110.0f), height(-4.0f, 4.0f), unit(0.0f, 1.0f);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  const float sub = exact::FromBits(0x00012345u);  // a subnormal
  const float min_range = std::sqrt(p.min_range2), max_range = std::sqrt(p.max_range2);
  Cloud cloud;
  cloud.xyzi.reserve(4 * n);
  for (size_t i = 0; i < n; ++i) {
    float x = xy(rng), y = xy(rng), z = height(rng), in = unit(rng) * 255.0f;
    int32_t ring = int32_t(rng() % p.beams);
    const uint32_t k = 1 + rng() % (p.width - 1);  // a column boundary
    const float scale = 1.0f + unit(rng) * 80.0f;
    // clang-format off
    switch (rng() % 32) {
      case 0: x = nan; break;
      case 1: z = inf; break;
      case 2: x = 0.0f, y = -0.0f, z = 0.0f; break;           // the origin (no return)
      case 3: x = 0.5f * min_range, y = 0.0f; break;          // too near
      case 4: x = std::nextafter(max_range, 1e9f), y = 0.0f; break;  // too far
      case 5: z = p.h_noise - unit(rng), in = unit(rng) * 2.0f; break;  // reflection noise
      case 6: case 7: case 8:                                 // a duplicate (ties)
        if (i > 0) {
          const size_t j = rng() % i;
          x = cloud.x(j), y = cloud.y(j), z = cloud.z(j), in = cloud.intensity(j);
          if (with_ring) ring = cloud.ring[j];
        }
        break;
      case 9: case 10:                                        // on a boundary direction
        x = t.column_dir[2 * k] * scale, y = t.column_dir[2 * k + 1] * scale; break;
      case 11: x = t.column_dir[2 * k], y = t.column_dir[2 * k + 1]; break;  // the entry itself
      case 12: y = 0.0f; break;                               // on the axes
      case 13: x = 0.0f; break;
      case 14: y = -0.0f; break;
      case 15: x = -0.0f; break;
      case 16: y = sub; break;                                // just off an axis
      case 17: y = -sub; break;
      case 18: x = -sub; break;
      case 19: x = 1e-20f, y = -10.0f; break;                 // products in the subnormal range
      case 20: z = 1e-21f; break;
      case 21: z = -1e-21f; break;
      case 22: z = sub; break;
      case 23: x = std::round(x), y = std::round(y), z = std::round(z); break;
      case 24: z = 0.0f; break;
      default: break;
    }
    // clang-format on
    cloud.Push(x, y, z, in);
    if (with_ring) cloud.ring.push_back(rng() % 50 == 0 ? int32_t(p.beams) : ring);  // some bad
  }
  return cloud;
}

struct Sensor {
  Params p;
  Tables t;
};

Sensor SmallSensorSetup() {
  SensorProfile s = test::SmallSensor();
  Sensor setup{ParamsForSensor(s), {}};
  setup.t = MakeTables(s, setup.p);
  return setup;
}

Sensor ProfileSensorSetup(const std::string& name) {
  const SensorProfile s = LoadSensorProfile(name, test::SensorsDir());
  Sensor setup{ParamsForSensor(s), {}};
  setup.t = MakeTables(s, setup.p);
  return setup;
}

struct CloudCase {
  size_t points;
  bool ring;
};

class ProjectVk : public test::VkTest, public ::testing::WithParamInterface<CloudCase> {};

TEST_P(ProjectVk, RandomCloudMatchesTheReference) {
  const CloudCase c = GetParam();
  const Sensor s = SmallSensorSetup();
  const Cloud cloud = RandomCloud(c.points, c.ring, s.p, s.t, uint32_t(c.points * 2 + c.ring));
  ExpectSameProject(device(), cloud, s.p, s.t, "small sensor");
}

TEST_P(ProjectVk, RandomCloudHdl64eMatchesTheReference) {  // 2048 columns, laser origins
  const CloudCase c = GetParam();
  const Sensor s = ProfileSensorSetup("hdl64e");
  const Cloud cloud = RandomCloud(c.points, c.ring, s.p, s.t, uint32_t(c.points * 3 + c.ring));
  ExpectSameProject(device(), cloud, s.p, s.t, "hdl64e");
}

INSTANTIATE_TEST_SUITE_P(
    Sizes, ProjectVk,
    ::testing::Values(CloudCase{1, false}, CloudCase{2, true}, CloudCase{63, false},
                      CloudCase{64, true}, CloudCase{65, false}, CloudCase{1000, true},
                      CloudCase{4099, false}, CloudCase{65536, true}, CloudCase{120001, false},
                      CloudCase{200000, true}, CloudCase{200000, false}),
    [](const ::testing::TestParamInfo<CloudCase>& info) {
      return std::to_string(info.param.points) + (info.param.ring ? "_ring" : "_xyzi");
    });

class ProjectVkScan : public test::VkTest {};

// Every boundary direction at several scales, and the axes, in one cloud: the column walk's
// hardest inputs, many sharing a pixel (ties broken by index).
TEST_F(ProjectVkScan, BoundaryDirectionsAndAxes) {
  for (const std::string name : {"small", "hdl64e"}) {
    const Sensor s = name == "small" ? SmallSensorSetup() : ProfileSensorSetup(name);
    Cloud cloud;
    for (float scale : {1.0f, 3.0f, 7.5f, 20.0f, 20.0f, 33.3f}) {
      for (uint32_t k = 0; k < s.p.width; ++k)
        cloud.Push(s.t.column_dir[2 * k] * scale, s.t.column_dir[2 * k + 1] * scale, -1.5f, 50.0f);
      for (float a : {scale, -scale, 0.0f, -0.0f})
        for (float b : {scale, -scale, 0.0f, -0.0f}) cloud.Push(a, b, -1.0f, 10.0f);
    }
    ExpectSameProject(device(), cloud, s.p, s.t, name);
  }
}

class ProjectVkScene : public test::StageScene {};

TEST_P(ProjectVkScene, MatchesTheReference) { ExpectSameProject(device(), cloud, p, t, what); }

LPIR_STAGE_SCENES(ProjectVkScene);

}  // namespace
}  // namespace lpir
