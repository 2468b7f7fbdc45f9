// lpir-gseg demo: runs with no data at all, reports its scores and writes its pictures.
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

}  // namespace
}  // namespace lpir
