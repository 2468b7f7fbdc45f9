// A Livox drive (tests/data/drives/livox/: two simulated Mid-70 frames as livox_ros_driver2's
// PointCloud2, x y z intensity tag line timestamp, point_step 26, written by @mcap/core and
// @foxglove/rosmsg2-serialization; scripts/make_livox_drive_fixture.sh): the reader decodes each
// message to its frame's .bin without a ring (`line` is no ring, `tag` and `timestamp` are
// passed over), and `segment` labels each message byte for byte as it labels the .bin, with the
// Livox profile and with a spinning one. python/tests/test_drive.py holds Python to the same.
#include <gtest/gtest.h>

#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "host/drive/drive.h"
#include "host/io/kitti_bin.h"
#include "tests/drive_fixtures.h"
#include "tests/test_util.h"

namespace lpir {
namespace {

constexpr size_t kLivoxFrames = 2;

std::string LivoxDir() { return test::DrivesDir() + "/livox"; }
std::string LivoxDrive() { return LivoxDir() + "/mid70.mcap"; }

// "<LivoxDir>/<i %06>.bin": frame i as `simulate` wrote it.
std::string LivoxBin(size_t i) {
  char name[16];
  std::snprintf(name, sizeof(name), "/%06zu.bin", i);
  return LivoxDir() + name;
}

// The label files `segment --sensor SENSOR` writes in a fresh folder for `inputs`, in name order
// (a drive's are named by sequence, so in message order), with their bytes; fails the test when
// segment does not exit 0.
std::vector<std::string> SegmentLabels(const std::string& inputs, const std::string& sensor) {
  test::ScopedDir out;
  std::string log;
  const int rc = test::RunCommand(test::CliPath() + " segment " + inputs + " --sensor " + sensor +
                                      " --backend cpu --quiet" + " --out " + out.path,
                                  &log);
  EXPECT_EQ(rc, 0) << log;
  std::vector<std::string> labels;
  for (const std::string& name : test::LabelFiles(out.path))
    labels.push_back(test::ReadFileBytes(out.path + "/" + name));
  return labels;
}

std::string BinInputs() {
  std::string inputs;
  for (size_t i = 0; i < kLivoxFrames; ++i) inputs += " " + LivoxBin(i);
  return inputs;
}

TEST(DriveLivox, EachMessageDecodesToItsFrameWithoutARing) {
  std::unique_ptr<DriveReader> reader = OpenDrive(LivoxDrive());
  reader->SelectTopic("/livox/lidar");
  size_t frame = 0;
  DriveMessage message;
  std::string problem;
  for (DriveStep step; (step = reader->Next(&message, &problem)) != DriveStep::kEnd;) {
    ASSERT_EQ(step, DriveStep::kMessage) << problem;
    ASSERT_LT(frame, kLivoxFrames);
    EXPECT_EQ(message.log_time_ns, uint64_t(test::kFirstStampNs) + frame * 100000000ull);
    const Cloud cloud = DecodeDriveCloud(LivoxDrive(), message);
    EXPECT_TRUE(cloud.ring.empty()) << "message " << frame << ": a ring read from `line`";
    EXPECT_TRUE(test::SameBits(cloud, ReadKittiBin(LivoxBin(frame)))) << "message " << frame;
    ++frame;
  }
  EXPECT_EQ(frame, kLivoxFrames);
}

TEST(CliDriveLivox, TheDrivesMessagesGetTheLabelsOfTheirBinFiles) {
  const std::vector<std::string> bins = SegmentLabels(BinInputs(), "mid70");
  const std::vector<std::string> drive = SegmentLabels(LivoxDrive(), "mid70");
  ASSERT_EQ(bins.size(), kLivoxFrames);
  ASSERT_EQ(drive.size(), kLivoxFrames);
  for (size_t i = 0; i < kLivoxFrames; ++i) {
    const size_t points = ReadKittiBin(LivoxBin(i)).size();
    ASSERT_EQ(bins[i].size(), points * 4) << "frame " << i;
    EXPECT_EQ(drive[i], bins[i]) << "frame " << i;
    size_t ground = 0;
    for (size_t k = 0; k < points; ++k) ground += bins[i][4 * k] == 1;
    EXPECT_GT(ground, points / 5) << "frame " << i;  // the street's road ahead
    EXPECT_LT(ground, points) << "frame " << i;
  }
}

TEST(CliDriveLivox, ASpinningProfileReadsTheDriveAsItsBinFiles) {
  const std::vector<std::string> bins = SegmentLabels(BinInputs(), "hdl64e");
  const std::vector<std::string> drive = SegmentLabels(LivoxDrive(), "hdl64e");
  ASSERT_EQ(bins.size(), kLivoxFrames);
  ASSERT_EQ(drive, bins);
  for (size_t i = 0; i < kLivoxFrames; ++i)
    EXPECT_EQ(drive[i].size(), ReadKittiBin(LivoxBin(i)).size() * 4) << "frame " << i;
}

}  // namespace
}  // namespace lpir
