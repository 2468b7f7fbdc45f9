// lpir-gseg segment on both backends, as a user runs it: `--backend vulkan` and `--backend cpu`
// write identical .label files for every real scan in ../shared/data (KITTI HDL-64E, nuScenes and
// PLY HDL-32E, Ouster OS1-64, VLP-32C), with the validation layer on and silent; `--timings`
// prints every stage; without any Vulkan driver it falls back to the reference with one notice;
// auto takes a GPU, and where lavapipe is the only device the reference, saying so.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

#include "reference_cpu/pipeline.h"
#include "tests/test_util.h"

namespace fs = std::filesystem;

namespace lpir {
namespace {

size_t Count(const std::string& text, const std::string& what) {
  size_t n = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

// Segments `files` with `sensor` on each backend and compares every .label file byte for byte.
void ExpectSameLabelsOnBothBackends(const std::vector<std::string>& files,
                                    const std::string& sensor) {
  LPIR_REQUIRE_VULKAN();
  std::string inputs;
  std::vector<std::string> stems;
  for (const std::string& f : files) {
    if (test::DataFile(f).empty()) continue;
    inputs += " '" + test::DataFile(f) + "'";
    std::string stem = fs::path(f).stem().string();
    stems.push_back(stem);
  }
  if (stems.empty())
    GTEST_SKIP() << "none of the scans is under " << test::EnvOr("LPIR_DATA_DIR", LPIR_DATA_DIR);
  const std::string out = test::TempDir();
  std::string log;
  ASSERT_EQ(
      test::RunCommand("LPIR_VK_VALIDATION=1 " + test::CliPath() + " segment" + inputs +
                           " --sensor " + sensor + " --backend vulkan --out " + out + "/vulkan",
                       &log),
      0)
      << log;
  EXPECT_NE(log.find("on Vulkan on "), std::string::npos) << log;
  EXPECT_EQ(log.find("[vulkan"), std::string::npos) << "validation messages:\n" << log;
  ASSERT_EQ(test::RunCommand(test::CliPath() + " segment" + inputs + " --sensor " + sensor +
                                 " --backend cpu --out " + out + "/cpu",
                             &log),
            0)
      << log;
  EXPECT_NE(log.find("on the CPU reference"), std::string::npos) << log;
  for (const std::string& stem : stems) {
    const std::string vulkan = test::ReadFileBytes(out + "/vulkan/" + stem + ".label");
    const std::string cpu = test::ReadFileBytes(out + "/cpu/" + stem + ".label");
    EXPECT_GT(cpu.size(), 0u) << stem;
    EXPECT_TRUE(vulkan == cpu) << stem << ": the .label files differ (" << vulkan.size() << " and "
                               << cpu.size() << " bytes)";
    std::printf("[cli_backend] %s (%s): %zu labels identical on vulkan and cpu\n", stem.c_str(),
                sensor.c_str(), cpu.size() / 4);
  }
}

TEST(CliBackend, KittiHdl64eScansSameOnBothBackends) {
  ExpectSameLabelsOnBothBackends(
      {"kitti/07/velodyne/000964.bin", "kitti/unknown/velodyne/000056.bin",
       "kitti/00/velodyne/000000.bin", "kitti/00/velodyne/000001.bin",
       "kitti/00/velodyne/000002.bin", "kitti/00/velodyne/000003.bin",
       "kitti/00/velodyne/000004.bin", "kitti/00/velodyne/000005.bin"},
      "hdl64e");
}

TEST(CliBackend, Hdl32eScansSameOnBothBackends) {
  ExpectSameLabelsOnBothBackends(
      {"nuscenes/n015-2018-07-24-11-22-45+0800__LIDAR_TOP__1532402927647951.pcd.bin",
       "hdl32e/source.ply", "hdl32e/target.ply"},
      "hdl32e");
}

TEST(CliBackend, OusterOs1ScansSameOnBothBackends) {
  ExpectSameLabelsOnBothBackends(
      {"rellis3d/os1/000104.bin", "rellis3d/os1/frame000104-1581624663_170.ply"}, "os1-64");
}

TEST(CliBackend, Vlp32cScanSameOnBothBackends) {
  ExpectSameLabelsOnBothBackends({"rellis3d/vlp32c/000104.bin"}, "vlp32c");
}

TEST(CliBackend, TimingsNameEveryStage) {
  LPIR_REQUIRE_VULKAN();
  LPIR_REQUIRE_DATA("kitti/07/velodyne/000964.bin");
  std::string log;
  ASSERT_EQ(test::RunCommand(
                test::CliPath() + " segment " + test::DataFile("kitti/07/velodyne/000964.bin") +
                    " --sensor hdl64e --backend vulkan --timings --out " + test::TempDir(),
                &log),
            0)
      << log;
  std::vector<std::string> columns = {"upload", "download", "total"};
  columns.insert(columns.end(), std::begin(kStageNames), std::end(kStageNames));
  for (const std::string& column : columns)
    EXPECT_EQ(Count(log, " " + column + " "), 2u) << column << " in\n" << log;
  EXPECT_NE(log.find("median over 1 frame (GPU timestamps, ms)"), std::string::npos) << log;
}

// No Vulkan driver at all: auto falls back to the reference with one notice and the same labels;
// --backend vulkan is an error that says why.
TEST(CliBackend, NoVulkanDriverFallsBackToTheReference) {
  LPIR_REQUIRE_DATA("kitti/07/velodyne/000964.bin");
  const std::string scan = test::DataFile("kitti/07/velodyne/000964.bin");
  const std::string out = test::TempDir();
  std::string log;
  ASSERT_EQ(test::RunCommand("VK_ICD_FILENAMES=/nonexistent.json " + test::CliPath() + " segment " +
                                 scan + " --sensor hdl64e --out " + out + "/auto",
                             &log),
            0)
      << log;
  EXPECT_EQ(Count(log, "note: "), 1u) << log;
  EXPECT_NE(log.find("lpir-gseg segment: note: CPU reference, no Vulkan device: no Vulkan driver "
                     "found: vkCreateInstance: VK_ERROR_INCOMPATIBLE_DRIVER"),
            std::string::npos)
      << log;
  EXPECT_NE(log.find("on the CPU reference"), std::string::npos) << log;
  ASSERT_EQ(test::RunCommand(test::CliPath() + " segment " + scan +
                                 " --sensor hdl64e --backend cpu --out " + out + "/cpu",
                             &log),
            0)
      << log;
  const std::string fallback = test::ReadFileBytes(out + "/auto/000964.label");
  EXPECT_EQ(fallback.size(), 4u * 120485);
  EXPECT_TRUE(fallback == test::ReadFileBytes(out + "/cpu/000964.label"));

  EXPECT_EQ(
      test::RunCommand("VK_ICD_FILENAMES=/nonexistent.json " + test::CliPath() + " segment " +
                           scan + " --sensor hdl64e --backend vulkan --out " + out + "/vulkan",
                       &log),
      4);  // cannot run
  EXPECT_NE(log.find("the Vulkan backend could not be set up"), std::string::npos) << log;
  EXPECT_NE(log.find("VK_ICD_FILENAMES=/nonexistent.json"), std::string::npos) << log;
  EXPECT_FALSE(fs::exists(out + "/vulkan/000964.label"));
}

// Auto takes a GPU, never a CPU driver: where lavapipe is the only device (this project's
// machines), auto runs the CPU reference with one note that names the driver and --backend
// vulkan; --backend vulkan and --device 0 run on lavapipe without a note; all three write the
// same labels. On a machine with a GPU, auto runs on it.
TEST(CliBackend, AutoTakesAGpuElseTheReferenceWithANote) {
  LPIR_REQUIRE_VULKAN();
  const std::string dir = test::TempDir();
  std::string log;
  ASSERT_EQ(test::RunCommand(test::CliPath() + " simulate --sensor vlp16 --seed 1 --out " + dir +
                                 "/s.bin --labels " + dir + "/s.label",
                             &log),
            0)
      << log;
  ASSERT_EQ(test::RunCommand(test::CliPath() + " devices", &log), 0) << log;
  const bool gpu =
      log.find("(segment --backend auto without --device): the CPU reference") == std::string::npos;
  const std::string segment = test::CliPath() + " segment " + dir + "/s.bin --sensor vlp16";
  ASSERT_EQ(test::RunCommand(segment + " --out " + dir + "/auto", &log), 0) << log;
  if (gpu) {
    EXPECT_NE(log.find("on Vulkan on "), std::string::npos) << log;
    EXPECT_EQ(log.find("on Vulkan on llvmpipe"), std::string::npos) << log;
    EXPECT_EQ(Count(log, "note: "), 0u) << log;
  } else {
    EXPECT_EQ(Count(log, "note: "), 1u) << log;
    EXPECT_NE(log.find("lpir-gseg segment: note: CPU reference: the only "), std::string::npos)
        << log;
    EXPECT_NE(log.find(" a CPU driver (llvmpipe); --backend vulkan uses it\n"), std::string::npos)
        << log;
    EXPECT_NE(log.find("segmented 1 of 1 file on the CPU reference"), std::string::npos) << log;
  }
  // The note and the summary each fit a 120-column terminal, the summary with a 35-character
  // folder (the folder's name is the user's).
  std::istringstream lines(log);
  for (std::string line; std::getline(lines, line);) {
    const size_t folder = line.find("; labels in ");
    const size_t width = folder == std::string::npos ? line.size() : folder + 12 + 35;
    EXPECT_LE(width, 120u) << line;
  }
  const std::string labels = test::ReadFileBytes(dir + "/auto/s.label");
  EXPECT_GT(labels.size(), 0u);
  const struct {
    const char* option;
    const char* out;
  } asked[] = {{" --backend vulkan", "/vulkan"}, {" --device 0", "/device"}};
  for (const auto& a : asked) {
    ASSERT_EQ(test::RunCommand(segment + a.option + " --out " + dir + a.out, &log), 0)
        << a.option << "\n"
        << log;
    EXPECT_EQ(Count(log, "note: "), 0u) << a.option << "\n" << log;
    EXPECT_NE(log.find("on Vulkan on "), std::string::npos) << a.option << "\n" << log;
    if (!gpu) {
      EXPECT_NE(log.find("on Vulkan on llvmpipe"), std::string::npos) << a.option;
    }
    EXPECT_TRUE(test::ReadFileBytes(dir + a.out + "/s.label") == labels) << a.option;
  }
  ASSERT_EQ(test::RunCommand(segment + " --backend cpu --out " + dir + "/cpu", &log), 0) << log;
  EXPECT_EQ(Count(log, "note: "), 0u) << log;
}

TEST(CliBackend, BadBackendOrDeviceIsAnError) {
  std::string log;
  EXPECT_EQ(test::RunCommand(test::CliPath() + " segment x.bin --sensor hdl64e --backend cuda " +
                                 "--out " + test::TempDir(),
                             &log),
            2);  // usage
  EXPECT_NE(log.find("unknown backend 'cuda' (auto, cpu or vulkan)"), std::string::npos) << log;
  LPIR_REQUIRE_VULKAN();  // without a device, --device fails before any device is named
  EXPECT_EQ(test::RunCommand(test::CliPath() + " segment x.bin --sensor hdl64e --device nosuch " +
                                 "--out " + test::TempDir(),
                             &log),
            4);  // cannot run: no such device
  EXPECT_NE(log.find("nosuch"), std::string::npos) << log;
}

TEST(CliBackend, DevicesListsLavapipe) {
  LPIR_REQUIRE_VULKAN();
  std::string log;
  ASSERT_EQ(test::RunCommand(test::CliPath() + " devices", &log), 0) << log;
  EXPECT_NE(log.find("#0 "), std::string::npos) << log;
  EXPECT_NE(log.find("default (segment --backend auto without --device): "), std::string::npos)
      << log;
  EXPECT_NE(log.find("segment --backend vulkan without --device: "), std::string::npos) << log;
  EXPECT_EQ(
      test::RunCommand("VK_ICD_FILENAMES=/nonexistent.json " + test::CliPath() + " devices", &log),
      4);  // cannot run
  EXPECT_NE(log.find("no Vulkan device"), std::string::npos) << log;
}

}  // namespace
}  // namespace lpir
