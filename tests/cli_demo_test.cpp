// lpir-gseg demo: runs with no data at all, reports its scores and writes its pictures, and
// states its timing as set-up and first frame apart from the steady state.
#include <gtest/gtest.h>

#include <filesystem>
#include <regex>
#include <string>

#include "tests/test_util.h"

namespace lpir {
namespace {

TEST(CliDemo, SegmentsTheBuiltInSceneAccuratelyAndLeavesCarsAlone) {
  const std::string out = test::TempDir();
  std::string log;
  ASSERT_EQ(test::RunCommand(test::CliPath() + " demo --out " + out, &log), 0) << log;
  std::smatch m;
  ASSERT_TRUE(std::regex_search(log, m, std::regex(R"(F1 ([0-9.]+) %)"))) << log;
  EXPECT_GE(std::stod(m[1]), 97.0) << log;
  ASSERT_TRUE(
      std::regex_search(log, m, std::regex(R"(car points labelled ground: (\d+) of (\d+))")))
      << log;
  EXPECT_EQ(m[1], "0") << log;
  EXPECT_GT(std::stoi(m[2]), 100) << log;
  EXPECT_TRUE(std::filesystem::exists(out + "/images/demo_scan_bev.png"));
  EXPECT_TRUE(std::filesystem::exists(out + "/demo_scan.label"));
}

// The timing lines: set-up and the first frame on one line, the steady state (--runs frames after
// the warm-up) on another, its frames per second those of its median frame.
TEST(CliDemo, StatesSteadyStateTimingApartFromSetUp) {
  const test::ScopedDir out;
  std::string log;
  ASSERT_EQ(
      test::RunCommand(test::CliPath() + " demo --backend cpu --runs 7 --out " + out.path, &log), 0)
      << log;
  std::smatch m;
  ASSERT_TRUE(std::regex_search(
      log, m,
      std::regex(R"(set-up on the CPU reference: ([0-9.]+) ms \(device, pipelines, buffers\), )"
                 R"(then the first frame ([0-9.]+) ms\n)")))
      << log;
  EXPECT_GE(std::stod(m[1]), 0.0) << log;
  EXPECT_GT(std::stod(m[2]), 0.0) << log;
  ASSERT_TRUE(std::regex_search(
      log, m,
      std::regex(R"(steady state over (\d+) frames after (\d+) warm-up frames: median ([0-9.]+) )"
                 R"(ms a frame \(wall time, upload to download\), ([0-9.]+) frames/s)")))
      << log;
  EXPECT_EQ(m[1], "7") << log;
  EXPECT_GE(std::stoi(m[2]), 1) << log;
  const double median_ms = std::stod(m[3]), fps = std::stod(m[4]);
  ASSERT_GT(median_ms, 0.0) << log;
  EXPECT_NEAR(fps, 1000.0 / median_ms, 0.05 + 0.01 * fps) << log;  // both printed rounded
  // The old single-frame figure is gone: no timing but these two lines.
  EXPECT_EQ(log.find("segmented in "), std::string::npos) << log;
  EXPECT_TRUE(std::filesystem::exists(out.path + "/demo_scan.label"));
}

}  // namespace
}  // namespace lpir
