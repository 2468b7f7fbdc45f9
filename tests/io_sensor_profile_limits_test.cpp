// Regression (issue 6, found under UBSan): a sensor profile could give a mount tilt (k_xz, k_yz)
// or a max_range so large that a valid point's corrected height z_t overflowed the float -> int64
// conversion of coarse_segment's fixed point (reference_cpu/exact.h ToFixed), undefined behaviour
// that the two backends need not agree on. The reader now bounds |k| <= 1 and max_range <= 1000 m;
// at those bounds the most extreme valid points go through every stage (the sanitizer build
// aborts on any overflow, so this test is only as strong as that build; the plain build checks
// the labels' contract).
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "host/io/io_error.h"
#include "host/io/sensor_profile.h"
#include "reference_cpu/frame.h"
#include "reference_cpu/params.h"
#include "reference_cpu/pipeline.h"
#include "tests/test_util.h"

namespace lpir {
namespace {

std::string Profile(const std::string& extra) {
  return "name limits\nbeams 4\nwidth 256\nelevation_deg 10 0 -10 -20\nmin_range 1\n" + extra;
}

std::string Write(const std::string& text) {
  const std::string path = test::TempDir() + "/profile.txt";
  std::ofstream(path) << text;
  return path;
}

// The IoError's message, "" when the profile loads.
std::string LoadError(const std::string& text) {
  const std::string path = Write(text);
  try {
    LoadSensorProfile(path, test::SensorsDir());
  } catch (const IoError& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.rfind(path + ": line 6: ", 0), 0u) << message;
    return message;
  }
  return "";
}

TEST(IoSensorProfileLimits, TiltBeyond45DegreesIsRejected) {
  EXPECT_NE(LoadError(Profile("k_xz 1e30\n")).find("k_xz must be within -1..1"), std::string::npos);
  EXPECT_NE(LoadError(Profile("k_yz -1.01\n")).find("k_yz must be within -1..1"),
            std::string::npos);
  EXPECT_EQ(LoadError(Profile("k_xz -1\n")), "");
  EXPECT_EQ(LoadError(Profile("k_yz 0.0123\n")), "");
}

TEST(IoSensorProfileLimits, MaxRangeBeyond1000MetresIsRejected) {
  EXPECT_NE(LoadError(Profile("max_range 1e30\n")).find("max_range must be at most 1000 m"),
            std::string::npos);
  EXPECT_NE(LoadError(Profile("max_range 1000.001\n")).find("at most 1000 m"), std::string::npos);
  EXPECT_EQ(LoadError(Profile("max_range 1000\n")), "");
}

// The extreme profile and the extreme valid points: planar range at max_range, |z| at max_range,
// the largest tilt both ways, so |z_t| reaches 3 max_range.
TEST(IoSensorProfileLimits, ExtremeValidPointsPassEveryStage) {
  const SensorProfile sensor =
      LoadSensorProfile(Write(Profile("max_range 1000\nk_xz 1\nk_yz -1\n")), test::SensorsDir());
  const Params params = ParamsForSensor(sensor);
  const Tables tables = MakeTables(sensor, params);
  Cloud cloud;
  for (float sx : {-1.0f, 1.0f})
    for (float sy : {-1.0f, 1.0f})
      for (float z : {-1000.0f, -1.7f, 0.0f, 1000.0f})
        for (float r : {1.5f, 20.0f, 500.0f, 707.0f}) cloud.Push(sx * r, sy * r, z, 0.5f);
  Frame frame;
  RunReference(cloud, params, tables, frame);
  ASSERT_EQ(frame.label.size(), cloud.size());
  size_t valid = 0;
  for (size_t i = 0; i < cloud.size(); ++i) {
    EXPECT_LE(frame.label[i], 1u);
    valid += frame.why[i] != kWhyInvalid;
  }
  EXPECT_EQ(valid, cloud.size()) << "every point lies inside the profile's range";
}

}  // namespace
}  // namespace lpir
