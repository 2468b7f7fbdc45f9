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

#include "apps/sim/scene.h"
#include "host/io/kitti_bin.h"
#include "host/io/label_file.h"
#include "host/io/sensor_profile.h"
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

// A simulated street of `sensor` (seed 5), as a nuScenes-layout .pcd.bin (x, y, z, intensity,
// ring) when `rings`, else a KITTI .bin; returns the file's path.
std::string StreetFile(const std::string& dir, const std::string& sensor, bool rings) {
  SimOptions o;
  o.seed = 5;
  o.emit_rings = rings;
  const Cloud c = Simulate(LoadSensorProfile(sensor, test::SensorsDir()), o).cloud;
  const std::string path = dir + "/" + sensor + (rings ? ".pcd.bin" : ".bin");
  if (!rings) {
    WriteKittiBin(path, c);
    return path;
  }
  std::vector<float> values;
  for (size_t i = 0; i < c.size(); ++i)
    values.insert(values.end(), {c.x(i), c.y(i), c.z(i), c.intensity(i), float(c.ring[i])});
  WriteBytes(path, std::string(reinterpret_cast<const char*>(values.data()), 4 * values.size()));
  return path;
}

TEST(CliSegment, RingsOfAnotherSensorAreRefusedNamingTheProfile) {
  const std::string dir = test::TempDir();
  const std::string file = StreetFile(dir, "hdl64e", true);
  std::string log;
  EXPECT_EQ(Segment(file + " --sensor vlp32c --max-points 400000 --out " + dir + "/out", &log), 1)
      << log;
  EXPECT_NE(log.find("ring values up to 63"), std::string::npos) << log;
  EXPECT_NE(log.find("profile 'vlp32c' has 32 beams: wrong --sensor?"), std::string::npos) << log;
  // The same file with its own profile: segmented, no warning.
  EXPECT_EQ(Segment(file + " --sensor hdl64e --out " + dir + "/own", &log), 0) << log;
  EXPECT_EQ(log.find("warning"), std::string::npos) << log;
}

TEST(CliSegment, ElevationsOutsideTheProfileAreAWarning) {
  const std::string dir = test::TempDir();
  const std::string file = StreetFile(dir, "hdl64e", false);
  std::string log;
  EXPECT_EQ(Segment(file + " --sensor vlp16 --max-points 400000 --out " + dir + "/out", &log), 0)
      << log;
  EXPECT_NE(log.find("warning: " + file + ": "), std::string::npos) << log;
  EXPECT_NE(log.find("below the bottom beam (-15.0 deg) of profile 'vlp16': wrong --sensor"),
            std::string::npos)
      << log;
}

TEST(CliSegment, TheSummaryNamesWhyPointsAreInvalid) {
  const std::string dir = test::TempDir();
  Cloud c = SmallScan();
  const float nan = std::numeric_limits<float>::quiet_NaN();
  c.Push(nan, 1.0f, 1.0f, 0.0f);
  c.Push(0.0f, 0.0f, 0.0f, 0.0f);
  WriteKittiBin(dir + "/scan.bin", c);
  std::string log;
  EXPECT_EQ(Segment(dir + "/scan.bin --sensor hdl64e --out " + dir + "/out", &log), 0) << log;
  EXPECT_NE(log.find("2 invalid points (non-ground: 1 NaN/Inf, 1 at the origin)"),
            std::string::npos)
      << log;
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

// The pictures' library is loaded only for --images: a copy of the program without it beside it
// labels as before, and with --images stops first (exit 4) naming the library, writing nothing.
TEST(CliSegment, PicturesNeedTheirLibraryAndNothingElseDoes) {
  const std::string dir = test::TempDir();
  WriteKittiBin(dir + "/scan.bin", SmallScan());
  fs::copy_file(Cli(), dir + "/lpir-gseg");
  std::string log;
  const std::string run = dir + "/lpir-gseg segment " + dir + "/scan.bin --sensor hdl64e --out ";
  ASSERT_EQ(test::RunCommand(run + dir + "/labels --quiet", &log), 0) << log;
  EXPECT_TRUE(fs::exists(dir + "/labels/scan.label"));
  EXPECT_EQ(test::RunCommand(run + dir + "/pictures --images", &log), 4) << log;
  EXPECT_NE(log.find(dir + "/liblpir_images.so: cannot load the pictures' library"),
            std::string::npos)
      << log;
  EXPECT_FALSE(fs::exists(dir + "/pictures"));
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
  EXPECT_NE(log.find("more than the 100 this segmenter takes"), std::string::npos) << log;
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
  EXPECT_NE(log.find("segmented 3 of 3 files on the CPU reference in "), std::string::npos) << log;
  EXPECT_NE(log.find(" frames/s; labels in " + dir + "/d\n"), std::string::npos) << log;
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

// A simulated VLP-16 street (a few thousand points, ground and objects): dir/name.
void Simulate(const std::string& path, int seed) {
  std::string log;
  ASSERT_EQ(test::RunCommand(Cli() + " simulate --sensor vlp16 --seed " + std::to_string(seed) +
                                 " --out " + path + " --labels " + path + ".truth",
                             &log),
            0)
      << log;
}

TEST(CliSegment, TwoInputsOfOneStemAreRefusedNamingBothAndNothingIsWritten) {
  const test::ScopedDir dir;
  const std::string a = dir.path + "/a/000000.bin", b = dir.path + "/b/000000.bin";
  fs::create_directories(dir.path + "/a");
  fs::create_directories(dir.path + "/b");
  Simulate(a, 1);
  Simulate(b, 2);
  for (const char* format : {"label", "pcd", "ply"}) {
    SCOPED_TRACE(format);
    std::string log;
    // the folders, and the files themselves
    for (const std::string& inputs :
         {dir.path + "/a " + dir.path + "/b", a + " " + b, dir.path + "/a " + b}) {
      EXPECT_EQ(
          Segment(inputs + " -s vlp16 -b cpu -f " + format + " -o " + dir.path + "/out", &log), 2)
          << log;
      EXPECT_NE(
          log.find(a + " and " + b + " would both write " + dir.path + "/out/000000." + format),
          std::string::npos)
          << log;
      EXPECT_NE(log.find("nothing written"), std::string::npos) << log;
      EXPECT_FALSE(fs::exists(dir.path + "/out")) << "nothing written, not even the folder";
    }
  }
  // One file listed twice, and an output that would overwrite its input.
  std::string log;
  EXPECT_EQ(Segment(dir.path + "/a " + a + " -s vlp16 -o " + dir.path + "/out", &log), 2);
  EXPECT_NE(log.find(a + " is listed twice"), std::string::npos) << log;
  fs::create_directories(dir.path + "/p");
  ASSERT_EQ(Segment(a + " -s vlp16 -b cpu -q -f pcd -o " + dir.path + "/p", &log), 0) << log;
  const std::string pcd = dir.path + "/p/000000.pcd";
  const std::string before = test::ReadFileBytes(pcd);
  EXPECT_EQ(Segment(pcd + " -s vlp16 -b cpu -f pcd -o " + dir.path + "/p", &log), 2);
  EXPECT_NE(log.find("would overwrite the input"), std::string::npos) << log;
  EXPECT_EQ(test::ReadFileBytes(pcd), before);
}

TEST(CliSegment, RecursiveKeepsEachFilesPathBelowTheFolder) {
  const test::ScopedDir dir;
  const std::string kitti = dir.path + "/kitti";
  fs::create_directories(kitti + "/00/velodyne");
  fs::create_directories(kitti + "/07/velodyne");
  Simulate(kitti + "/00/velodyne/000000.bin", 1);
  Simulate(kitti + "/07/velodyne/000000.bin", 2);
  std::string log;
  // Without --recursive: no cloud files in kitti/ itself, and the hint.
  EXPECT_EQ(Segment(kitti + " -s vlp16 -o " + dir.path + "/out", &log), 2);
  EXPECT_NE(log.find(kitti + ": folder holds no cloud files or drives, but its subfolders hold 2: "
                             "--recursive (-r)"),
            std::string::npos)
      << log;
  EXPECT_FALSE(fs::exists(dir.path + "/out"));
  ASSERT_EQ(Segment(kitti + " --recursive -s vlp16 -b cpu --images -o " + dir.path + "/out", &log),
            0)
      << log;
  EXPECT_NE(log.find("segmented 2 of 2 files"), std::string::npos) << log;
  for (const char* seq : {"00", "07"}) {
    SCOPED_TRACE(seq);
    const std::string rel = std::string(seq) + "/velodyne/000000";
    // each as it is labelled alone
    const std::string alone = dir.path + "/alone" + seq;
    ASSERT_EQ(Segment(kitti + "/" + rel + ".bin -s vlp16 -b cpu -q -o " + alone, &log), 0) << log;
    const std::string labels = test::ReadFileBytes(dir.path + "/out/" + rel + ".label");
    EXPECT_FALSE(labels.empty());
    EXPECT_EQ(labels, test::ReadFileBytes(alone + "/000000.label"));
    EXPECT_TRUE(fs::exists(dir.path + "/out/images/" + seq + "/velodyne/000000_bev.png"));
  }
  // Two folders whose files share their paths below them: refused, as two stems are.
  EXPECT_EQ(Segment(kitti + "/00 " + kitti + "/07 -r -s vlp16 -o " + dir.path + "/o2", &log), 2);
  EXPECT_NE(log.find(" would both write " + dir.path + "/o2/velodyne/000000.label"),
            std::string::npos)
      << log;
}

TEST(CliSegment, NoOutputFolderForNothingAndAClearErrorForAFile) {
  const test::ScopedDir dir;
  std::string log;
  EXPECT_EQ(Segment(dir.path + "/nosuch.bin -s vlp16 -o " + dir.path + "/out", &log), 1);
  EXPECT_NE(log.find(dir.path + "/nosuch.bin: no such file"), std::string::npos) << log;
  EXPECT_NE(log.find("nothing written"), std::string::npos) << log;
  EXPECT_FALSE(fs::exists(dir.path + "/out"));
  // --out naming a file, or a folder below a file: named, before anything is read.
  Simulate(dir.path + "/scan.bin", 1);
  WriteBytes(dir.path + "/afile", "x");
  EXPECT_EQ(Segment(dir.path + "/scan.bin -s vlp16 -o " + dir.path + "/afile", &log), 4);
  EXPECT_NE(log.find(dir.path + "/afile: is a file, not a folder"), std::string::npos) << log;
  EXPECT_EQ(log.find("filesystem error"), std::string::npos) << log;
  EXPECT_EQ(Segment(dir.path + "/scan.bin -s vlp16 -o " + dir.path + "/afile/sub", &log), 4);
  EXPECT_NE(log.find(dir.path + "/afile/sub: cannot be made: " + dir.path +
                     "/afile is a file, not a folder"),
            std::string::npos)
      << log;
  EXPECT_EQ(test::ReadFileBytes(dir.path + "/afile"), "x");
}

TEST(CliSegment, OptionsAsPeopleTypeThem) {
  const test::ScopedDir dir;
  Simulate(dir.path + "/scan.bin", 3);
  std::string log;
  ASSERT_EQ(Segment(dir.path + "/scan.bin --sensor vlp16 --backend cpu --out " + dir.path + "/long",
                    &log),
            0)
      << log;
  const std::string labels = test::ReadFileBytes(dir.path + "/long/scan.label");
  ASSERT_FALSE(labels.empty());
  for (const std::string& options :
       {std::string("--sensor=vlp16 --backend=cpu --out=") + dir.path + "/o1",
        std::string("-s vlp16 -b cpu -o ") + dir.path + "/o2",
        std::string("-q -s vlp16 -b=cpu -o ") + dir.path + "/o3"}) {
    SCOPED_TRACE(options);
    const std::string out = options.substr(options.size() - 2);
    ASSERT_EQ(Segment(dir.path + "/scan.bin " + options, &log), 0) << log;
    EXPECT_EQ(test::ReadFileBytes(dir.path + "/" + out + "/scan.label"), labels);
  }
  EXPECT_EQ(Segment(dir.path + "/scan.bin -s vlp16 --quiet=yes -o " + dir.path + "/o4", &log), 2);
  EXPECT_NE(log.find("--quiet takes no value"), std::string::npos) << log;
  // `--` ends the options: a file whose name starts with '-'.
  fs::copy_file(dir.path + "/scan.bin", dir.path + "/-scan.bin");
  ASSERT_EQ(
      test::RunCommand(
          "cd " + dir.path + " && " + Cli() + " segment -s vlp16 -b cpu -o o5 -- -scan.bin", &log),
      0)
      << log;
  EXPECT_EQ(test::ReadFileBytes(dir.path + "/o5/-scan.label"), labels);
}

TEST(CliSegment, TyposGetTheNearestName) {
  const test::ScopedDir dir;
  Simulate(dir.path + "/scan.bin", 3);
  const std::string scan = dir.path + "/scan.bin";
  const std::string out = " -o " + dir.path + "/out";
  std::string log;
  EXPECT_EQ(test::RunCommand(Cli() + " segmnet " + scan, &log), 2);
  EXPECT_NE(log.find("unknown command 'segmnet' (did you mean segment?)"), std::string::npos)
      << log;
  EXPECT_EQ(test::RunCommand(Cli() + " help evalute", &log), 2);
  EXPECT_NE(log.find("no command 'evalute' (did you mean evaluate?)"), std::string::npos) << log;
  EXPECT_EQ(Segment(scan + " --sensr vlp16" + out, &log), 2);
  EXPECT_NE(log.find("unknown option --sensr (did you mean --sensor?)"), std::string::npos) << log;
  EXPECT_EQ(Segment(scan + " -sensor vlp16" + out, &log), 2);
  EXPECT_NE(log.find("unknown option -sensor (did you mean --sensor?)"), std::string::npos) << log;
  EXPECT_EQ(Segment(scan + " --sensor hdl-64e" + out, &log), 2);
  EXPECT_NE(log.find("unknown sensor profile 'hdl-64e' (did you mean hdl64e?)"), std::string::npos)
      << log;
  EXPECT_EQ(Segment(scan + " -s vlp16 --set sensr_height=1.9" + out, &log), 2);
  EXPECT_NE(log.find("--set sensr_height=1.9: no setting 'sensr_height' (did you mean "
                     "sensor_height?)"),
            std::string::npos)
      << log;
  // Nothing near: no guess.
  EXPECT_EQ(Segment(scan + " -s vlp16 --frobnicate" + out, &log), 2);
  EXPECT_NE(log.find("unknown option --frobnicate\n"), std::string::npos) << log;
  EXPECT_FALSE(fs::exists(dir.path + "/out"));
}

TEST(CliSegment, SetChangesTheProfileAsAProfileLineWould) {
  const test::ScopedDir dir;
  Simulate(dir.path + "/scan.bin", 4);
  const std::string scan = dir.path + "/scan.bin";
  // The shipped profile with the same changes written into it.
  std::string profile = test::ReadFileBytes(test::SensorsDir() + "/vlp16.txt");
  const size_t at = profile.find("sensor_height 1.73");
  ASSERT_NE(at, std::string::npos);
  profile.replace(at, 18, "sensor_height 1.9");
  const size_t component = profile.find("param min_component 150");
  ASSERT_NE(component, std::string::npos);
  profile.replace(component, 23, "param min_component 90");
  profile += "param h_athr 0.2\n";
  WriteBytes(dir.path + "/mine.txt", profile);
  std::string log;
  ASSERT_EQ(
      Segment(scan + " -s " + dir.path + "/mine.txt -b cpu -q -o " + dir.path + "/file", &log), 0)
      << log;
  ASSERT_EQ(Segment(scan +
                        " -s vlp16 -b cpu -q --set sensor_height=1.9 --set h_athr=0.2 "
                        "--set=min_component=90 -o " +
                        dir.path + "/set",
                    &log),
            0)
      << log;
  ASSERT_EQ(Segment(scan + " -s vlp16 -b cpu -q -o " + dir.path + "/plain", &log), 0) << log;
  const std::string with_file = test::ReadFileBytes(dir.path + "/file/scan.label");
  ASSERT_FALSE(with_file.empty());
  EXPECT_EQ(test::ReadFileBytes(dir.path + "/set/scan.label"), with_file);
  // A setting that moves labels does: points beyond 10 m become invalid, non-ground.
  ASSERT_EQ(Segment(scan + " -s vlp16 -b cpu -o " + dir.path + "/near --set max_range=10", &log), 0)
      << log;
  EXPECT_NE(log.find("invalid points"), std::string::npos) << log;
  EXPECT_NE(test::ReadFileBytes(dir.path + "/near/scan.label"),
            test::ReadFileBytes(dir.path + "/plain/scan.label"));
  // Bad values and names: usage errors naming the setting, nothing written.
  const struct {
    const char* set;
    const char* says;
  } bad[] = {
      {"sensor_height=-1", "--set sensor_height=-1: sensor_height must be > 0"},
      {"sensor_height=high", "--set sensor_height=high: sensor_height: 'high' is not a finite"},
      {"min_component=2.5", "--set min_component=2.5: parameter min_component expects a whole"},
      {"max_range=1", "--set max_range=1: max_range must be larger than min_range"},
      {"sectors_near=100", "sectors_near and sectors_far must divide the image width"},
      {"beams=32", "--set beams=32: no setting 'beams'"},
      {"sensor_height", "--set expects NAME=VALUE"},
  };
  for (const auto& b : bad) {
    SCOPED_TRACE(b.set);
    EXPECT_EQ(Segment(scan + " -s vlp16 --set " + b.set + " -o " + dir.path + "/bad", &log), 2);
    EXPECT_NE(log.find(b.says), std::string::npos) << log;
  }
  EXPECT_FALSE(fs::exists(dir.path + "/bad"));
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
