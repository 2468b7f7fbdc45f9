// lpir-gseg calibrate, run as a user would: `simulate --pitch --roll` scans read back as their
// tilt, --write-profile gives a profile that `segment` reads, several scans pool, and every
// refusal is a message saying why and what to do, with exit code 3 and no profile written.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <ostream>
#include <random>
#include <string>

#include "host/io/kitti_bin.h"
#include "host/io/label_file.h"
#include "host/io/sensor_profile.h"
#include "tests/test_util.h"

namespace fs = std::filesystem;

namespace lpir {
namespace {

constexpr double kPi = 3.14159265358979323846;

int Cli(const std::string& args, std::string* out) {
  return test::RunCommand(test::CliPath() + " " + args, out);
}

// The number after "key": in a JSON object; NaN when absent.
double JsonValue(const std::string& json, const std::string& key) {
  const size_t at = json.find("\"" + key + "\": ");
  if (at == std::string::npos) return std::nan("");
  return std::strtod(json.c_str() + at + key.size() + 4, nullptr);
}

std::string Simulate(const std::string& dir, const std::string& name, const std::string& scene,
                     double pitch, double roll, int seed = 1) {
  const std::string bin = dir + "/" + name + ".bin";
  std::string log;
  EXPECT_EQ(Cli("simulate --sensor hdl64e --seed " + std::to_string(seed) + " --scene " + scene +
                    " --pitch " + std::to_string(pitch) + " --roll " + std::to_string(roll) +
                    " --out " + bin + " --labels " + dir + "/" + name + ".label",
                &log),
            0)
      << log;
  return bin;
}

// Points every 25 cm from r0 to r1 m in the 6 columns around front, rear, left and right.
template <class Height>
std::string WriteBands(const std::string& path, const Height& height, double r0 = 3.5,
                       double r1 = 30.0) {
  Cloud c;
  for (double az0 : {0.0, kPi, kPi / 2, -kPi / 2})
    for (int col = -3; col < 3; ++col)
      for (double r = r0; r < r1; r += 0.25) {
        const double az = az0 + (col + 0.5) * 2 * kPi / 2048;
        const double x = r * std::cos(az), y = r * std::sin(az);
        c.Push(float(x), float(y), float(height(x, y)), 0.3f);
      }
  WriteKittiBin(path, c);
  return path;
}

TEST(CliCalibrate, SimulatedTiltReadsBackAsItself) {
  const std::string dir = test::TempDir();
  for (auto [pitch, roll] : {std::pair{2.5, -1.5}, {-4.0, 3.0}}) {
    const std::string bin = Simulate(dir, "flat", "flat", pitch, roll);
    std::string out;
    ASSERT_EQ(Cli("calibrate " + bin + " --sensor hdl64e --json", &out), 0) << out;
    EXPECT_NEAR(JsonValue(out, "pitch_deg"), pitch, 0.05) << out;
    EXPECT_NEAR(JsonValue(out, "roll_deg"), roll, 0.05) << out;
    EXPECT_NEAR(JsonValue(out, "k_xz"), std::tan(pitch * kPi / 180), 1e-3) << out;
    EXPECT_NEAR(JsonValue(out, "k_yz"), std::tan(roll * kPi / 180), 1e-3) << out;
    EXPECT_NEAR(JsonValue(out, "b_x"), 1.73, 0.01) << out;
    EXPECT_NEAR(JsonValue(out, "b_y"), 1.73, 0.01) << out;
    EXPECT_NE(out.find("\"accepted\": true"), std::string::npos) << out;
  }
}

TEST(CliCalibrate, WrittenProfileIsWhatSegmentReads) {
  const std::string dir = test::TempDir();
  const std::string flat = Simulate(dir, "flat", "flat", 3.0, 1.0);
  const std::string profile = dir + "/tilted.txt";
  std::string log;
  ASSERT_EQ(Cli("calibrate " + flat + " --sensor hdl64e --write-profile " + profile, &log), 0)
      << log;
  ASSERT_NE(log.find("accepted: pitch "), std::string::npos) << log;
  EXPECT_NEAR(std::strtod(log.c_str() + log.find("accepted: pitch ") + 16, nullptr), 3.0, 0.05);
  const SensorProfile base = LoadSensorProfile("hdl64e", test::SensorsDir());
  const SensorProfile p = LoadSensorProfile(profile, test::SensorsDir());
  EXPECT_NEAR(p.k_xz, std::tan(3.0 * kPi / 180), 1e-3);
  EXPECT_NEAR(p.k_yz, std::tan(1.0 * kPi / 180), 1e-3);
  EXPECT_NEAR(p.b_x, 1.73, 0.01);
  EXPECT_NEAR(p.b_y, 1.73, 0.01);
  // Everything else is the profile it came from.
  EXPECT_EQ(p.name, base.name);
  EXPECT_EQ(p.elevation_deg, base.elevation_deg);
  EXPECT_EQ(p.beam_origin_z, base.beam_origin_z);
  EXPECT_EQ(p.sensor_height, base.sensor_height);
  EXPECT_EQ(p.overrides, base.overrides);

  // A street through the same mount, segmented with the written profile.
  const std::string street = Simulate(dir, "street", "urban", 3.0, 1.0, 2);
  ASSERT_EQ(
      Cli("segment " + street + " --sensor " + profile + " --backend cpu --out " + dir + "/pred",
          &log),
      0)
      << log;
  ASSERT_EQ(Cli("evaluate --pred " + dir + "/pred --gt " + dir +
                    "/street.label --protocol dg "
                    "--json",
                &log),
            0)
      << log;
  const double f1 = JsonValue(log.substr(log.find("\"total\"")), "f1");
  EXPECT_GT(f1, 0.9) << log;
}

TEST(CliCalibrate, SeveralScansArePooled) {
  const std::string dir = test::TempDir();
  const std::string a = Simulate(dir, "a", "flat", -2.0, 0.5, 1);
  const std::string b = Simulate(dir, "b", "flat-objects", -2.0, 0.5, 2);
  std::string one, two;
  ASSERT_EQ(Cli("calibrate " + a + " --sensor hdl64e --json", &one), 0) << one;
  ASSERT_EQ(Cli("calibrate " + a + " " + b + " --sensor hdl64e --json", &two), 0) << two;
  EXPECT_EQ(JsonValue(two, "scans"), 2);
  EXPECT_GT(JsonValue(two, "front"), JsonValue(one, "front"));
  EXPECT_NEAR(JsonValue(two, "pitch_deg"), -2.0, 0.05) << two;
  EXPECT_NEAR(JsonValue(two, "roll_deg"), 0.5, 0.05) << two;
}

struct Refusal {
  const char* name;
  double (*height)(double x, double y);
  double r0;            // the scan's ground starts this far out (m)
  const char* refusal;  // the JSON refusal field
  const char* says;     // the message must hold this
  const char* advice;   // ... and this (what to do)
};

void PrintTo(const Refusal& r, std::ostream* os) { *os << r.name; }

double Flat(double, double) { return -1.73; }
double Bumpy(double x, double y) {  // +-30 cm of pseudo-random heights
  const double h = std::sin(12.9898 * x + 78.233 * y) * 43758.5453;
  return -1.73 + (h - std::floor(h) - 0.5) * 0.6;
}
double Step(double x, double y) { return std::abs(y) > std::abs(x) ? -1.70 : -1.73; }

class CliCalibrateRefuses : public ::testing::TestWithParam<Refusal> {};

TEST_P(CliCalibrateRefuses, SaysWhyAndWhatToDoAndExitsNonZero) {
  const Refusal& r = GetParam();
  const std::string dir = test::TempDir();
  const std::string scan = WriteBands(dir + "/scan.bin", r.height, r.r0, r.r0 + 26.5);
  const std::string profile = dir + "/out.txt";
  std::string log;
  EXPECT_EQ(Cli("calibrate " + scan + " --sensor hdl64e --write-profile " + profile, &log), 3)
      << log;
  EXPECT_NE(log.find("lpir-gseg calibrate: refused: "), std::string::npos) << log;
  EXPECT_NE(log.find(r.says), std::string::npos) << log;
  EXPECT_NE(log.find(r.advice), std::string::npos) << log;
  EXPECT_NE(log.find(profile + " not written"), std::string::npos) << log;
  EXPECT_FALSE(fs::exists(profile));
  ASSERT_EQ(Cli("calibrate " + scan + " --sensor hdl64e --json 2>/dev/null", &log), 3) << log;
  EXPECT_NE(log.find(std::string("\"refusal\": \"") + r.refusal + "\""), std::string::npos) << log;
  EXPECT_NE(log.find("\"accepted\": false"), std::string::npos) << log;
}

INSTANTIATE_TEST_SUITE_P(
    Cases, CliCalibrateRefuses,
    ::testing::Values(
        // Ground only beyond the 30 m distance gate.
        Refusal{"too_few", Flat, 31.0, "too_few_points", "too few points survive the gates",
                "parking lot"},
        Refusal{"not_flat", Bumpy, 3.5, "not_flat", "not flat enough", "flat, open surface"},
        Refusal{"heights", Step, 3.5, "heights_disagree", "differ by 3.00 cm",
                "Recalibrate on a flatter surface"}),
    [](const ::testing::TestParamInfo<Refusal>& info) { return info.param.name; });

TEST(CliCalibrate, ALargerHeightLimitAcceptsTheStep) {
  const std::string dir = test::TempDir();
  const std::string scan = WriteBands(dir + "/scan.bin", Step);
  std::string log;
  EXPECT_EQ(Cli("calibrate " + scan + " --sensor hdl64e --max-b-diff 0.05", &log), 0) << log;
  const std::string flat = WriteBands(dir + "/flat.bin", Flat);
  EXPECT_EQ(Cli("calibrate " + flat + " --sensor hdl64e", &log), 0) << log;
  ASSERT_NE(log.find("accepted: pitch "), std::string::npos) << log;
  EXPECT_NEAR(std::strtod(log.c_str() + log.find("accepted: pitch ") + 16, nullptr), 0.0, 1e-3);
}

TEST(CliCalibrate, BadInvocationsFailWithAMessage) {
  const std::string dir = test::TempDir();
  std::string log;
  EXPECT_EQ(Cli("calibrate --sensor hdl64e", &log), 2) << log;  // usage
  EXPECT_NE(log.find("no scan given"), std::string::npos) << log;
  EXPECT_EQ(Cli("calibrate " + dir + "/missing.bin --sensor hdl64e", &log), 4)
      << log;  // cannot run
  EXPECT_NE(log.find(dir + "/missing.bin"), std::string::npos) << log;
  const std::string flat = WriteBands(dir + "/flat.bin", Flat);
  EXPECT_EQ(Cli("calibrate " + flat, &log), 2) << log;
  EXPECT_NE(log.find("--sensor is required"), std::string::npos) << log;
  EXPECT_EQ(Cli("calibrate " + flat + " --sensor hdl64e --max-b-diff -1", &log), 2) << log;
  EXPECT_NE(log.find("--max-b-diff"), std::string::npos) << log;
  EXPECT_EQ(Cli("calibrate --help", &log), 0) << log;
  EXPECT_NE(log.find("z = k_xz x + k_yz y - b"), std::string::npos) << log;
}

}  // namespace
}  // namespace lpir
