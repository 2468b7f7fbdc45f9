// lpir-gseg segment and topics on drives as recorders and people leave them, run as a user runs
// them, on the fixtures independent writers made (tests/data/drives/, README there): ROS 2 bag
// folders of two split files, a .bag.active a killed ROS 1 recorder left, several drives and
// folders of drives in one call, damaged drives listed. Every label file is compared, byte for
// byte, with what `segment` writes for the same frame given as a file.
#include <gtest/gtest.h>

#include <cctype>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <ostream>
#include <sstream>
#include <string>
#include <vector>

#include "host/io/pcd.h"
#include "tests/drive_fixtures.h"
#include "tests/io_test_helpers.h"
#include "tests/test_util.h"

namespace fs = std::filesystem;

namespace lpir {
namespace {

using test::kFirstStampNs;
const char* const kTopic = test::kFixtureTopic;
constexpr size_t kFrames = test::kFixtureFrames;

std::string Cli() { return test::CliPath(); }
const std::string kSegment = " --sensor vlp16 --backend cpu --out ";

bool Has(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

// "<sequence %06>_<stamp ns>.label": segment's name for a drive's message of frame `frame`.
std::string LabelName(size_t sequence, size_t frame) {
  char name[64];
  std::snprintf(name, sizeof(name), "%06zu_%lld.label", sequence,
                kFirstStampNs + (long long)frame * 100000000LL);
  return name;
}

// `segment`'s labels of the fixture frames given as files with their rings (PCD files written
// here, as the drives carry them): `frame(i)` gives frame i.
class FrameLabels {
 public:
  explicit FrameLabels(const std::function<Cloud(size_t)>& frame) {
    std::string args;
    for (size_t i = 0; i < kFrames; ++i) {
      const std::string pcd = dir_.path + "/" + std::to_string(i) + ".pcd";
      WritePcd(pcd, frame(i), nullptr, true);
      args += " " + pcd;
    }
    std::string log;
    EXPECT_EQ(
        test::RunCommand(Cli() + " segment" + args + kSegment + dir_.path + "/out --quiet", &log),
        0)
        << log;
    size_t ground = 0;
    for (size_t i = 0; i < kFrames; ++i)
      for (char c : (*this)(i)) ground += c == 1;
    EXPECT_GT(ground, 50u) << "labels all 0 would make the comparisons empty";
  }
  // The .label bytes of frame i.
  std::string operator()(size_t i) const {
    return test::ReadFileBytes(dir_.path + "/out/" + std::to_string(i) + ".label");
  }

 private:
  test::ScopedDir dir_;
};

const FrameLabels& Narrow() {
  static const FrameLabels* labels = new FrameLabels(test::NarrowFrame);  // to the end of the run
  return *labels;
}
const FrameLabels& Whole() {
  static const FrameLabels* labels = new FrameLabels(test::FixtureFrame);
  return *labels;
}

// `dir` holds the labels of `count` messages, frames 0.. in order, equal to `expected`'s.
void ExpectDriveLabels(const std::string& dir, const FrameLabels& expected, size_t count,
                       const std::string& log) {
  std::vector<std::string> names;
  for (size_t i = 0; i < count; ++i) {
    names.push_back(LabelName(i, i));
    EXPECT_EQ(test::ReadFileBytes(dir + "/" + LabelName(i, i)), expected(i))
        << dir << " message " << i << "\n"
        << log;
  }
  EXPECT_EQ(test::LabelFiles(dir), names) << log;
  std::istringstream index(test::ReadFileBytes(dir + "/index.csv"));
  size_t lines = 0;
  for (std::string line; std::getline(index, line);) ++lines;
  EXPECT_EQ(lines, count + 1) << dir << "/index.csv";
}

std::string Fixture(const std::string& name) { return test::DrivesDir() + "/" + name; }

// ---- ROS 2 bag folders ----

struct SplitBag {
  const char* folder;
  const char* ext;
};
void PrintTo(const SplitBag& b, std::ostream* os) { *os << b.folder; }

class CliBagFolder : public ::testing::TestWithParam<SplitBag> {};

TEST_P(CliBagFolder, LabelsAsTheFramesAsFilesAndAsItsFilesOneByOne) {
  const std::string folder = Fixture(GetParam().folder);
  test::ScopedDir out;
  std::string log;
  ASSERT_EQ(test::RunCommand(Cli() + " segment " + folder + kSegment + out.path + "/bag", &log), 0)
      << log;
  ExpectDriveLabels(out.path + "/bag", Narrow(), kFrames, log);
  EXPECT_TRUE(Has(log, "segmented 3 of 3 messages of /velodyne_points in " + folder)) << log;
  // each file on its own gives the same bytes, numbered from 0 in each
  for (int n : {0, 1}) {
    const std::string file =
        folder + "/" + GetParam().folder + "_" + std::to_string(n) + GetParam().ext;
    const std::string dir = out.path + "/" + std::to_string(n);
    ASSERT_EQ(test::RunCommand(Cli() + " segment " + file + kSegment + dir + " --quiet", &log), 0)
        << log;
    const std::vector<std::pair<size_t, size_t>> messages =  // (sequence in the file, frame)
        n == 0 ? std::vector<std::pair<size_t, size_t>>{{0, 0}, {1, 1}}
               : std::vector<std::pair<size_t, size_t>>{{0, 2}};
    for (const auto& [sequence, frame] : messages)
      EXPECT_EQ(test::ReadFileBytes(dir + "/" + LabelName(sequence, frame)),
                test::ReadFileBytes(out.path + "/bag/" + LabelName(frame, frame)))
          << file << " frame " << frame;
  }
}

TEST_P(CliBagFolder, TopicsListsItAsOneDrive) {
  std::string log;
  ASSERT_EQ(test::RunCommand(Cli() + " topics " + Fixture(GetParam().folder) + "/", &log), 0)
      << log;
  std::istringstream lines(log);
  std::string head, row;
  std::getline(lines, head);
  std::getline(lines, row);
  EXPECT_TRUE(Has(row, kTopic) && Has(row, "sensor_msgs/msg/PointCloud2") && Has(row, " 3")) << log;
  EXPECT_EQ(test::RunCommand(Cli() + " topics " + Fixture(GetParam().folder) + " --chunks", &log),
            0);
  EXPECT_EQ(log, std::string(GetParam().ext) == ".mcap" ? "3\n" : "0\n");
}

INSTANTIATE_TEST_SUITE_P(Fixtures, CliBagFolder,
                         ::testing::Values(SplitBag{"vlp16_split_mcap", ".mcap"},
                                           SplitBag{"vlp16_split_db3", ".db3"}),
                         [](const ::testing::TestParamInfo<SplitBag>& info) {
                           return std::string(info.param.ext + 1);
                         });

// ---- a ROS 1 recorder killed while writing ----

TEST(CliKilledBag, SegmentsWhatTheRecorderFinishedAndNamesTheRest) {
  const std::string bag = Fixture("vlp16_killed.bag.active");
  test::ScopedDir out;
  std::string log;
  EXPECT_EQ(test::RunCommand(Cli() + " segment " + bag + kSegment + out.path, &log), 1) << log;
  ExpectDriveLabels(out.path, Narrow(), 2, log);
  EXPECT_TRUE(Has(log, "lpir-gseg segment: note: " + bag + ": no index")) << log;
  EXPECT_TRUE(Has(log, "lpir-gseg segment: error: " + bag + ": chunk 2 at byte")) << log;
  EXPECT_TRUE(Has(log, bag + ": 1 problem")) << log;
  EXPECT_EQ(test::RunCommand(Cli() + " topics " + bag, &log), 1) << log;
  EXPECT_TRUE(Has(log, "/velodyne_points  sensor_msgs/PointCloud2  ros1      2")) << log;
}

// ---- several drives in one call ----

// A folder holding three drives of three kinds and a file that is neither cloud nor drive.
struct DrivesFolder {
  test::ScopedDir dir;
  std::string path = dir.path + "/drives";
  DrivesFolder() {
    fs::create_directories(path);
    fs::copy(Fixture("vlp16_zstd.mcap"), path + "/vlp16_zstd.mcap");
    fs::copy(Fixture("vlp16_bz2.bag"), path + "/vlp16_bz2.bag");
    fs::copy(Fixture("vlp16_split_db3"), path + "/vlp16_split_db3", fs::copy_options::recursive);
    test::WriteRaw(path + "/README.txt", "three drives");
  }
};

TEST(CliSeveralDrives, AFolderOfThreeDrivesIsSegmentedInOneCall) {
  const DrivesFolder drives;
  const std::string out = drives.dir.path + "/out";
  std::string log;
  ASSERT_EQ(
      test::RunCommand(Cli() + " segment " + drives.path + kSegment + out + " --verbose", &log), 0)
      << log;
  ExpectDriveLabels(out + "/vlp16_zstd", Whole(), kFrames, log);
  ExpectDriveLabels(out + "/vlp16_bz2", Whole(), kFrames, log);
  ExpectDriveLabels(out + "/vlp16_split_db3", Narrow(), kFrames, log);
  EXPECT_TRUE(Has(log, "segmented 9 of 9 messages of 3 drives")) << log;
  EXPECT_TRUE(Has(log, "passed over " + drives.path + "/README.txt")) << log;
}

TEST(CliSeveralDrives, DrivesAndFilesTogetherEachWriteTheirOwn) {
  test::ScopedDir out;
  std::string log;
  ASSERT_EQ(test::RunCommand(Cli() + " segment " + Fixture("vlp16_lz4.bag") + " " +
                                 test::NarrowFrameBase(0) + ".bin " + Fixture("vlp16_split_mcap") +
                                 kSegment + out.path,
                             &log),
            0)
      << log;
  ExpectDriveLabels(out.path + "/vlp16_lz4", Whole(), kFrames, log);
  ExpectDriveLabels(out.path + "/vlp16_split_mcap", Narrow(), kFrames, log);
  EXPECT_EQ(test::LabelFiles(out.path), std::vector<std::string>{"000000.label"});
  EXPECT_TRUE(Has(log, "segmented 1 of 1 file and 6 of 6 messages of 2 drives")) << log;
}

TEST(CliSeveralDrives, ADriveThatCannotBeReadIsOneFailureTheOthersAreSegmented) {
  const DrivesFolder drives;
  test::WriteRaw(drives.path + "/broken.mcap", "not an MCAP file at all");
  const std::string out = drives.dir.path + "/out";
  std::string log;
  EXPECT_EQ(test::RunCommand(Cli() + " segment " + drives.path + kSegment + out, &log), 1) << log;
  EXPECT_TRUE(Has(log, "lpir-gseg segment: error: " + drives.path + "/broken.mcap: not an MCAP"))
      << log;
  ExpectDriveLabels(out + "/vlp16_zstd", Whole(), kFrames, log);
  ExpectDriveLabels(out + "/vlp16_split_db3", Narrow(), kFrames, log);
  EXPECT_FALSE(fs::exists(out + "/broken")) << log;
  EXPECT_TRUE(Has(log, "1 of 4 inputs with problems")) << log;
}

TEST(CliSeveralDrives, TwoDrivesOfOneStemAreRefusedBeforeAnythingIsWritten) {
  test::ScopedDir dir;
  fs::copy(Fixture("vlp16_zstd.mcap"), dir.path + "/run.mcap");
  fs::copy(Fixture("vlp16_lz4.bag"), dir.path + "/run.bag");
  std::string log;
  EXPECT_EQ(test::RunCommand(Cli() + " segment " + dir.path + kSegment + dir.path + "/out", &log),
            2)
      << log;
  EXPECT_TRUE(Has(log, dir.path + "/run.bag and " + dir.path + "/run.mcap")) << log;
  EXPECT_FALSE(fs::exists(dir.path + "/out")) << log;
  EXPECT_EQ(test::RunCommand(Cli() + " segment " + Fixture("vlp16_zstd.mcap") + " " +
                                 Fixture("vlp16_lz4.bag") + " --chunks 1:1" + kSegment + dir.path +
                                 "/out",
                             &log),
            2);
  EXPECT_TRUE(Has(log, "--chunks is for one recorded drive")) << log;
}

// Drives of one stem in two subfolders: --recursive over the folder above keeps each at its path
// below it (the output rule, as for cloud files); given as two folders they are refused.
TEST(CliSeveralDrives, RecursiveKeepsDrivesOfOneStemApartByTheirPaths) {
  test::ScopedDir dir;
  for (const char* sub : {"/runs/a", "/runs/b"}) {
    fs::create_directories(dir.path + sub);
    fs::copy(Fixture("vlp16_zstd.mcap"), dir.path + sub + "/drive.mcap");
  }
  fs::copy(Fixture("vlp16_split_mcap"), dir.path + "/runs/b/bag", fs::copy_options::recursive);
  const std::string out = dir.path + "/out";
  std::string log;
  EXPECT_EQ(test::RunCommand(Cli() + " segment " + dir.path + "/runs" + kSegment + out, &log), 2)
      << log;
  EXPECT_TRUE(Has(log, dir.path + "/runs: folder holds no cloud files or drives, but its "
                                  "subfolders hold 3: --recursive (-r)"))
      << log;
  EXPECT_EQ(test::RunCommand(
                Cli() + " segment " + dir.path + "/runs/a " + dir.path + "/runs/b" + kSegment + out,
                &log),
            2)
      << log;
  EXPECT_TRUE(Has(log, dir.path + "/runs/a/drive.mcap and " + dir.path +
                           "/runs/b/drive.mcap would both write " + out + "/drive"))
      << log;
  EXPECT_FALSE(fs::exists(out)) << log;
  ASSERT_EQ(test::RunCommand(
                Cli() + " segment -r " + dir.path + "/runs" + kSegment + out + " --images", &log),
            0)
      << log;
  ExpectDriveLabels(out + "/a/drive", Whole(), kFrames, log);
  ExpectDriveLabels(out + "/b/drive", Whole(), kFrames, log);
  ExpectDriveLabels(out + "/b/bag", Narrow(), kFrames, log);
  const std::string first = LabelName(0, 0);  // "<sequence>_<stamp>.label"
  EXPECT_TRUE(fs::exists(out + "/images/a/drive/" + first.substr(0, first.size() - 6) + "_bev.png"))
      << log;
  EXPECT_TRUE(Has(log, "segmented 9 of 9 messages of 3 drives")) << log;
  // topics takes the same rule
  ASSERT_EQ(test::RunCommand(Cli() + " topics -r " + dir.path + "/runs --chunks", &log), 0) << log;
  EXPECT_TRUE(Has(log, dir.path + "/runs/b/bag: 3\n")) << log;
}

TEST(CliSeveralDrives, TopicsListsEachDriveUnderItsName) {
  const DrivesFolder drives;
  std::string log;
  ASSERT_EQ(test::RunCommand(Cli() + " topics " + drives.path, &log), 0) << log;
  for (const char* name : {"vlp16_bz2.bag", "vlp16_split_db3", "vlp16_zstd.mcap"})
    EXPECT_TRUE(Has(log, drives.path + "/" + name + ":\ntopic")) << log;
  ASSERT_EQ(test::RunCommand(Cli() + " topics " + drives.path + " --chunks", &log), 0) << log;
  EXPECT_TRUE(Has(log, drives.path + "/vlp16_split_db3: 0\n")) << log;
  EXPECT_TRUE(Has(log, drives.path + "/vlp16_zstd.mcap: 3\n")) << log;
}

// ---- damage, listed ----

class CliTopicsOfACutDrive : public ::testing::TestWithParam<const char*> {};

TEST_P(CliTopicsOfACutDrive, ListsWhatItReadNamesTheDamageAndExits1) {
  test::ScopedDir dir;
  const std::string bytes = test::ReadRaw(Fixture(GetParam()));
  const std::string cut = dir.path + "/" + GetParam();
  test::WriteRaw(cut, bytes.substr(0, bytes.size() * 85 / 100));  // inside the third chunk
  std::string log;
  EXPECT_EQ(test::RunCommand(Cli() + " topics " + cut, &log), 1) << log;
  EXPECT_TRUE(Has(log, "/velodyne_points")) << log;
  EXPECT_TRUE(Has(log, "lpir-gseg topics: error: " + cut + ": chunk 3")) << log;
  EXPECT_TRUE(Has(log, cut + ": damaged (1 part, named above)")) << log;
}

INSTANTIATE_TEST_SUITE_P(Fixtures, CliTopicsOfACutDrive,
                         ::testing::Values("vlp16_zstd.mcap", "vlp16_none.mcap", "vlp16_bz2.bag"),
                         [](const ::testing::TestParamInfo<const char*>& info) {
                           std::string name = info.param;
                           for (char& c : name)
                             if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                           return name;
                         });

// A 3 KB stub of an MCAP: topics says it is damaged; segment says the same with or without
// --topic, and never sends the user from one to the other.
TEST(CliDamagedStub, TopicsAndSegmentAgreeWithAndWithoutTopic) {
  test::ScopedDir dir;
  const std::string stub = dir.path + "/stub.mcap";
  test::WriteRaw(stub, test::ReadRaw(Fixture("vlp16_zstd.mcap")).substr(0, 3000));
  std::string log;
  EXPECT_EQ(test::RunCommand(Cli() + " topics " + stub, &log), 1) << log;
  EXPECT_TRUE(Has(log, "(no topics)")) << log;
  EXPECT_TRUE(Has(log, "lpir-gseg topics: error: " + stub + ": chunk 1")) << log;
  for (const std::string topic : {"", " --topic /velodyne_points"}) {
    EXPECT_EQ(
        test::RunCommand(Cli() + " segment " + stub + topic + kSegment + dir.path + "/o", &log), 4)
        << topic << "\n"
        << log;
    EXPECT_TRUE(Has(log, "in what could be read: the drive is damaged (" + stub + ": chunk 1"))
        << topic << "\n"
        << log;
    EXPECT_FALSE(Has(log, "--topic T reads")) << log;
    EXPECT_FALSE(fs::exists(dir.path + "/o")) << log;
  }
}

}  // namespace
}  // namespace lpir
