// lpir-gseg segment over folders holding bad files among good ones, on `--backend vulkan` (with
// the validation layer on, LPIR_VK_VALIDATION=1, and silent) and `--backend cpu`: every good file
// is labelled, with the very labels it gets when segmented alone (frames in flight must not
// shift or drop a frame around a failure), the bad ones are named and get no output, the summary
// counts them and the exit code is 1. The bad files sit in the middle, first and last.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <string>
#include <vector>

#include "apps/sim/scene.h"
#include "host/io/kitti_bin.h"
#include "host/io/sensor_profile.h"
#include "tests/test_util.h"

namespace fs = std::filesystem;

namespace lpir {
namespace {

void WriteBytes(const std::string& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary) << bytes;
}

// A simulated VLP-16 street; a different one per seed, so a label file written under the wrong
// name would not match.
void WriteScan(const std::string& path, uint32_t seed) {
  SimOptions options;
  options.seed = seed;
  WriteKittiBin(path, Simulate(LoadSensorProfile("vlp16", test::SensorsDir()), options).cloud);
}

struct Run {
  int code = 0;
  std::string log;
};

Run Segment(const std::string& inputs, const std::string& backend, const std::string& out,
            const std::string& extra = "") {
  Run run;
  const std::string env = backend == "vulkan" ? "LPIR_VK_VALIDATION=1 " : "";
  run.code =
      test::RunCommand(env + test::CliPath() + " segment " + inputs + " --sensor vlp16 --backend " +
                           backend + " --out " + out + " " + extra,
                       &run.log);
  return run;
}

// Segments `dir`/in, which holds the good files `good` (stems) and the bad files `bad` (names),
// on `backend`; checks each good file's labels against those of the folder of good files alone
// (`reference`), and the report.
void ExpectGoodLabelledBadNamed(const std::string& dir, const std::string& backend,
                                const std::vector<std::string>& good,
                                const std::vector<std::string>& bad, const std::string& reference,
                                const std::string& extra = "") {
  const std::string out = dir + "/out_" + backend;
  const Run run = Segment(dir + "/in", backend, out, extra);
  EXPECT_EQ(run.code, 1) << run.log;
  if (backend == "vulkan") {
    EXPECT_NE(run.log.find("on Vulkan on "), std::string::npos) << run.log;
    EXPECT_EQ(run.log.find("[vulkan"), std::string::npos) << "validation messages:\n" << run.log;
  }
  for (const std::string& stem : good) {
    const std::string labels = test::ReadFileBytes(out + "/" + stem + ".label");
    EXPECT_GT(labels.size(), 1000u) << backend << ": " << stem;
    EXPECT_TRUE(labels == test::ReadFileBytes(reference + "/" + stem + ".label"))
        << backend << ": " << stem << ".label differs from the file segmented without bad ones";
  }
  for (const std::string& name : bad) {
    EXPECT_FALSE(fs::exists(out + "/" + fs::path(name).stem().string() + ".label"))
        << backend << ": " << name;
    EXPECT_NE(run.log.find(dir + "/in/" + name), std::string::npos)
        << backend << ": the report does not name " << name << ":\n"
        << run.log;
  }
  const std::string summary = std::to_string(bad.size()) + " of " +
                              std::to_string(good.size() + bad.size()) + " files failed";
  EXPECT_NE(run.log.find(summary), std::string::npos) << backend << ":\n" << run.log;
}

// The good files alone, on the CPU reference: the labels every backend must reproduce.
std::string SegmentGoodAlone(const std::string& dir, const std::vector<std::string>& good) {
  fs::create_directories(dir + "/good");
  for (const std::string& stem : good)
    fs::copy_file(dir + "/in/" + stem + ".bin", dir + "/good/" + stem + ".bin");
  const Run run = Segment(dir + "/good", "cpu", dir + "/reference");
  EXPECT_EQ(run.code, 0) << run.log;
  return dir + "/reference";
}

TEST(CliHostileVk, ATruncatedFileInTheMiddleOfAFolder) {
  LPIR_REQUIRE_VULKAN();
  const std::string dir = test::TempDir();
  fs::create_directories(dir + "/in");
  const std::vector<std::string> good = {"a", "b", "d", "e"};
  for (size_t k = 0; k < good.size(); ++k) WriteScan(dir + "/in/" + good[k] + ".bin", 11 + k);
  WriteBytes(dir + "/in/c.bin", std::string(16 * 1000 + 7, '\1'));  // truncated mid-point
  const std::string reference = SegmentGoodAlone(dir, good);
  for (const char* backend : {"vulkan", "cpu"})
    ExpectGoodLabelledBadNamed(dir, backend, good, {"c.bin"}, reference);
}

// Every kind of failure a frame can meet, first, in the middle and last: unreadable files, a
// cloud over --max-points (read, then refused by the segmenter), a PCD whose header promises
// more points than it holds.
TEST(CliHostileVk, BadFilesFirstInTheMiddleAndLast) {
  LPIR_REQUIRE_VULKAN();
  const std::string dir = test::TempDir();
  fs::create_directories(dir + "/in");
  const std::vector<std::string> good = {"b", "c", "e", "f"};
  for (size_t k = 0; k < good.size(); ++k) WriteScan(dir + "/in/" + good[k] + ".bin", 21 + k);
  WriteBytes(dir + "/in/a.bin", "");  // empty
  Cloud big;
  for (int i = 0; i < 40000; ++i) big.Push(5.0f + float(i % 90), float(i % 7), -1.7f, 0.3f);
  WriteKittiBin(dir + "/in/d.bin", big);  // over --max-points 35000
  WriteBytes(dir + "/in/g.pcd",
             "VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nWIDTH 3\nDATA ascii\n1 2 3\n");
  const std::string reference = SegmentGoodAlone(dir, good);
  for (const char* backend : {"vulkan", "cpu"})
    ExpectGoodLabelledBadNamed(dir, backend, good, {"a.bin", "d.bin", "g.pcd"}, reference,
                               "--max-points 35000");
}

}  // namespace
}  // namespace lpir
