// Labels do not depend on the unit of intensity (docs/decisions/intensity.md): a scan and the same
// scan with every intensity multiplied by 0.01, 255 or 65535, set to 0, or replaced by NaN, give
// the same label and why bytes, on a simulated street of every profile and on the real scans of
// ../shared/data (KITTI, nuScenes, RELLIS-3D) when present.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "apps/sim/scene.h"
#include "host/api/segmenter.h"
#include "host/io/kitti_bin.h"
#include "host/io/sensor_profile.h"
#include "tests/test_util.h"

namespace lpir {
namespace {

// `cloud` with its intensities replaced: scale * intensity, or `fixed` for every point when
// scale is 0.
Cloud WithIntensities(const Cloud& cloud, float scale, float fixed) {
  Cloud c = cloud;
  for (size_t i = 0; i < c.size(); ++i)
    c.xyzi[4 * i + 3] = scale != 0.0f ? c.xyzi[4 * i + 3] * scale : fixed;
  return c;
}

// Segments `cloud` as it is and in every other unit; expects the same labels and whys.
void ExpectSameInEveryUnit(const std::string& sensor, const Cloud& cloud, const std::string& what) {
  Segmenter seg(LoadSensorProfile(sensor, test::SensorsDir()),
                SegmenterOptions::For(Backend::kCpu));
  const Frame base = seg.Segment(cloud);
  size_t ground = 0;
  for (uint8_t l : base.label) ground += l;
  EXPECT_GT(ground, cloud.size() / 10) << what << ": too little ground to tell anything";
  const struct {
    const char* name;
    float scale, fixed;
  } units[] = {{"x0.01", 0.01f, 0.0f},
               {"x255", 255.0f, 0.0f},
               {"x65535", 65535.0f, 0.0f},
               {"all 0", 0.0f, 0.0f},
               {"all NaN", 0.0f, std::numeric_limits<float>::quiet_NaN()}};
  for (const auto& u : units) {
    const Frame f = seg.Segment(WithIntensities(cloud, u.scale, u.fixed));
    EXPECT_EQ(f.label, base.label) << what << ", intensities " << u.name;
    EXPECT_EQ(f.why, base.why) << what << ", intensities " << u.name;
  }
}

TEST(IntensityUnits, SimulatedStreetOfEveryProfile) {
  for (const std::string& sensor : KnownSensorProfiles(test::SensorsDir())) {
    SimOptions options;
    options.seed = 3;
    const Cloud cloud = Simulate(LoadSensorProfile(sensor, test::SensorsDir()), options).cloud;
    ExpectSameInEveryUnit(sensor, cloud, sensor + " street");
  }
}

TEST(IntensityUnits, RealScans) {
  LPIR_REQUIRE_DATA("kitti/00/velodyne/000000.bin");
  const struct {
    const char* sensor;
    const char* file;
  } scans[] = {{"hdl64e", "kitti/00/velodyne/000000.bin"},
               {"hdl64e", "kitti/sglc/velodyne/000052.bin"},
               {"hdl32e", "nuscenes/lidarseg/scene-0001/velodyne/000010.bin"},
               {"os1-64", "rellis3d/os1/000104.bin"}};
  for (const auto& s : scans) {
    const std::string path = test::DataFile(s.file);
    if (path.empty()) {
      ADD_FAILURE() << s.file << " is missing from ../shared/data";
      continue;
    }
    ExpectSameInEveryUnit(s.sensor, ReadKittiBin(path), s.file);
  }
}

}  // namespace
}  // namespace lpir
