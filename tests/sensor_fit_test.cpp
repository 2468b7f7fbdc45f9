// A cloud that does not fit its sensor profile (host/api/sensor_fit.h): rings past the beams are an
// error on more than 1 % of the points and a warning below that; elevations outside the profile's
// table, or outside a rosette's circle, are a warning; a simulated street of every profile fits its
// own profile.
#include "host/api/sensor_fit.h"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include "apps/sim/scene.h"
#include "host/api/segmenter.h"
#include "host/io/cloud_file.h"
#include "host/io/sensor_profile.h"
#include "tests/test_util.h"

namespace lpir {
namespace {

SensorProfile Profile(const std::string& name) {
  return LoadSensorProfile(name, test::SensorsDir());
}

// A simulated street of `sensor` (seed 2), with its rings when `rings`.
Cloud Street(const std::string& sensor, bool rings) {
  SimOptions o;
  o.seed = 2;
  o.emit_rings = rings;
  return Simulate(Profile(sensor), o).cloud;
}

bool Contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

TEST(SensorFit, RingsOfA64BeamSensorOnA32BeamProfileAreRefused) {
  const Cloud cloud = Street("hdl64e", true);
  Segmenter seg(Profile("vlp32c"), SegmenterOptions::For(Backend::kCpu));
  try {
    seg.Segment(cloud);
    ADD_FAILURE() << "a 64-ring cloud was segmented with a 32-beam profile";
  } catch (const std::invalid_argument& e) {
    const std::string m = e.what();
    EXPECT_TRUE(Contains(m, "ring values up to 63")) << m;
    EXPECT_TRUE(Contains(m, "points outside 0..31")) << m;
    EXPECT_TRUE(Contains(m, "profile 'vlp32c' has 32 beams: wrong --sensor?")) << m;
  }
}

TEST(SensorFit, ACloudLargerThanTheProfileTakesNamesTheProfile) {
  const Cloud cloud = Street("hdl64e", false);  // 127,974 points
  Segmenter seg(Profile("vlp16"), SegmenterOptions::For(Backend::kCpu));
  try {
    seg.Segment(cloud);
    ADD_FAILURE() << "a cloud larger than max_points was segmented";
  } catch (const std::length_error& e) {
    const std::string m = e.what();
    EXPECT_TRUE(Contains(m, "cloud has " + std::to_string(cloud.size()) + " points")) << m;
    EXPECT_TRUE(Contains(m, "profile 'vlp16', 16 beams x 1792 columns): wrong --sensor?")) << m;
  }
}

TEST(SensorFit, AFewRingsPastTheBeamsAreAWarningAndInvalidPoints) {
  Cloud cloud = Street("vlp32c", true);
  const size_t bad = cloud.size() / 200;  // 0.5 %
  for (size_t k = 0; k < bad; ++k) cloud.ring[k * 200] = 40;
  const SensorProfile sensor = Profile("vlp32c");
  const SensorFit fit = MeasureSensorFit(cloud, sensor);
  EXPECT_EQ(fit.rings_outside, bad);
  EXPECT_EQ(fit.ring_max, 40);
  EXPECT_EQ(SensorFitError(fit, sensor), "");
  const std::vector<std::string> warnings = SensorFitWarnings(fit, sensor);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_TRUE(Contains(warnings[0], "have a ring outside 0..31 (seen 0..40)")) << warnings[0];
  Segmenter seg(sensor, SegmenterOptions::For(Backend::kCpu));
  const Frame& f = seg.Segment(cloud);
  for (size_t k = 0; k < bad; ++k) EXPECT_EQ(f.why[k * 200], kWhyInvalid) << "point " << k * 200;
  // 2 % of the points: the error.
  for (size_t k = 0; k < cloud.size(); k += 50) cloud.ring[k] = -3;
  EXPECT_TRUE(
      Contains(SensorFitError(MeasureSensorFit(cloud, sensor), sensor), "ring values down to -3"));
}

TEST(SensorFit, ElevationsOutsideTheTableAreAWarning) {
  // An HDL-64E street (down to -24.9 deg) read with the VLP-16 profile (down to -15 deg).
  const Cloud cloud = Street("hdl64e", false);
  const SensorProfile vlp16 = Profile("vlp16");
  const SensorFit fit = MeasureSensorFit(cloud, vlp16);
  EXPECT_GT(fit.sampled, 1000u);
  EXPECT_GT(fit.below, fit.sampled / 10);
  EXPECT_EQ(fit.above, 0u);
  const std::vector<std::string> warnings = SensorFitWarnings(fit, vlp16);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_TRUE(Contains(warnings[0], "below the bottom beam (-15.0 deg) of profile 'vlp16'"))
      << warnings[0];
  EXPECT_TRUE(Contains(warnings[0], "wrong --sensor")) << warnings[0];
}

TEST(SensorFit, AFullTurnReadAsARosetteIsAWarning) {
  // An HDL-64E street (a full turn, elevations within the Mid-70's +-35 deg table) read with the
  // Mid-70 profile, which sees a 35 deg circle ahead: three quarters of the points lie behind
  // or beside it.
  const SensorProfile mid70 = Profile("mid70");
  const SensorFit fit = MeasureSensorFit(Street("hdl64e", false), mid70);
  EXPECT_GT(fit.outside_circle, fit.sampled / 2);
  EXPECT_EQ(fit.above + fit.below, 0u);
  const std::vector<std::string> warnings = SensorFitWarnings(fit, mid70);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_TRUE(Contains(warnings[0],
                       "outside the 35.0 deg circle about the x axis that profile "
                       "'mid70' sees"))
      << warnings[0];
  EXPECT_TRUE(Contains(warnings[0], "wrong --sensor")) << warnings[0];
}

TEST(SensorFit, EveryProfilesStreetFitsItsOwnProfile) {
  for (const std::string& name : KnownSensorProfiles(test::SensorsDir())) {
    const SensorProfile sensor = Profile(name);
    for (bool rings : {false, true}) {
      if (rings && sensor.pattern != ScanPattern::kSpinning) continue;  // no rings to simulate
      const SensorFit fit = MeasureSensorFit(Street(name, rings), sensor);
      EXPECT_GT(fit.sampled, 1000u) << name;
      EXPECT_EQ(fit.rings_outside, 0u) << name;
      EXPECT_EQ(SensorFitError(fit, sensor), "") << name;
      EXPECT_TRUE(SensorFitWarnings(fit, sensor).empty())
          << name << ": " << SensorFitWarnings(fit, sensor).front();
    }
  }
}

TEST(SensorFit, RealScansFitTheirOwnProfiles) {
  LPIR_REQUIRE_DATA("kitti/00/velodyne/000000.bin");
  const struct {
    const char* sensor;
    const char* file;
  } scans[] = {{"hdl64e", "kitti/00/velodyne/000000.bin"},
               {"hdl32e", "nuscenes/lidarseg/scene-0001/velodyne/000000.bin"},
               {"os1-64", "rellis3d/os1/000104.bin"},
               {"vlp32c", "rellis3d/vlp32c/000104.bin"},
               {"mid70", "livox/00/velodyne/000000.bin"},
               {"mid70", "livox/05/velodyne/000000.bin"},
               {"mid70", "livox/08/velodyne/000000.bin"}};
  for (const auto& s : scans) {
    const std::string path = test::DataFile(s.file);
    ASSERT_FALSE(path.empty()) << s.file;
    const SensorProfile sensor = Profile(s.sensor);
    const SensorFit fit = MeasureSensorFit(ReadCloud(path), sensor);
    EXPECT_TRUE(SensorFitWarnings(fit, sensor).empty()) << s.file;
    EXPECT_LT(fit.above + fit.below + fit.outside_circle, fit.sampled / 100 + 1) << s.file;
  }
  // And the KITTI scan with the VLP-16 profile is called out.
  const SensorProfile vlp16 = Profile("vlp16");
  const SensorFit wrong =
      MeasureSensorFit(ReadCloud(test::DataFile("kitti/00/velodyne/000000.bin")), vlp16);
  EXPECT_EQ(SensorFitWarnings(wrong, vlp16).size(), 1u);
}

}  // namespace
}  // namespace lpir
