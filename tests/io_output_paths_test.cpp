// Where a run's outputs go (host/io/output_paths.h): named after each input's path below the
// folder it was found in, and two inputs that would write one output refused naming both.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "host/io/io_error.h"
#include "host/io/output_paths.h"
#include "tests/test_util.h"

namespace fs = std::filesystem;

namespace lpir {
namespace {

// The message of the std::invalid_argument that OutputPaths throws ("" when it throws none).
std::string Refusal(const std::vector<RunInput>& inputs, const std::string& out,
                    const std::string& extension = ".label") {
  try {
    OutputPaths(inputs, out, extension);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

TEST(OutputPaths, AFileGivenItselfKeepsItsNameAFileFoundInAFolderItsPathBelowIt) {
  EXPECT_EQ(OutputPath({"a/000000.bin", "", false}, "out", ".label"), "out/000000.label");
  EXPECT_EQ(OutputPath({"/data/x.pcd", "", false}, "/o/", ".ply"), "/o/x.ply");
  EXPECT_EQ(OutputPath({"n/x.pcd.bin", "", false}, "out", ".label"), "out/x.pcd.label");
  EXPECT_EQ(OutputPath({"kitti/00/velodyne/000000.bin", "kitti", false}, "out", ".label"),
            "out/00/velodyne/000000.label");
  EXPECT_EQ(OutputPath({"kitti/00/velodyne/000000.bin", "kitti/", false}, "out", ".label"),
            "out/00/velodyne/000000.label");
  EXPECT_EQ(OutputPath({"a/000000.bin", "a", false}, "out", ".label"), "out/000000.label");
  // A drive writes a folder: its name without the extension (DriveStem).
  EXPECT_EQ(OutputPath({"drives/run1.mcap", "", true}, "out", ".label"), "out/run1");
  EXPECT_EQ(OutputPath({"d/r/run.bag.active", "d", true}, "out", ".label"), "out/r/run");
}

TEST(OutputPaths, ADrivesStemIsItsNameWithoutTheDriveExtensionABagFoldersItsWholeName) {
  EXPECT_EQ(DriveStem("/a/b/drive.mcap"), "drive");
  EXPECT_EQ(DriveStem("/a/b/drive.bag.active"), "drive");
  EXPECT_EQ(DriveStem("x.v2.db3"), "x.v2");
  const test::ScopedDir dir;
  const std::string bag = dir.path + "/rosbag2_2024.05.01";
  fs::create_directories(bag);
  EXPECT_EQ(DriveStem(bag), "rosbag2_2024.05.01");
  EXPECT_EQ(DriveStem(bag + "/"), "rosbag2_2024.05.01");
  EXPECT_EQ(OutputPath({bag + "/", "", true}, "o", ".label"), "o/rosbag2_2024.05.01");
  EXPECT_EQ(OutputPath({bag, dir.path, true}, "o", ".label"), "o/rosbag2_2024.05.01");
}

TEST(OutputPaths, DistinctOutputsInInputOrder) {
  const std::vector<std::string> outputs = OutputPaths(
      {{"b/2.bin", "", false}, {"a/1.bin", "", false}, {"d.mcap", "", true}}, "out", ".label");
  EXPECT_EQ(outputs, (std::vector<std::string>{"out/2.label", "out/1.label", "out/d"}));
}

TEST(OutputPaths, TwoInputsOfOneOutputAreRefusedNamingBoth) {
  const test::ScopedDir dir;
  for (const char* sub : {"/a", "/b"}) {
    fs::create_directories(dir.path + sub);
    std::ofstream(dir.path + sub + "/000000.bin") << "x";
  }
  const std::string a = dir.path + "/a/000000.bin", b = dir.path + "/b/000000.bin";
  EXPECT_EQ(Refusal({{a, dir.path + "/a", false}, {b, dir.path + "/b", false}}, "out"),
            a + " and " + b + " would both write out/000000.label");
  // other extensions of one stem in one folder
  EXPECT_EQ(Refusal({{"s/x.bin", "", false}, {"s/x.pcd", "", false}}, "o", ".pcd"),
            "s/x.bin and s/x.pcd would both write o/x.pcd");
  // two drives of one name, and a file written into a drive's folder
  EXPECT_EQ(Refusal({{"a/d.mcap", "", true}, {"b/d.bag", "", true}}, "o"),
            "a/d.mcap and b/d.bag would both write o/d");
  EXPECT_EQ(Refusal({{"a/d.mcap", "", true}, {"k/d/0.bin", "k", false}}, "o"),
            "a/d.mcap and k/d/0.bin would both write into o/d");
  // kept apart by their paths below a common folder
  EXPECT_EQ(Refusal({{a, dir.path, false}, {b, dir.path, false}}, "out"), "");
}

TEST(OutputPaths, AFileListedTwiceOrAnOutputThatIsAnInputIsRefused) {
  const test::ScopedDir dir;
  const std::string scan = dir.path + "/scan.pcd";
  std::ofstream(scan) << "x";
  const std::string twice =
      Refusal({{scan, "", false}, {dir.path + "/./scan.pcd", "", false}}, dir.path + "/out");
  EXPECT_NE(twice.find(" is listed twice (also as " + scan + ")"), std::string::npos) << twice;
  const std::string over = Refusal({{scan, "", false}}, dir.path, ".pcd");
  EXPECT_NE(over.find(", the output of " + scan + ", is the input " + scan), std::string::npos)
      << over;
  EXPECT_EQ(Refusal({{scan, "", false}}, dir.path, ".label"), "");
}

TEST(OutputPaths, OutputFoldersAreCheckedBeforeAndMadeWhenWritten) {
  const test::ScopedDir dir;
  std::ofstream(dir.path + "/afile") << "x";
  EXPECT_NO_THROW(CheckOutputFolder(dir.path));
  EXPECT_NO_THROW(CheckOutputFolder(dir.path + "/new/deeper"));
  EXPECT_FALSE(fs::exists(dir.path + "/new"));
  try {
    CheckOutputFolder(dir.path + "/afile");
    ADD_FAILURE() << "a file taken for a folder";
  } catch (const IoError& e) {
    EXPECT_EQ(std::string(e.what()), dir.path +
                                         "/afile: is a file, not a folder: the outputs go "
                                         "into a folder (made when missing)");
  }
  try {
    MakeOutputFolder(dir.path + "/afile/sub/x");
    ADD_FAILURE() << "a folder made below a file";
  } catch (const IoError& e) {
    EXPECT_EQ(std::string(e.what()), dir.path + "/afile/sub/x: cannot be made: " + dir.path +
                                         "/afile is a file, not a folder");
  }
  MakeOutputFolder(dir.path + "/new/deeper");
  EXPECT_TRUE(fs::is_directory(dir.path + "/new/deeper"));
  EXPECT_NO_THROW(MakeOutputFolder(dir.path + "/new/deeper"));  // already there
}

}  // namespace
}  // namespace lpir
