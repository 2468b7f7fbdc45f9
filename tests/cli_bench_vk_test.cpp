// lpir-gseg bench as a user runs it (few runs, on lavapipe under ctest): the table names every
// stage, both backends and the device in every row; --json holds the fields the issue lists, with
// finite positive times and the scaling rows from 16 to 256 beams with doubling points.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <regex>
#include <string>

#include "tests/test_util.h"

namespace lpir {
namespace {

// Runs `bench` with few repetitions (stdout only); skips without lavapipe.
std::string Bench(const std::string& extra) {
  if (!test::HasLavapipe()) return "";
  std::string out;
  const int code = test::RunCommand(test::CliPath() + " bench --runs 1 --scaling-runs 1 --frames 2 " +
                                        extra + " 2>/dev/null",
                                    &out);
  EXPECT_EQ(code, 0) << out;
  return out;
}

double Number(const std::string& json, const std::string& key) {
  const std::regex re("\"" + key + "\": (-?[0-9.]+)");
  std::smatch m;
  if (!std::regex_search(json, m, re)) {
    ADD_FAILURE() << "no \"" << key << "\" in " << json;
    return -1;
  }
  return std::stod(m[1]);
}

TEST(CliBench, JsonHoldsEveryField) {
  const std::string json = Bench("--json");
  if (json.empty()) GTEST_SKIP() << "no lavapipe ICD; install mesa-vulkan-drivers";
  EXPECT_NE(json.find("\"device\": \"llvmpipe"), std::string::npos) << json;
  EXPECT_NE(json.find("\"end_to_end\": {\"cpu\": {\"median_ms\": "), std::string::npos) << json;
  EXPECT_NE(json.find("\"vulkan\": {\"median_ms\": "), std::string::npos) << json;
  for (const char* stage : {"prepare", "project", "grid_reduce", "coarse_segment", "feature_maps",
                            "classify_pixels", "fuse", "grow", "back_project"})
    EXPECT_NE(json.find(std::string("{\"name\": \"") + stage + "\", \"cpu_ms\": "),
              std::string::npos)
        << stage;
  for (const char* key : {"median_ms", "cpu_ms", "vulkan_ms", "\"1", "\"2", "\"4", "peak_host_mib",
                          "device_mib", "points"}) {
    const std::string k = key[0] == '"' ? std::string(key + 1) : std::string(key);
    EXPECT_GT(Number(json, k), 0.0) << k;
  }
  // The scaling rows: 16 to 256 beams, each row about twice the points of the one before.
  const std::regex row("\"beams\": ([0-9]+), \"width\": [0-9]+, \"points\": ([0-9]+)");
  std::vector<double> beams, points;
  for (std::sregex_iterator it(json.begin(), json.end(), row), end; it != end; ++it)
    beams.push_back(std::stod((*it)[1])), points.push_back(std::stod((*it)[2]));
  ASSERT_EQ(beams.size(), 5u) << json;
  EXPECT_EQ(beams.front(), 16);
  EXPECT_EQ(beams.back(), 256);
  for (size_t k = 2; k < points.size(); ++k) EXPECT_NEAR(points[k] / points[k - 1], 2.0, 0.2);
}

TEST(CliBench, TableNamesTheDeviceInEveryRow) {
  const std::string table = Bench("");
  if (table.empty()) GTEST_SKIP() << "no lavapipe ICD; install mesa-vulkan-drivers";
  size_t rows = 0;
  for (size_t at = table.find("llvmpipe"); at != std::string::npos;
       at = table.find("llvmpipe", at + 1))
    ++rows;
  // 13 stage rows, throughput, memory, 5 scaling rows, and the header line.
  EXPECT_GE(rows, 21u) << table;
  for (const char* what : {"end to end", "throughput (frames/s", "frames in flight 1:",
                           "peak host RSS", "device memory allocated", "os1-256", "vk/cpu"})
    EXPECT_NE(table.find(what), std::string::npos) << what << " in\n" << table;
}

}  // namespace
}  // namespace lpir
