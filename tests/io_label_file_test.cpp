// SemanticKITTI .label files: round trips, malformed files, the real label files.
#include <gtest/gtest.h>

#include "host/io/kitti_bin.h"
#include "host/io/label_file.h"
#include "tests/io_test_helpers.h"
#include "tests/test_util.h"

namespace lpir {
namespace {

using test::ThrowsIoError;
using test::WriteRaw;

TEST(IoLabelFile, RoundTrip) {
  const std::string path = test::TempDir() + "/a.label";
  const std::vector<uint32_t> labels = {0, 40, 72, (7u << 16) | 10u, 0xFFFFFFFFu};
  WriteLabelFile(path, labels);
  EXPECT_EQ(test::ReadRaw(path).size(), 20u);
  EXPECT_EQ(ReadLabelFile(path), labels);
  EXPECT_EQ(ReadLabelFile(path, 5), labels);
}

TEST(IoLabelFile, IsLittleEndianUint32) {
  const std::string path = test::TempDir() + "/a.label";
  WriteRaw(path, std::string("\x28\x00\x03\x00", 4));  // class 40, instance 3
  const std::vector<uint32_t> labels = ReadLabelFile(path);
  ASSERT_EQ(labels.size(), 1u);
  EXPECT_EQ(labels[0] & 0xFFFF, 40u);
  EXPECT_EQ(labels[0] >> 16, 3u);
}

TEST(IoLabelFile, MissingFile) {
  const std::string path = test::TempDir() + "/absent.label";
  EXPECT_TRUE(ThrowsIoError([&] { ReadLabelFile(path); }, path, {"no such file"}));
}

TEST(IoLabelFile, FolderIsNotAFile) {
  const std::string path = test::TempDir();
  EXPECT_TRUE(ThrowsIoError([&] { ReadLabelFile(path); }, path, {"folder"}));
}

TEST(IoLabelFile, EmptyFile) {
  const std::string path = test::TempDir() + "/empty.label";
  WriteRaw(path, "");
  EXPECT_TRUE(ThrowsIoError([&] { ReadLabelFile(path); }, path, {"empty file"}));
}

TEST(IoLabelFile, SizeNotAWholeNumberOfLabels) {
  const std::string path = test::TempDir() + "/odd.label";
  WriteRaw(path, std::string(10, '\0'));
  EXPECT_TRUE(ThrowsIoError([&] { ReadLabelFile(path); }, path,
                            {"size 10 bytes", "not a whole number of 4-byte labels"}));
}

TEST(IoLabelFile, CountDiffersFromTheCloud) {
  const std::string path = test::TempDir() + "/short.label";
  WriteLabelFile(path, std::vector<uint32_t>(999, 40));
  EXPECT_TRUE(ThrowsIoError([&] { ReadLabelFile(path, 1000); }, path,
                            {"holds 999 labels", "cloud has 1000 points"}));
}

TEST(IoLabelFile, RealKittiLabelsMatchTheScan) {
  LPIR_REQUIRE_DATA("kitti/07/labels/000964.label");
  LPIR_REQUIRE_DATA("kitti/07/velodyne/000964.bin");
  const Cloud cloud = ReadKittiBin(test::DataFile("kitti/07/velodyne/000964.bin"));
  const std::string path = test::DataFile("kitti/07/labels/000964.label");
  const std::vector<uint32_t> labels = ReadLabelFile(path, cloud.size());
  ASSERT_EQ(labels.size(), 120485u);
  size_t road = 0;
  for (uint32_t label : labels) road += (label & 0xFFFF) == 40;
  EXPECT_GT(road, 1000u);  // an urban street scene
  EXPECT_TRUE(ThrowsIoError([&] { ReadLabelFile(path, 120484); }, path,
                            {"holds 120485 labels", "cloud has 120484 points"}));
}

TEST(IoLabelFile, RealRellisLabelsMatchTheScan) {
  LPIR_REQUIRE_DATA("rellis3d/os1/000104.label");
  const std::vector<uint32_t> labels =
      ReadLabelFile(test::DataFile("rellis3d/os1/000104.label"), 131072);
  EXPECT_EQ(labels.size(), 131072u);
}

}  // namespace
}  // namespace lpir
