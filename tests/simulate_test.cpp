// Tests of the synthetic scene and virtual LiDAR (apps/sim): determinism, plausible scans, the
// tilt sign convention read back by a plane fit, the hard cases the scene promises (cars touching
// the road, the ramp, curbs, reflection noise) and the `simulate` subcommand.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "apps/sim/scan_pattern.h"
#include "apps/sim/scene.h"
#include "host/io/kitti_bin.h"
#include "host/io/label_file.h"
#include "host/io/sensor_profile.h"
#include "tests/test_util.h"

namespace lpir {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDeg = kPi / 180.0;

// An HDL-64E-like profile built by hand (the KITTI layout: 32 beams at ~1/3 degree from +2,
// 32 at 1/2 degree from -8.83), so these tests do not depend on the profile parser.
SensorProfile Hdl64Like() {
  SensorProfile s;
  s.name = "hdl64-test";
  s.beams = 64;
  s.width = 2048;
  for (int i = 0; i < 32; ++i) s.elevation_deg.push_back(2.0f - i * (10.33f / 31.0f));
  for (int i = 0; i < 32; ++i) s.elevation_deg.push_back(-8.83f - i * 0.5f);
  s.sensor_height = 1.73f;
  s.min_range = 2.5f;
  s.max_range = 120.0f;
  return s;
}

// Livox-like profiles by hand: 1 degree elevation bins over a Mid-70's 70 degree circle and a
// Mid-360's -7..+52 degree band, the datasheets' returns a 100 ms frame.
SensorProfile LivoxLike(ScanPattern pattern) {
  SensorProfile s;
  s.pattern = pattern;
  const bool rosette = pattern == ScanPattern::kRosette;
  s.name = rosette ? "rosette-test" : "band-test";
  s.beams = rosette ? 70 : 59;
  s.width = rosette ? 768 : 384;
  s.frame_points = rosette ? 10000 : 20000;
  const float top = rosette ? 34.5f : 51.5f;
  for (unsigned i = 0; i < s.beams; ++i) s.elevation_deg.push_back(top - i);
  s.sensor_height = rosette ? 1.5f : 0.5f;
  s.min_range = rosette ? 3.0f : 0.3f;
  s.max_range = rosette ? 260.0f : 70.0f;
  return s;
}

SimOptions Urban(uint32_t seed) {
  SimOptions o;
  o.seed = seed;
  return o;
}

struct WorldPoint {
  double x, y, z;
  uint32_t label;
};

std::vector<WorldPoint> ToWorld(const SimScan& scan) {
  std::vector<WorldPoint> out;
  for (size_t i = 0; i < scan.cloud.size(); ++i) {
    const double p[3] = {scan.cloud.x(i), scan.cloud.y(i), scan.cloud.z(i)};
    double w[3];
    scan.scene.SensorToWorld(p, w);
    out.push_back({w[0], w[1], w[2], scan.labels[i]});
  }
  return out;
}

double Median(std::vector<double> v) {
  if (v.empty()) return NAN;
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}

TEST(Simulate, SameSeedGivesByteIdenticalScan) {
  const SimScan a = Simulate(Hdl64Like(), Urban(7));
  const SimScan b = Simulate(Hdl64Like(), Urban(7));
  ASSERT_EQ(a.cloud.xyzi.size(), b.cloud.xyzi.size());
  EXPECT_EQ(0, std::memcmp(a.cloud.xyzi.data(), b.cloud.xyzi.data(),
                           a.cloud.xyzi.size() * sizeof(float)));
  EXPECT_EQ(a.labels, b.labels);
}

TEST(Simulate, DifferentSeedGivesDifferentScan) {
  const SimScan a = Simulate(Hdl64Like(), Urban(7));
  const SimScan b = Simulate(Hdl64Like(), Urban(8));
  const bool same = a.cloud.xyzi.size() == b.cloud.xyzi.size() &&
                    std::memcmp(a.cloud.xyzi.data(), b.cloud.xyzi.data(),
                                a.cloud.xyzi.size() * sizeof(float)) == 0;
  EXPECT_FALSE(same);
  EXPECT_NE(a.scene.road_half_width, b.scene.road_half_width);
}

TEST(Simulate, PointCountAndClassesArePlausible) {
  const std::set<uint32_t> known = {0,  1,  10,  11,  13,  15,  16,  18,  20,  30, 31, 32,
                                    40, 44, 48,  49,  50,  51,  52,  60,  70,  71, 72, 80,
                                    81, 99, 252, 253, 254, 255, 256, 257, 258, 259};
  for (uint32_t seed : {1u, 2u, 3u}) {
    const SimScan scan = Simulate(Hdl64Like(), Urban(seed));
    EXPECT_GT(scan.cloud.size(), 80000u) << "seed " << seed;
    EXPECT_LT(scan.cloud.size(), 64u * 2048u);
    ASSERT_EQ(scan.labels.size(), scan.cloud.size());
    EXPECT_TRUE(scan.cloud.ring.empty());
    std::set<uint32_t> seen;
    size_t ground = 0;
    for (uint32_t l : scan.labels) {
      EXPECT_TRUE(known.count(l)) << "unknown class " << l;
      seen.insert(l);
      ground += IsSimGroundClass(l);
    }
    for (uint32_t want :
         {SkClass::kRoad, SkClass::kSidewalk, SkClass::kLaneMarking, SkClass::kCar,
          SkClass::kBuilding, SkClass::kPole, SkClass::kVegetation, SkClass::kOutlier})
      EXPECT_TRUE(seen.count(want)) << "seed " << seed << " has no class " << want;
    const double fraction = static_cast<double>(ground) / scan.cloud.size();
    EXPECT_GT(fraction, 0.3);
    EXPECT_LT(fraction, 0.85);
    for (size_t i = 0; i < scan.cloud.size(); ++i) {
      const double r = std::hypot(scan.cloud.x(i), scan.cloud.y(i));
      ASSERT_GE(r, 2.5);
      ASSERT_LE(r, 120.0);
      ASSERT_GE(scan.cloud.intensity(i), 0.0f);
      ASSERT_LE(scan.cloud.intensity(i), 1.0f);
    }
  }
}

// The tilt convention of scene.h, read back the way `calibrate` will: a least-squares plane
// z = a x + b y + c through the ground must give atan(a) = pitch, atan(b) = roll,
// c = -sensor_height.
void ExpectTiltReadsBack(SceneKind kind, float pitch, float roll) {
  SimOptions o;
  o.seed = 11;
  o.kind = kind;
  o.pitch_deg = pitch;
  o.roll_deg = roll;
  o.range_noise_m = 0.002f;
  const SensorProfile sensor = Hdl64Like();
  const SimScan scan = Simulate(sensor, o);
  std::vector<size_t> ground;
  for (size_t i = 0; i < scan.cloud.size(); ++i)
    if (scan.labels[i] == SkClass::kRoad) ground.push_back(i);
  ASSERT_GT(ground.size(), 10000u);
  Eigen::MatrixXd a(ground.size(), 3);
  Eigen::VectorXd z(ground.size());
  for (size_t k = 0; k < ground.size(); ++k) {
    a(k, 0) = scan.cloud.x(ground[k]);
    a(k, 1) = scan.cloud.y(ground[k]);
    a(k, 2) = 1.0;
    z(k) = scan.cloud.z(ground[k]);
  }
  const Eigen::Vector3d fit = a.colPivHouseholderQr().solve(z);
  const std::string where = "pitch " + std::to_string(pitch) + " roll " + std::to_string(roll);
  EXPECT_NEAR(std::atan(fit(0)) / kDeg, pitch, 0.02) << where;
  EXPECT_NEAR(std::atan(fit(1)) / kDeg, roll, 0.02) << where;
  EXPECT_NEAR(fit(2), -sensor.sensor_height, 0.01) << where;
}

TEST(Simulate, TiltSignConventionReadsBackOnFlatGround) {
  const float cases[][2] = {{0, 0},  {5, 0}, {0, 5},   {-5, 0},      {0, -5},        {3, -2},
                            {-5, 5}, {5, 5}, {-5, -5}, {2.5f, 4.0f}, {-1.25f, -3.5f}};
  for (const auto& c : cases) ExpectTiltReadsBack(kFlat, c[0], c[1]);
  ExpectTiltReadsBack(kFlatWithObjects, 4.0f, -3.0f);
}

TEST(Simulate, PositivePitchRaisesTheGroundAheadAndPositiveRollToTheLeft) {
  SimOptions o;
  o.kind = kFlat;
  o.range_noise_m = 0;
  o.pitch_deg = 5;
  SimScan scan = Simulate(Hdl64Like(), o);
  double ahead = -1e9, behind = 1e9;  // ground height in the sensor frame at |x| ~ 10 m
  for (size_t i = 0; i < scan.cloud.size(); ++i) {
    if (std::abs(scan.cloud.y(i)) > 1 || std::abs(std::abs(scan.cloud.x(i)) - 10) > 1) continue;
    if (scan.cloud.x(i) > 0) ahead = std::max(ahead, static_cast<double>(scan.cloud.z(i)));
    if (scan.cloud.x(i) < 0) behind = std::min(behind, static_cast<double>(scan.cloud.z(i)));
  }
  EXPECT_GT(ahead, behind + 1.0);
  o.pitch_deg = 0;
  o.roll_deg = 5;
  scan = Simulate(Hdl64Like(), o);
  double left = 0, right = 0;
  for (size_t i = 0; i < scan.cloud.size(); ++i) {
    if (std::abs(scan.cloud.x(i)) > 1 || std::abs(std::abs(scan.cloud.y(i)) - 10) > 1) continue;
    (scan.cloud.y(i) > 0 ? left : right) += scan.cloud.z(i);
  }
  EXPECT_GT(left, right);
}

TEST(Simulate, CarsStandOnTheRoad) {
  for (uint32_t seed : {1u, 4u}) {
    SimOptions o = Urban(seed);
    o.range_noise_m = 0.005f;
    const SimScan scan = Simulate(Hdl64Like(), o);
    const SimScene& s = scan.scene;
    double lowest = 1e9;
    size_t cars = 0, ahead = 0;
    for (const WorldPoint& p : ToWorld(scan)) {
      if (p.label != SkClass::kCar) continue;
      ++cars;
      lowest = std::min(lowest, p.z - s.GroundHeight(p.x, p.y));
      if (p.x > 6 && p.x < 18 && std::abs(p.y - s.road_center_y) < 1.5) ++ahead;
      EXPECT_LT(p.z - s.GroundHeight(p.x, p.y), 1.7);
    }
    EXPECT_GT(cars, 2000u) << "seed " << seed;
    EXPECT_GT(ahead, 200u) << "the car on the road ahead, seed " << seed;
    EXPECT_GT(lowest, -0.05) << "seed " << seed;
    EXPECT_LT(lowest, 0.05) << "seed " << seed;
  }
}

TEST(Simulate, RoadHasARampOfAtLeastEightPercent) {
  int plateaus = 0;
  for (uint32_t seed : {1u, 2u, 3u, 4u, 5u}) {
    const SimScan scan = Simulate(Hdl64Like(), Urban(seed));
    const SimScene& s = scan.scene;
    EXPECT_GE(s.ramp_grade, 0.08);
    EXPECT_LE(s.ramp_grade, 0.10);
    const double x0 = s.ramp_start_x, x1 = s.ramp_start_x + s.ramp_length;
    // Road points on the ramp: fit z = a x + b in the world frame.
    std::vector<double> xs, zs, top;
    for (const WorldPoint& p : ToWorld(scan)) {
      if (p.label != SkClass::kRoad || std::abs(p.y - s.road_center_y) > s.road_half_width - 0.3)
        continue;
      if (p.x > x0 + 1 && p.x < x1 - 1) xs.push_back(p.x), zs.push_back(p.z);
      if (p.x > x1 + 2) top.push_back(p.z);
    }
    ASSERT_GT(xs.size(), 200u) << "seed " << seed;
    Eigen::MatrixXd a(xs.size(), 2);
    Eigen::VectorXd z(xs.size());
    for (size_t k = 0; k < xs.size(); ++k) a(k, 0) = xs[k], a(k, 1) = 1.0, z(k) = zs[k];
    const Eigen::Vector2d fit = a.colPivHouseholderQr().solve(z);
    EXPECT_GE(fit(0), 0.08) << "seed " << seed;
    EXPECT_NEAR(fit(0), s.ramp_grade, 0.005) << "seed " << seed;
    // The road beyond is flat again; it rises 1.2-2 m, close to the sensor's height, so only
    // some scenes show it to the near-horizontal beams.
    if (top.size() >= 20) {
      ++plateaus;
      EXPECT_NEAR(Median(top), s.ramp_grade * s.ramp_length, 0.02) << "road beyond the ramp";
    }
  }
  EXPECT_GT(plateaus, 0);
}

TEST(Simulate, CurbsAreTenToFifteenCentimetres) {
  for (uint32_t seed : {1u, 2u, 3u, 4u, 5u}) {
    const SimScan scan = Simulate(Hdl64Like(), Urban(seed));
    const SimScene& s = scan.scene;
    std::vector<double> road, walk[2];
    size_t face = 0;
    for (const WorldPoint& p : ToWorld(scan)) {
      if (p.x < -30 || p.x > 15) continue;  // the flat stretch before the ramp
      const double dy = p.y - s.road_center_y;
      const int side = dy < 0 ? 0 : 1;
      if (p.label == SkClass::kRoad && std::abs(dy) < s.road_half_width - 0.2) road.push_back(p.z);
      if (p.label != SkClass::kSidewalk) continue;
      if (std::abs(dy) > s.road_half_width + 0.3 &&
          std::abs(dy) < s.road_half_width + s.sidewalk_width[side] - 0.1)
        walk[side].push_back(p.z);
      if (std::abs(std::abs(dy) - s.road_half_width) < 0.05 && p.z > 0.02 &&
          p.z < s.curb_height[side] - 0.02)
        ++face;
    }
    const double road_z = Median(road);
    EXPECT_NEAR(road_z, 0.0, 0.01);
    for (int side = 0; side < 2; ++side) {
      EXPECT_GE(s.curb_height[side], 0.10);
      EXPECT_LE(s.curb_height[side], 0.15);
      ASSERT_GT(walk[side].size(), 200u) << "seed " << seed << " side " << side;
      const double step = Median(walk[side]) - road_z;
      EXPECT_NEAR(step, s.curb_height[side], 0.01) << "seed " << seed << " side " << side;
    }
    EXPECT_GT(face, 5u) << "points on the vertical curb faces, seed " << seed;
  }
}

TEST(Simulate, ReflectionNoiseLiesUnderTheRoad) {
  SimOptions o = Urban(3);
  const SimScan scan = Simulate(Hdl64Like(), o);
  size_t noise = 0;
  for (size_t i = 0; i < scan.cloud.size(); ++i) {
    if (scan.labels[i] != SkClass::kOutlier) continue;
    ++noise;
    const double p[3] = {scan.cloud.x(i), scan.cloud.y(i), scan.cloud.z(i)};
    double w[3];
    scan.scene.SensorToWorld(p, w);
    const double depth = scan.scene.GroundHeight(w[0], w[1]) - w[2];
    EXPECT_GT(depth, 0.4);
    EXPECT_LT(depth, 2.3);
    EXPECT_LT(scan.cloud.intensity(i), 0.06f);
  }
  EXPECT_GE(noise, 3u);
  EXPECT_LE(noise, 200u);
  o.reflection_noise = false;
  const SimScan clean = Simulate(Hdl64Like(), o);
  EXPECT_EQ(0, std::count(clean.labels.begin(), clean.labels.end(), SkClass::kOutlier));
}

TEST(Simulate, RingsAzimuthAndIntensity) {
  SensorProfile sensor = Hdl64Like();
  SimOptions o;
  o.kind = kFlat;
  o.emit_rings = true;
  o.range_noise_m = 0;
  const SimScan scan = Simulate(sensor, o);
  ASSERT_EQ(scan.cloud.ring.size(), scan.cloud.size());
  // Beam by beam from the top: ring_zero_is_top is false, so rings count down from 63.
  EXPECT_TRUE(std::is_sorted(scan.cloud.ring.rbegin(), scan.cloud.ring.rend()));
  EXPECT_EQ(scan.cloud.ring.back(), 0);
  // On flat ground every ray of the lowest beam hits: column 0 looks back along -x, just left
  // of it, and the sweep turns clockwise (through +y, then +x, then -y).
  const size_t n = scan.cloud.size(), first = n - 2048;
  ASSERT_EQ(scan.cloud.ring[first], 0);
  EXPECT_LT(scan.cloud.x(first), 0.0f);
  EXPECT_GT(scan.cloud.y(first), 0.0f);
  EXPECT_LT(std::abs(scan.cloud.y(first)), 0.02f);
  EXPECT_GT(scan.cloud.y(first + 512), 3.0f);
  EXPECT_GT(scan.cloud.x(first + 1024), 3.0f);
  EXPECT_LT(scan.cloud.y(first + 1536), -3.0f);
  float max_intensity = 0;
  for (size_t i = 0; i < n; ++i) max_intensity = std::max(max_intensity, scan.cloud.intensity(i));
  EXPECT_GT(max_intensity, 0.15f);  // the surfaces' reflectivity, in [0, 1]
  EXPECT_LE(max_intensity, 1.0f);

  sensor.ring_zero_is_top = true;
  const SimScan top = Simulate(sensor, o);
  EXPECT_TRUE(std::is_sorted(top.cloud.ring.begin(), top.cloud.ring.end()));
  EXPECT_EQ(top.cloud.ring.back(), 63);
}

TEST(Simulate, SceneDoesNotDependOnTheSensor) {
  SensorProfile other = Hdl64Like();
  other.beams = 16;
  other.width = 1800;
  other.elevation_deg.clear();
  for (int i = 0; i < 16; ++i) other.elevation_deg.push_back(15.0f - 2.0f * i);
  other.sensor_height = 1.9f;
  const SimScan a = Simulate(Hdl64Like(), Urban(5));
  const SimScan b = Simulate(other, Urban(5));
  EXPECT_EQ(a.scene.primitives.size(), b.scene.primitives.size());
  EXPECT_EQ(a.scene.ramp_start_x, b.scene.ramp_start_x);
  EXPECT_GT(b.cloud.size(), 5000u);
}

TEST(Simulate, RejectsBadInput) {
  SensorProfile bad = Hdl64Like();
  bad.elevation_deg.pop_back();
  EXPECT_THROW(Simulate(bad, Urban(1)), std::invalid_argument);
  SimOptions o = Urban(1);
  o.pitch_deg = 31;
  EXPECT_THROW(Simulate(Hdl64Like(), o), std::invalid_argument);
  o.pitch_deg = 0;
  o.roll_deg = NAN;
  EXPECT_THROW(Simulate(Hdl64Like(), o), std::invalid_argument);
}

double AngleFromX(double x, double y, double z) { return std::atan2(std::hypot(y, z), x) / kDeg; }

double Elevation(double x, double y, double z) { return std::atan2(z, std::hypot(x, y)) / kDeg; }

// The range-image pixel (row by 1 degree bin under the table's top edge, column by eq. 1's
// azimuth) of each ray of a frame.
std::set<std::pair<int, int>> Pixels(const SensorProfile& s,
                                     const std::vector<std::array<double, 3>>& rays) {
  const double top = s.elevation_deg[0] + 0.5;
  std::set<std::pair<int, int>> pixels;
  for (const auto& d : rays) {
    const double az = std::atan2(d[1], d[0]);
    const int row = static_cast<int>(std::floor(top - Elevation(d[0], d[1], d[2])));
    const int col = static_cast<int>(std::floor((kPi - az) / (2 * kPi) * s.width)) % s.width;
    pixels.insert({row, col});
  }
  return pixels;
}

TEST(SimulatePattern, RosetteRaysFillTheFieldOfViewCircle) {
  const SensorProfile s = LivoxLike(ScanPattern::kRosette);
  const std::vector<std::array<double, 3>> rays = PatternRays(s, 3);
  ASSERT_EQ(rays.size(), 10000u);
  double widest = 0;
  for (const auto& d : rays) {
    EXPECT_NEAR(d[0] * d[0] + d[1] * d[1] + d[2] * d[2], 1.0, 1e-12);
    widest = std::max(widest, AngleFromX(d[0], d[1], d[2]));
  }
  EXPECT_LE(widest, 35.0 + 1e-9);  // the table's top bin centre plus half a bin
  EXPECT_GT(widest, 34.9);         // the petals reach the edge
  // Simulated points keep their ray's direction (the range noise moves them along it).
  const SimScan scan = Simulate(s, Urban(3));
  EXPECT_GT(scan.cloud.size(), 3000u);
  EXPECT_LT(scan.cloud.size(), 10000u);  // sky, and the returns under min_range, give none
  for (size_t i = 0; i < scan.cloud.size(); ++i)
    ASSERT_LE(AngleFromX(scan.cloud.x(i), scan.cloud.y(i), scan.cloud.z(i)), 35.01) << i;
}

TEST(SimulatePattern, BandRaysTurnThroughTheElevationBand) {
  const SensorProfile s = LivoxLike(ScanPattern::kBand);
  const std::vector<std::array<double, 3>> rays = PatternRays(s, 3);
  ASSERT_EQ(rays.size(), 20000u);
  double lowest = 90, highest = -90;
  std::set<int> octants;  // the azimuth's eighths of a turn
  for (const auto& d : rays) {
    const double e = Elevation(d[0], d[1], d[2]);
    lowest = std::min(lowest, e), highest = std::max(highest, e);
    const double eighths = (std::atan2(d[1], d[0]) + kPi) / (kPi / 4);  // in [0, 8]
    octants.insert(std::min(7, static_cast<int>(eighths)));
  }
  EXPECT_GE(lowest, -7.0 - 1e-9);
  EXPECT_LE(highest, 52.0 + 1e-9);
  EXPECT_LT(lowest, -6.9);
  EXPECT_GT(highest, 51.9);
  EXPECT_EQ(octants.size(), 8u);
  const SimScan scan = Simulate(s, Urban(3));
  EXPECT_GT(scan.cloud.size(), 3000u);
  EXPECT_LT(scan.cloud.size(), 20000u);
  for (size_t i = 0; i < scan.cloud.size(); ++i) {
    const double e = Elevation(scan.cloud.x(i), scan.cloud.y(i), scan.cloud.z(i));
    ASSERT_GE(e, -7.01) << i;
    ASSERT_LE(e, 52.01) << i;
  }
}

// Frames (seeds) fire other rays, and ten of them together fill far more of the image than one:
// the pattern does not repeat.
TEST(SimulatePattern, FramesDifferAndTogetherFillTheImage) {
  for (ScanPattern pattern : {ScanPattern::kRosette, ScanPattern::kBand}) {
    const SensorProfile s = LivoxLike(pattern);
    SCOPED_TRACE(s.name);
    const std::vector<std::array<double, 3>> one = PatternRays(s, 1), two = PatternRays(s, 2);
    ASSERT_EQ(one.size(), two.size());
    size_t same = 0;
    for (size_t k = 0; k < one.size(); ++k) same += one[k] == two[k];
    EXPECT_EQ(same, 0u);
    EXPECT_EQ(PatternRays(s, 1), one);  // and the same seed fires the same rays

    const size_t first = Pixels(s, one).size();
    std::set<std::pair<int, int>> all;
    for (uint32_t seed = 1; seed <= 10; ++seed) {
      const std::set<std::pair<int, int>> p = Pixels(s, PatternRays(s, seed));
      all.insert(p.begin(), p.end());
    }
    std::printf("%s: one frame %zu pixels, ten frames %zu\n", s.name.c_str(), first, all.size());
    // Measured: rosette 2,450 -> 8,471 (of the circle's ~8,500), band 15,614 -> all 22,656.
    EXPECT_GT(static_cast<double>(all.size()),
              (pattern == ScanPattern::kRosette ? 2.5 : 1.3) * first);
  }
}

TEST(SimulatePattern, RejectsRingsAndAMissingFrameSize) {
  SensorProfile s = LivoxLike(ScanPattern::kRosette);
  SimOptions o = Urban(1);
  o.emit_rings = true;
  EXPECT_THROW(Simulate(s, o), std::invalid_argument);
  s.frame_points = 0;
  try {
    Simulate(s, Urban(1));
    ADD_FAILURE() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("frame_points"), std::string::npos) << e.what();
  }
  EXPECT_THROW(PatternRays(Hdl64Like(), 1), std::invalid_argument);
}

TEST(SimulateCli, RejectsBadArguments) {
  const std::string dir = test::TempDir();
  const std::string cli = test::CliPath() + " simulate ";
  const std::string files = " --out " + dir + "/a.bin --labels " + dir + "/a.label";
  std::string out;
  EXPECT_NE(0, test::RunCommand(cli + "--sensor hdl64e --seed -3" + files, &out)) << out;
  EXPECT_NE(out.find("--seed"), std::string::npos) << out;
  EXPECT_NE(0, test::RunCommand(cli + "--sensor hdl64e --seed abc" + files, &out)) << out;
  EXPECT_NE(0, test::RunCommand(cli + "--sensor hdl64e --seed 1 --pitch 45" + files, &out));
  EXPECT_NE(out.find("--pitch"), std::string::npos) << out;
  EXPECT_NE(0, test::RunCommand(cli + "--sensor hdl64e --seed 1 --roll -31" + files, &out));
  EXPECT_NE(0, test::RunCommand(cli + "--sensor no-such-lidar --seed 1" + files, &out));
  EXPECT_NE(out.find("no-such-lidar"), std::string::npos) << out;
  EXPECT_NE(0, test::RunCommand(cli + "--sensor hdl64e --seed 1 --scene moon" + files, &out));
  EXPECT_NE(0, test::RunCommand(cli + "--sensor hdl64e --seed 1", &out));
}

// Through a profile file written next to the outputs (so this does not need sensors/*.txt), then
// by name when the shipped hdl64e profile exists.
TEST(SimulateCli, WritesScanAndLabels) {
  const std::string dir = test::TempDir();
  SensorProfile profile = Hdl64Like();
  WriteSensorProfile(dir + "/hdl64-test.txt", profile);
  std::string out;
  ASSERT_EQ(0, test::RunCommand(test::CliPath() + " simulate --sensor " + dir +
                                    "/hdl64-test.txt --seed 3 --pitch 1 --roll -2 --out " + dir +
                                    "/s.bin --labels " + dir + "/s.label",
                                &out))
      << out;
  EXPECT_NE(out.find("points"), std::string::npos) << out;
  EXPECT_NE(out.find("ground"), std::string::npos) << out;
  EXPECT_NE(out.find("s.label"), std::string::npos) << out;
  const Cloud cloud = ReadKittiBin(dir + "/s.bin");
  const std::vector<uint32_t> labels = ReadLabelFile(dir + "/s.label", cloud.size());
  SimOptions o = Urban(3);
  o.pitch_deg = 1;
  o.roll_deg = -2;
  const SimScan direct = Simulate(profile, o);
  ASSERT_EQ(cloud.xyzi.size(), direct.cloud.xyzi.size());
  EXPECT_EQ(0, std::memcmp(cloud.xyzi.data(), direct.cloud.xyzi.data(),
                           cloud.xyzi.size() * sizeof(float)));
  EXPECT_EQ(labels, direct.labels);

  ASSERT_EQ(0, test::RunCommand(test::CliPath() + " simulate --sensor " + dir +
                                    "/hdl64-test.txt --seed 3 --scene flat --out " + dir +
                                    "/f.bin --labels " + dir + "/f.label",
                                &out))
      << out;
  if (!std::filesystem::exists(test::SensorsDir() + "/hdl64e.txt"))
    GTEST_SKIP() << "sensors/hdl64e.txt not found in " << test::SensorsDir();
  ASSERT_EQ(0, test::RunCommand(test::CliPath() + " simulate --sensor hdl64e --seed 3 --out " +
                                    dir + "/k.bin --labels " + dir + "/k.label",
                                &out))
      << out;
  EXPECT_GT(ReadKittiBin(dir + "/k.bin").size(), 80000u);
}

// The shipped Livox profiles simulate their own pattern: a Mid-70 frame's points within its
// 35 degree circle, a Mid-360's all around, fewer than the frame's returns (sky gives none).
TEST(SimulateCli, LivoxProfilesCastTheirPattern) {
  if (!std::filesystem::exists(test::SensorsDir() + "/mid70.txt"))
    GTEST_SKIP() << "sensors/mid70.txt not found in " << test::SensorsDir();
  const std::string dir = test::TempDir();
  for (const char* name : {"mid70", "mid360"}) {
    SCOPED_TRACE(name);
    const SensorProfile profile = LoadSensorProfile(name, test::SensorsDir());
    std::string out;
    ASSERT_EQ(0,
              test::RunCommand(test::CliPath() + " simulate --sensor " + name + " --seed 2 --out " +
                                   dir + "/l.bin --labels " + dir + "/l.label",
                               &out))
        << out;
    const Cloud cloud = ReadKittiBin(dir + "/l.bin");
    EXPECT_GT(cloud.size(), profile.frame_points / 5);
    EXPECT_LT(cloud.size(), profile.frame_points);
    double widest = 0, behind = 0;
    for (size_t i = 0; i < cloud.size(); ++i) {
      widest = std::max(widest, AngleFromX(cloud.x(i), cloud.y(i), cloud.z(i)));
      behind += cloud.x(i) < 0;
    }
    if (profile.pattern == ScanPattern::kRosette) {
      EXPECT_LE(widest, 35.01);
    } else {
      EXPECT_GT(behind, cloud.size() / 4);
    }
  }
}

}  // namespace
}  // namespace lpir
