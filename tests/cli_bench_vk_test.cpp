// lpir-gseg bench as a user runs it (few runs, on lavapipe under ctest, or on the machine's own
// device): the table names every stage, both backends and the device in every row; --json holds
// the fields the issue lists, with finite positive times, the scaling rows from 16 to 256 beams
// with doubling points, and the counted GPU cost of both shapes (a dispatch count that is the
// same on every frame, labels equal to the reference's).
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <regex>
#include <string>

#include "reference_cpu/pipeline.h"
#include "reference_cpu/wide.h"
#include "tests/test_util.h"

namespace lpir {
namespace {

// Runs `bench` with few repetitions (stdout only); "" without a Vulkan device.
std::string Bench(const std::string& extra) {
  if (!test::HasVulkanDevice()) return "";
  std::string out;
  const int code = test::RunCommand(
      test::CliPath() + " bench --runs 1 --scaling-runs 1 --frames 2 " + extra + " 2>/dev/null",
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
  if (json.empty()) GTEST_SKIP() << "no Vulkan device; install mesa-vulkan-drivers";
  EXPECT_NE(json.find("\"device\": \""), std::string::npos) << json;
  EXPECT_EQ(json.find("\"device\": \"none"), std::string::npos) << json;
  EXPECT_NE(json.find("\"end_to_end\": {\"cpu\": {\"median_ms\": "), std::string::npos) << json;
  // The CPU's name says which build of the kernels ran (reference_cpu/wide.h).
  EXPECT_EQ(json.find(", 1 thread, AVX2 kernels\"") != std::string::npos, WideKernels()) << json;
  EXPECT_NE(json.find("\"vulkan\": {\"median_ms\": "), std::string::npos) << json;
  for (const char* stage : kStageNames)
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

  // gpu_cost: both shapes, every key, counts positive, the dispatch count the same on every
  // frame (the frames have different point counts), the labels equal to the reference's.
  const size_t cost = json.find("\"gpu_cost\": {");
  ASSERT_NE(cost, std::string::npos) << json;
  const size_t cpu_shape = json.find("\"cpu\": {", cost);
  ASSERT_NE(json.find("\"gpu\": {", cost), std::string::npos) << json;
  ASSERT_NE(cpu_shape, std::string::npos) << json;
  for (const std::string& part : {json.substr(cost, cpu_shape - cost), json.substr(cpu_shape)}) {
    for (const char* key : {"dispatches_per_frame_min", "dispatches_per_frame_max",
                            "barriers_per_frame", "workgroups_per_frame", "upload_bytes_per_point",
                            "download_bytes_per_point", "device_mib"})
      EXPECT_GT(Number(part, key), 0.0) << key << " in " << part;
    EXPECT_EQ(Number(part, "dispatches_per_frame_min"), Number(part, "dispatches_per_frame_max"))
        << part;
    EXPECT_GE(Number(part, "upload_bytes_per_point"), 16.0) << part;  // xyzi floats
    EXPECT_NE(part.find("\"labels_equal_reference\": true"), std::string::npos) << part;
  }
}

TEST(CliBench, TableNamesTheDeviceInEveryRow) {
  const std::string table = Bench("");
  if (table.empty()) GTEST_SKIP() << "no Vulkan device; install mesa-vulkan-drivers";
  const std::string header = "| Vulkan device: ";
  const size_t at_name = table.find(header);
  ASSERT_NE(at_name, std::string::npos) << table;
  const std::string name =
      table.substr(at_name + header.size(), table.find('\n', at_name) - at_name - header.size());
  ASSERT_FALSE(name.empty()) << table;
  size_t rows = 0;
  for (size_t at = table.find(name); at != std::string::npos; at = table.find(name, at + 1)) ++rows;
  // 13 stage rows, throughput, memory, 2 gpu cost rows, 5 scaling rows, and the header line.
  EXPECT_GE(rows, 23u) << table;
  for (const char* what : {"end to end", "throughput (frames/s", "frames in flight 1:",
                           "peak host RSS", "device memory allocated", "os1-256", "vk/cpu",
                           "gpu cost, shape gpu, per frame: ", "gpu cost, shape cpu, per frame: "})
    EXPECT_NE(table.find(what), std::string::npos) << what << " in\n" << table;
}

}  // namespace
}  // namespace lpir
