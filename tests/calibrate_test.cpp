// calibrate (host/eval/calibrate.h, paper III-B.3): simulated HDL-64E scans of flat
// ground tilted by known pitch and roll (apps/sim, the same sign convention) read back as
// themselves; noise, objects beside the ground and several scans; the refusals; and the payoff:
// segmenting a tilted street with the calibrated profile scores as the level street does.
#include "host/eval/calibrate.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "apps/sim/scene.h"
#include "host/api/segmenter.h"
#include "host/eval/metrics.h"
#include "host/io/sensor_profile.h"
#include "reference_cpu/params.h"

namespace lpir {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kAngleTol = 0.05;   // degrees (issue 4, done-when 1)
constexpr double kHeightTol = 0.01;  // m

SensorProfile Hdl64() { return LoadSensorProfile("hdl64e", LPIR_SENSORS_DIR); }

SimScan Tilted(SceneKind kind, uint32_t seed, float pitch, float roll, float noise = 0.02f) {
  SimOptions o;
  o.seed = seed;
  o.kind = kind;
  o.pitch_deg = pitch;
  o.roll_deg = roll;
  o.range_noise_m = noise;
  return Simulate(Hdl64(), o);
}

// Pitch and roll for seed s, uniform in [-5, 5] degrees (std::mt19937's raw outputs: portable).
void DrawTilt(uint32_t s, float* pitch, float* roll) {
  std::mt19937 rng(1000u + s);
  *pitch = float(double(rng()) / 4294967296.0 * 10.0 - 5.0);
  *roll = float(double(rng()) / 4294967296.0 * 10.0 - 5.0);
}

// Checks an accepted calibration against the simulated truth; returns the largest angle error.
double ExpectReadsBack(const Calibration& c, float pitch, float roll, float height) {
  EXPECT_TRUE(c.ok()) << c.reason;
  EXPECT_NEAR(c.pitch_deg, pitch, kAngleTol);
  EXPECT_NEAR(c.roll_deg, roll, kAngleTol);
  EXPECT_NEAR(c.b_x, height, kHeightTol);
  EXPECT_NEAR(c.b_y, height, kHeightTol);
  EXPECT_NEAR(c.k_xz, std::tan(pitch * kPi / 180), std::tan(kAngleTol * kPi / 180));
  return std::max(std::abs(c.pitch_deg - pitch), std::abs(c.roll_deg - roll));
}

TEST(Calibrate, FlatGroundTiltsReadBackAsThemselves) {
  const SensorProfile s = Hdl64();
  double worst = 0, worst_b = 0;
  // 24 random tilts plus the corners of [-5, 5]^2.
  std::vector<std::pair<float, float>> tilts;
  for (uint32_t seed = 0; seed < 24; ++seed) {
    float p, r;
    DrawTilt(seed, &p, &r);
    tilts.push_back({p, r});
  }
  for (float p : {-5.0f, 5.0f})
    for (float r : {-5.0f, 5.0f}) tilts.push_back({p, r});
  for (size_t t = 0; t < tilts.size(); ++t) {
    const auto [pitch, roll] = tilts[t];
    SCOPED_TRACE("scene seed " + std::to_string(t) + ": pitch " + std::to_string(pitch) + " roll " +
                 std::to_string(roll));
    const SimScan scan = Tilted(kFlat, uint32_t(t), pitch, roll);
    const Calibration c = Calibrate({scan.cloud}, s);
    worst = std::max(worst, ExpectReadsBack(c, pitch, roll, s.sensor_height));
    worst_b =
        std::max({worst_b, std::abs(c.b_x - s.sensor_height), std::abs(c.b_y - s.sensor_height)});
    for (int d = 0; d < 4; ++d) EXPECT_GT(c.band_points[d], 100u) << CalibDirectionName(d);
  }
  RecordProperty("worst_angle_error_deg", std::to_string(worst));
  RecordProperty("worst_height_error_m", std::to_string(worst_b));
  std::printf("flat, %zu tilts in [-5, 5] deg: worst angle error %.4f deg, worst b error %.4f m\n",
              tilts.size(), worst, worst_b);
}

TEST(Calibrate, NoisyGroundStillReadsBack) {
  const SensorProfile s = Hdl64();
  for (uint32_t seed = 0; seed < 4; ++seed) {
    float pitch, roll;
    DrawTilt(100 + seed, &pitch, &roll);
    SCOPED_TRACE("seed " + std::to_string(seed));
    // Range noise 2.5x the default, the simulator's reflection noise, and a cluster 2.5 m under
    // the ground straight ahead and to the left (multipath off a wet road).
    SimScan scan = Tilted(kFlat, seed, pitch, roll, 0.05f);
    const double kx = std::tan(pitch * kPi / 180), ky = std::tan(roll * kPi / 180);
    const float h_noise = ParamsForSensor(s).h_noise;
    size_t flaggable = 0;  // planted points the filter can see: raw z under h_noise (III-B.1)
    for (int k = 0; k < 300; ++k) {
      const double r = 5.0 + 0.08 * k, az = (k % 2 ? 1.0 : 0.0) * kPi / 2 + 0.001 * (k % 5 - 2);
      const double x = r * std::cos(az), y = r * std::sin(az);
      const float z = float(kx * x + ky * y - s.sensor_height - 2.5);
      scan.cloud.Push(float(x), float(y), z, 0.02f);
      flaggable += z < h_noise ? 1 : 0;
    }
    ASSERT_GT(flaggable, 100u);
    const Calibration c = Calibrate({scan.cloud}, s);
    ExpectReadsBack(c, pitch, roll, s.sensor_height);
    EXPECT_GE(c.noise_points, flaggable) << "the planted noise is not filtered (III-B.1)";
    // Without the filter the height gate and RANSAC still keep them out of the lines.
    CalibrateOptions no_filter;
    no_filter.noise_filter = false;
    const Calibration raw = Calibrate({scan.cloud}, s, no_filter);
    EXPECT_EQ(raw.noise_points, 0u);
    ExpectReadsBack(raw, pitch, roll, s.sensor_height);
  }
}

TEST(Calibrate, CarAndWallBesideFlatGroundDoNotBendTheLines) {
  const SensorProfile s = Hdl64();
  for (uint32_t seed = 0; seed < 6; ++seed) {
    float pitch, roll;
    DrawTilt(200 + seed, &pitch, &roll);
    SCOPED_TRACE("seed " + std::to_string(seed));
    const SimScan scan = Tilted(kFlatWithObjects, seed, pitch, roll);
    const Calibration c = Calibrate({scan.cloud}, s);
    ExpectReadsBack(c, pitch, roll, s.sensor_height);
    // The car (ahead) and the wall (left) put outliers into the bands; RANSAC leaves them out.
    EXPECT_LT(c.xoz.inliers, c.xoz.points);
    EXPECT_LT(c.yoz.inliers, c.yoz.points);
  }
}

TEST(Calibrate, SeveralScansArePooled) {
  const SensorProfile s = Hdl64();
  const SimScan a = Tilted(kFlat, 1, 2.0f, -1.5f), b = Tilted(kFlatWithObjects, 2, 2.0f, -1.5f);
  const Calibration ca = Calibrate({a.cloud}, s), cb = Calibrate({b.cloud}, s);
  const Calibration both = Calibrate({a.cloud, b.cloud}, s);
  EXPECT_EQ(both.scans, 2u);
  for (int d = 0; d < 4; ++d) EXPECT_EQ(both.band_points[d], ca.band_points[d] + cb.band_points[d]);
  ExpectReadsBack(both, 2.0f, -1.5f, s.sensor_height);
}

TEST(Calibrate, SameInputGivesTheSameOutput) {
  const SensorProfile s = Hdl64();
  const SimScan scan = Tilted(kFlatWithObjects, 7, -3.0f, 4.0f);
  const Calibration a = Calibrate({scan.cloud}, s), b = Calibrate({scan.cloud}, s);
  for (auto [x, y] : {std::pair{a.k_xz, b.k_xz}, {a.k_yz, b.k_yz}, {a.b_x, b.b_x}, {a.b_y, b.b_y}})
    EXPECT_EQ(std::memcmp(&x, &y, sizeof(double)), 0);
  EXPECT_EQ(a.xoz.inliers, b.xoz.inliers);
  EXPECT_EQ(a.yoz.inliers, b.yoz.inliers);
}

// A synthetic scan of the four bands (6 columns of 2048 each) every 25 cm from r0 to r1 m, z
// from `height(x, y)`.
template <class Height>
Cloud Bands(const Height& height, double r0 = 3.5, double r1 = 30.0) {
  const double width = 2048;
  Cloud c;
  for (double az0 : {0.0, kPi, kPi / 2, -kPi / 2})
    for (int col = -3; col < 3; ++col)
      for (double r = r0; r < r1; r += 0.25) {
        const double az = az0 + (col + 0.5) * 2 * kPi / width;
        const double x = r * std::cos(az), y = r * std::sin(az);
        c.Push(float(x), float(y), float(height(x, y)), 0.3f);
      }
  return c;
}

TEST(CalibrateRefuses, TooFewPointsSurviveTheGates) {
  const SensorProfile s = Hdl64();
  // Nothing at all; then ground only beyond the distance gate; then ground only ahead and
  // behind (a corridor between walls higher than the height gate: nothing to the sides).
  const Cloud beyond = Bands([](double, double) { return -1.73; }, 31.0, 60.0);
  const Cloud all = Bands([](double, double) { return -1.73; });
  Cloud corridor;
  for (size_t i = 0; i < all.size(); ++i)
    if (std::abs(all.x(i)) > std::abs(all.y(i))) corridor.Push(all.x(i), all.y(i), all.z(i), 0.3f);
  for (const Cloud* cloud : std::vector<const Cloud*>{nullptr, &beyond, &corridor}) {
    const Calibration c = cloud ? Calibrate({*cloud}, s) : Calibrate({}, s);
    EXPECT_EQ(c.refusal, CalibRefusal::kTooFewPoints) << c.reason;
    EXPECT_NE(c.reason.find("too few points survive the gates"), std::string::npos) << c.reason;
    EXPECT_NE(c.reason.find("parking lot"), std::string::npos) << c.reason;  // what to do
  }
}

TEST(CalibrateRefuses, GroundOfRandomHeightsIsNotFlat) {
  const SensorProfile s = Hdl64();
  std::mt19937 rng(5);
  const Cloud bumpy = Bands([&](double, double) {
    return -1.73 + (double(rng()) / 4294967296.0 - 0.5) * 0.6;  // +-30 cm
  });
  const Calibration c = Calibrate({bumpy}, s);
  EXPECT_EQ(c.refusal, CalibRefusal::kNotFlat) << c.reason;
  EXPECT_NE(c.reason.find("not flat enough"), std::string::npos) << c.reason;
  EXPECT_LT(c.xoz.inlier_fraction, CalibrateOptions{}.min_inlier_fraction);
}

TEST(CalibrateRefuses, HeightsAheadAndAsideDisagreeByMoreThanACentimetre) {
  const SensorProfile s = Hdl64();
  // The sides stand 3 cm higher than the front and rear (a crowned road seen from its edge).
  const Cloud step =
      Bands([](double x, double y) { return std::abs(y) > std::abs(x) ? -1.70 : -1.73; });
  const Calibration c = Calibrate({step}, s);
  EXPECT_EQ(c.refusal, CalibRefusal::kHeightsDisagree) << c.reason;
  EXPECT_NEAR(c.b_x - c.b_y, 0.03, 1e-4);
  EXPECT_NE(c.reason.find("differ by 3.00 cm"), std::string::npos) << c.reason;
  // 8 mm is within the paper's 1 cm.
  const Cloud small =
      Bands([](double x, double y) { return std::abs(y) > std::abs(x) ? -1.722 : -1.73; });
  EXPECT_TRUE(Calibrate({small}, s).ok());
  // A wider limit accepts the 3 cm step.
  CalibrateOptions wide;
  wide.max_b_diff = 0.05f;
  EXPECT_TRUE(Calibrate({step}, s, wide).ok());
}

TEST(CalibrateRefuses, SimulatedStreetWithCurbsAndARamp) {
  // The urban scene: a ramp ahead from 20-25 m, curbs and sidewalks 10-15 cm above the road
  // beside it. Recorded as measured: which check it trips.
  const SensorProfile s = Hdl64();
  for (uint32_t seed = 0; seed < 3; ++seed) {
    const SimScan scan = Tilted(kUrban, seed, 0.0f, 0.0f);
    const Calibration c = Calibrate({scan.cloud}, s);
    std::printf("urban seed %u: %s k_xz %.5f k_yz %.5f b_x %.4f b_y %.4f (%s)\n", seed,
                c.ok() ? "accepted" : "refused", c.k_xz, c.k_yz, c.b_x, c.b_y, c.reason.c_str());
    EXPECT_FALSE(c.ok());
    EXPECT_FALSE(c.reason.empty());
  }
}

TEST(Calibrate, ApplyCalibrationWritesTheProfileFields) {
  const SensorProfile s = Hdl64();
  const Calibration c = Calibrate({Tilted(kFlat, 3, 1.0f, -2.0f).cloud}, s);
  ASSERT_TRUE(c.ok()) << c.reason;
  const SensorProfile p = ApplyCalibration(s, c);
  EXPECT_EQ(p.k_xz, float(c.k_xz));
  EXPECT_EQ(p.k_yz, float(c.k_yz));
  EXPECT_EQ(p.b_x, float(c.b_x));
  EXPECT_EQ(p.b_y, float(c.b_y));
  EXPECT_EQ(p.sensor_height, s.sensor_height);
  EXPECT_EQ(ApplyCalibration(s, c, true).sensor_height, float(0.5 * (c.b_x + c.b_y)));
  Calibration refused = c;
  refused.refusal = CalibRefusal::kNotFlat;
  EXPECT_THROW(ApplyCalibration(s, refused), std::invalid_argument);
}

// Issue 4, done-when 2: the mount is calibrated once on flat ground, then a street seen through
// the same tilted mount is segmented with that profile and scores as the level street does.
double StreetF1(const SensorProfile& profile, const SimScan& scan) {
  Segmenter seg(profile, SegmenterOptions::For(Backend::kCpu));
  const Frame& f = seg.Segment(scan.cloud);
  const Labels pred(f.label.begin(), f.label.end());
  return ScoreCounts(CountFrame(Protocol::kDG, pred, scan.labels, nullptr)).f1;
}

TEST(Calibrate, CalibratedProfileRestoresF1OnATiltedStreet) {
  const SensorProfile s = Hdl64();
  for (auto [pitch, roll] : {std::pair{3.0f, 0.0f}, {0.0f, 3.0f}, {-3.0f, 0.0f}}) {
    SCOPED_TRACE("pitch " + std::to_string(pitch) + " roll " + std::to_string(roll));
    const Calibration c = Calibrate({Tilted(kFlat, 11, pitch, roll).cloud}, s);
    ASSERT_TRUE(c.ok()) << c.reason;
    const SensorProfile calibrated = ApplyCalibration(s, c);
    for (uint32_t seed : {1u, 2u}) {
      const double level = StreetF1(s, Tilted(kUrban, seed, 0.0f, 0.0f));
      const SimScan tilted = Tilted(kUrban, seed, pitch, roll);
      const double raw = StreetF1(s, tilted);
      const double fixed = StreetF1(calibrated, tilted);
      std::printf(
          "street seed %u, pitch %+.1f roll %+.1f: DG F1 level %.2f, tilted without "
          "calibration %.2f (drop %+.2f), with %.2f (drop %+.2f)\n",
          seed, pitch, roll, 100 * level, 100 * raw, 100 * (level - raw), 100 * fixed,
          100 * (level - fixed));
      RecordProperty("f1_drop_uncalibrated_p" + std::to_string(int(pitch)) + "_r" +
                         std::to_string(int(roll)) + "_seed" + std::to_string(seed),
                     std::to_string(100 * (level - raw)));
      EXPECT_NEAR(fixed, level, 0.005);  // within 0.5 F1 points (issue 4, done-when 2)
    }
  }
}

}  // namespace
}  // namespace lpir
