// lpir-gseg segment, run as a user would: real scans in, .label files out, and every bad input a
// clear message naming the file with a non-zero exit, never a crash.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "host/io/kitti_bin.h"
#include "host/io/label_file.h"
#include "tests/test_util.h"

namespace fs = std::filesystem;

namespace lpir {
namespace {

std::string Cli() { return test::CliPath(); }

// Runs the CLI; returns the exit code, output in *out.
int Segment(const std::string& args, std::string* out) {
  return test::RunCommand(Cli() + " segment " + args, out);
}

void WriteBytes(const std::string& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary) << bytes;
}

Cloud SmallScan() {
  Cloud c;
  for (int k = 0; k < 400; ++k) {
    const float a = float(k) * 0.0157f;
    c.Push(8.0f * std::cos(a), 8.0f * std::sin(a), -1.73f, 0.3f);  // a ring of road
    c.Push(6.0f * std::cos(a), 6.0f * std::sin(a), -1.73f, 0.3f);
  }
  return c;
}

TEST(CliSegment, LabelsARealKittiScan) {
  LPIR_REQUIRE_DATA("kitti/07/velodyne/000964.bin");
  const std::string out = test::TempDir();
  std::string log;
  ASSERT_EQ(Segment(test::DataFile("kitti/07/velodyne/000964.bin") +
                        " --sensor hdl64e --verbose --out " + out,
                    &log),
            0)
      << log;
  const std::vector<uint32_t> labels = ReadLabelFile(out + "/000964.label", 120485);
  size_t ground = 0;
  for (uint32_t l : labels) {
    ASSERT_LE(l, 1u);
    ground += l;
  }
  EXPECT_GT(ground, 20000u);
  EXPECT_LT(ground, 100000u);
  EXPECT_NE(log.find("000964: 120485 points"), std::string::npos) << log;
}

TEST(CliSegment, WritesPcdAndPlyWithLabelsAndPictures) {
  const std::string dir = test::TempDir();
  WriteKittiBin(dir + "/scan.bin", SmallScan());
  std::string log;
  for (const char* format : {"pcd", "ply"}) {
    ASSERT_EQ(
        Segment(dir + "/scan.bin --sensor hdl64e --out " + dir + "/o --images --format " + format,
                &log),
        0)
        << log;
    EXPECT_TRUE(fs::exists(dir + "/o/scan." + format)) << format;
  }
  EXPECT_TRUE(fs::exists(dir + "/o/images/scan_bev.png"));
  EXPECT_TRUE(fs::exists(dir + "/o/images/scan_classes.png"));
}

TEST(CliSegment, AFileWithoutIntensityIsNotedOnceARun) {
  const std::string dir = test::TempDir();
  fs::create_directories(dir + "/in");
  const Cloud scan = SmallScan();
  std::string xyz = "ply\nformat ascii 1.0\nelement vertex " + std::to_string(scan.size()) +
                    "\nproperty float x\nproperty float y\nproperty float z\nend_header\n";
  for (size_t i = 0; i < scan.size(); ++i)
    xyz += std::to_string(scan.x(i)) + " " + std::to_string(scan.y(i)) + " " +
           std::to_string(scan.z(i)) + "\n";
  WriteBytes(dir + "/in/a.ply", xyz);
  WriteBytes(dir + "/in/b.ply", xyz);
  WriteKittiBin(dir + "/in/c.bin", scan);
  std::string log;
  ASSERT_EQ(Segment(dir + "/in --sensor hdl64e --out " + dir + "/o", &log), 0) << log;
  const std::string note = "lpir-gseg segment: note: " + dir + "/in/a.ply has no intensity field";
  EXPECT_NE(log.find(note), std::string::npos) << log;
  EXPECT_NE(log.find("first such file only"), std::string::npos) << log;
  size_t notes = 0;
  for (size_t at = log.find("no intensity field"); at != std::string::npos;
       at = log.find("no intensity field", at + 1))
    ++notes;
  EXPECT_EQ(notes, 1u) << log;
  for (const char* stem : {"a", "b", "c"})
    EXPECT_TRUE(fs::exists(dir + "/o/" + stem + ".label")) << stem;
  ASSERT_EQ(Segment(dir + "/in --sensor hdl64e --quiet --out " + dir + "/q", &log), 0) << log;
  EXPECT_EQ(log, "");
}

TEST(CliSegment, NanInfAndOriginPointsAreNonGroundAndCounted) {
  const std::string dir = test::TempDir();
  Cloud c = SmallScan();
  const float nan = std::numeric_limits<float>::quiet_NaN();
  c.Push(nan, 1, 1, 0);
  c.Push(1, std::numeric_limits<float>::infinity(), 1, 0);
  c.Push(0, 0, 0, 0);
  WriteKittiBin(dir + "/scan.bin", c);
  std::string log;
  ASSERT_EQ(Segment(dir + "/scan.bin --sensor hdl64e --out " + dir, &log), 0) << log;
  const std::vector<uint32_t> labels = ReadLabelFile(dir + "/scan.label", c.size());
  EXPECT_EQ(labels[c.size() - 1], 0u);
  EXPECT_EQ(labels[c.size() - 2], 0u);
  EXPECT_EQ(labels[c.size() - 3], 0u);
  EXPECT_NE(log.find("3 invalid points"), std::string::npos) << log;
}

struct BadCase {
  const char* name;
  const char* file;  // written into a temp folder
  std::string bytes;
  const char* expect;  // a word the message must hold
};

class CliSegmentBadInput : public ::testing::TestWithParam<BadCase> {};

TEST_P(CliSegmentBadInput, FailsWithAMessageNamingTheFile) {
  const BadCase& bad = GetParam();
  const std::string dir = test::TempDir();
  const std::string path = dir + "/" + bad.file;
  WriteBytes(path, bad.bytes);
  std::string log;
  const int code = Segment(path + " --sensor hdl64e --out " + dir + "/out", &log);
  EXPECT_EQ(code, 1) << log;
  EXPECT_NE(log.find(path), std::string::npos) << log;
  EXPECT_NE(log.find(bad.expect), std::string::npos) << log;
}

INSTANTIATE_TEST_SUITE_P(
    Files, CliSegmentBadInput,
    ::testing::Values(
        BadCase{"empty_bin", "empty.bin", "", "empty"},
        BadCase{"truncated_bin", "cut.bin", std::string(4 * 4 * 3 + 5, '\0'), "16"},
        BadCase{"pcd_promises_more", "short.pcd",
                "VERSION 0.7\nFIELDS x y z intensity\nSIZE 4 4 4 4\nTYPE F F F F\nCOUNT 1 1 1 "
                "1\nWIDTH 3\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS 3\nDATA ascii\n1 2 3 4\n",
                "3"},
        BadCase{"ply_bad_type", "bad.ply",
                "ply\nformat ascii 1.0\nelement vertex 1\nproperty float128 x\nproperty float "
                "y\nproperty float z\nend_header\n1 2 3\n",
                "float128"},
        BadCase{"unknown_extension", "scan.xyz", "1 2 3\n", "xyz"}),
    [](const ::testing::TestParamInfo<BadCase>& info) { return std::string(info.param.name); });

TEST(CliSegment, MissingFileIsNamed) {
  std::string log;
  EXPECT_EQ(Segment("/nonexistent/scan.bin --sensor hdl64e --out " + test::TempDir(), &log), 1);
  EXPECT_NE(log.find("/nonexistent/scan.bin"), std::string::npos) << log;
}

TEST(CliSegment, UnknownSensorListsTheKnownOnes) {
  const std::string dir = test::TempDir();
  WriteKittiBin(dir + "/scan.bin", SmallScan());
  std::string log;
  EXPECT_NE(Segment(dir + "/scan.bin --sensor hdl65 --out " + dir, &log), 0);
  EXPECT_NE(log.find("hdl65"), std::string::npos) << log;
  EXPECT_NE(log.find("hdl64e"), std::string::npos) << log;
}

TEST(CliSegment, CloudLargerThanConfiguredIsAnError) {
  const std::string dir = test::TempDir();
  WriteKittiBin(dir + "/scan.bin", SmallScan());
  std::string log;
  EXPECT_EQ(Segment(dir + "/scan.bin --sensor hdl64e --max-points 100 --out " + dir, &log), 1);
  EXPECT_NE(log.find("800 points"), std::string::npos) << log;
  EXPECT_NE(log.find("maximum of 100"), std::string::npos) << log;
}

TEST(CliSegment, TruthWhoseCountDiffersIsAnError) {
  const std::string dir = test::TempDir();
  WriteKittiBin(dir + "/scan.bin", SmallScan());
  WriteLabelFile(dir + "/scan.label", std::vector<uint32_t>(799, 40));
  std::string log;
  EXPECT_EQ(Segment(dir + "/scan.bin --sensor hdl64e --images --gt " + dir + "/scan.label --out " +
                        dir + "/o",
                    &log),
            1);
  EXPECT_NE(log.find(dir + "/scan.label"), std::string::npos) << log;
  EXPECT_NE(log.find("799"), std::string::npos) << log;
}

TEST(CliSegment, AFolderWithOneBadFileLabelsTheRestAndFails) {
  const std::string dir = test::TempDir();
  fs::create_directories(dir + "/in");
  WriteKittiBin(dir + "/in/a.bin", SmallScan());
  WriteKittiBin(dir + "/in/c.bin", SmallScan());
  WriteBytes(dir + "/in/b.bin", std::string(21, '\1'));  // truncated
  std::string log;
  EXPECT_EQ(Segment(dir + "/in --sensor hdl64e --out " + dir + "/out", &log), 1);
  EXPECT_TRUE(fs::exists(dir + "/out/a.label"));
  EXPECT_TRUE(fs::exists(dir + "/out/c.label"));
  EXPECT_FALSE(fs::exists(dir + "/out/b.label"));
  EXPECT_NE(log.find(dir + "/in/b.bin"), std::string::npos) << log;
  EXPECT_NE(log.find("1 of 3 files failed"), std::string::npos) << log;
}

TEST(CliSegment, QuietPrintsNothingOnSuccessAndTheDefaultOneSummary) {
  const std::string dir = test::TempDir();
  fs::create_directories(dir + "/in");
  for (const char* name : {"a", "b", "c"}) WriteKittiBin(dir + "/in/" + name + ".bin", SmallScan());
  std::string log;
  ASSERT_EQ(Segment(dir + "/in --sensor hdl64e --backend cpu --quiet --out " + dir + "/q", &log), 0)
      << log;
  EXPECT_EQ(log, "");
  EXPECT_TRUE(fs::exists(dir + "/q/c.label"));
  // Piped: the progress as plain lines, then the summary; never a carriage return.
  ASSERT_EQ(Segment(dir + "/in --sensor hdl64e --backend cpu --out " + dir + "/d", &log), 0) << log;
  EXPECT_EQ(log.find('\r'), std::string::npos) << log;
  EXPECT_EQ(log.find(": 800 points"), std::string::npos) << log;  // no per-frame lines
  EXPECT_NE(log.find("progress: 3/3 100%"), std::string::npos) << log;
  EXPECT_NE(log.find("segmented 3 of 3 files with sensor 'hdl64e' on the CPU reference in "),
            std::string::npos)
      << log;
  EXPECT_NE(log.find(", 0 failed; labels in " + dir + "/d\n"), std::string::npos) << log;
  // --verbose: a line per frame too.
  ASSERT_EQ(Segment(dir + "/in --sensor hdl64e --backend cpu --verbose --out " + dir + "/v", &log),
            0)
      << log;
  EXPECT_NE(log.find("segmenting 3 files"), std::string::npos) << log;
  EXPECT_NE(log.find("b: 800 points"), std::string::npos) << log;
  EXPECT_NE(Segment(dir + "/in --sensor hdl64e --quiet --verbose --out " + dir + "/x", &log), 0);
  EXPECT_NE(log.find("--quiet and --verbose"), std::string::npos) << log;
}

TEST(CliSegment, VersionNamesTheVersionCommitAndBackends) {
  std::string log;
  ASSERT_EQ(test::RunCommand(Cli() + " --version", &log), 0) << log;
  EXPECT_EQ(log.rfind("lpir-gseg 0.", 0), 0u) << log;
  EXPECT_NE(log.find(" (commit "), std::string::npos) << log;
  EXPECT_NE(log.find("backend cpu: available"), std::string::npos) << log;
  EXPECT_NE(log.find("backend vulkan: "), std::string::npos) << log;
}

TEST(CliSegment, UsageErrorsExitNonZero) {
  std::string log;
  EXPECT_NE(Segment("--sensor hdl64e --out /tmp", &log), 0);
  EXPECT_NE(log.find("no INPUT"), std::string::npos) << log;
  EXPECT_NE(Segment("x.bin --sensor hdl64e --out /tmp --format las", &log), 0);
  EXPECT_NE(log.find("--format"), std::string::npos) << log;
  EXPECT_NE(test::RunCommand(Cli() + " segmnt", &log), 0);
  EXPECT_NE(log.find("unknown command"), std::string::npos) << log;
}

}  // namespace
}  // namespace lpir
