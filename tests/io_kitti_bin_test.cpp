// KITTI .bin and nuScenes .pcd.bin: round trips, malformed files, the real scans (absent, empty
// and cut files: tests/io_truncation_test.cpp).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "host/io/cloud_file.h"
#include "host/io/kitti_bin.h"
#include "tests/io_test_helpers.h"
#include "tests/test_util.h"

namespace lpir {
namespace {

using test::Bytes;
using test::SameBits;
using test::ThrowsIoError;
using test::WriteRaw;

TEST(IoKittiBin, RoundTripIsBitExact) {
  const std::string path = test::TempDir() + "/cloud.bin";
  Cloud cloud = test::SampleCloud(100, false);
  cloud.xyzi[5] = std::numeric_limits<float>::quiet_NaN();
  cloud.xyzi[6] = -std::numeric_limits<float>::infinity();
  WriteKittiBin(path, cloud);
  EXPECT_EQ(test::ReadRaw(path).size(), 100u * 16u);
  const Cloud back = ReadKittiBin(path);
  EXPECT_TRUE(SameBits(cloud, back));
  EXPECT_TRUE(back.ring.empty());
  EXPECT_TRUE(std::isnan(back.xyzi[5]));
}

TEST(IoKittiBin, WritingKittiLayoutDropsTheRing) {
  const std::string path = test::TempDir() + "/cloud.bin";
  const Cloud cloud = test::SampleCloud(10, true);
  WriteKittiBin(path, cloud);
  const Cloud back = ReadKittiBin(path);
  EXPECT_TRUE(back.ring.empty());
  EXPECT_EQ(back.xyzi, cloud.xyzi);
}

TEST(IoKittiBin, NuScenesRoundTripKeepsRing) {
  const std::string path = test::TempDir() + "/cloud.pcd.bin";
  const Cloud cloud = test::SampleCloud(70, true);
  WriteKittiBin(path, cloud, BinLayout::kNuScenes5);
  EXPECT_EQ(test::ReadRaw(path).size(), 70u * 20u);
  EXPECT_TRUE(SameBits(cloud, ReadKittiBin(path, BinLayout::kNuScenes5)));
}

TEST(IoKittiBin, NuScenesWriteWithoutRingIsAnError) {
  const std::string path = test::TempDir() + "/cloud.pcd.bin";
  EXPECT_TRUE(ThrowsIoError(
      [&] { WriteKittiBin(path, test::SampleCloud(3, false), BinLayout::kNuScenes5); }, path,
      {"ring"}));
}

TEST(IoKittiBin, SizeNotAWholeNumberOfPoints) {
  const std::string path = test::TempDir() + "/odd.bin";
  WriteRaw(path, std::string(1001, '\0'));
  EXPECT_TRUE(ThrowsIoError([&] { ReadKittiBin(path); }, path,
                            {"size 1001 bytes", "not a whole number of 16-byte points"}));
}

TEST(IoKittiBin, NuScenesSizeMustBeWhole20BytePoints) {
  const std::string path = test::TempDir() + "/odd.pcd.bin";
  WriteRaw(path, std::string(32, '\0'));  // two KITTI points, 1.6 nuScenes points
  EXPECT_TRUE(ThrowsIoError([&] { ReadKittiBin(path, BinLayout::kNuScenes5); }, path,
                            {"size 32 bytes", "20-byte points"}));
}

TEST(IoKittiBin, NuScenesNegativeRing) {
  const std::string path = test::TempDir() + "/neg.pcd.bin";
  WriteRaw(path, Bytes<float>({1, 2, 3, 4, 5, 1, 2, 3, 4, -1}));
  EXPECT_TRUE(ThrowsIoError([&] { ReadKittiBin(path, BinLayout::kNuScenes5); }, path,
                            {"point 1", "ring -1", "whole number >= 0"}));
}

TEST(IoKittiBin, NuScenesFractionalRing) {
  const std::string path = test::TempDir() + "/frac.pcd.bin";
  WriteRaw(path, Bytes<float>({1, 2, 3, 4, 2.5f}));
  EXPECT_TRUE(ThrowsIoError([&] { ReadKittiBin(path, BinLayout::kNuScenes5); }, path,
                            {"point 0", "ring 2.5", "whole number"}));
}

TEST(IoKittiBin, NuScenesNanRing) {
  const std::string path = test::TempDir() + "/nan.pcd.bin";
  WriteRaw(path, Bytes<float>({1, 2, 3, 4, std::numeric_limits<float>::quiet_NaN()}));
  EXPECT_TRUE(
      ThrowsIoError([&] { ReadKittiBin(path, BinLayout::kNuScenes5); }, path, {"ring nan"}));
}

TEST(IoKittiBin, ReadCloudDispatchesOnExtension) {
  const std::string dir = test::TempDir();
  const Cloud cloud = test::SampleCloud(8, true);
  WriteKittiBin(dir + "/a.BIN", cloud, BinLayout::kNuScenes5);
  EXPECT_TRUE(IsCloudFile(dir + "/a.BIN"));
  EXPECT_FALSE(IsCloudFile(dir + "/a.txt"));
  EXPECT_FALSE(IsCloudFile(dir + ".pcd/noext"));
  ReadOptions options;
  options.bin_layout = BinLayout::kNuScenes5;
  EXPECT_TRUE(SameBits(cloud, ReadCloud(dir + "/a.BIN", options)));
  const std::string txt = dir + "/a.txt";
  WriteRaw(txt, "1 2 3\n");
  EXPECT_TRUE(ThrowsIoError([&] { ReadCloud(txt); }, txt, {"unknown cloud file extension"}));
}

TEST(IoKittiBin, NuScenesFilesAreRecognisedByTheirName) {
  const std::string dir = test::TempDir();
  const Cloud cloud = test::SampleCloud(8, true);  // 8 x 20 bytes also divides into 16-byte points
  WriteKittiBin(dir + "/sweep.pcd.bin", cloud, BinLayout::kNuScenes5);
  EXPECT_EQ(BinLayoutFor(dir + "/sweep.pcd.bin", {}), BinLayout::kNuScenes5);
  EXPECT_EQ(BinLayoutFor(dir + "/000001.bin", {}), BinLayout::kKitti4);
  EXPECT_TRUE(SameBits(cloud, ReadCloud(dir + "/sweep.pcd.bin")));
  ReadOptions kitti;
  kitti.bin_layout = BinLayout::kKitti4;  // an explicit layout wins over the name
  EXPECT_EQ(ReadCloud(dir + "/sweep.pcd.bin", kitti).size(), 10u);
}

TEST(IoKittiBin, RealKittiScan) {
  LPIR_REQUIRE_DATA("kitti/07/velodyne/000964.bin");
  const Cloud cloud = ReadKittiBin(test::DataFile("kitti/07/velodyne/000964.bin"));
  ASSERT_EQ(cloud.size(), 120485u);
  EXPECT_TRUE(cloud.ring.empty());
  float min_i = 1e30f, max_i = -1e30f;
  for (size_t i = 0; i < cloud.size(); ++i) {
    ASSERT_TRUE(std::isfinite(cloud.x(i)) && std::isfinite(cloud.y(i)) &&
                std::isfinite(cloud.z(i)));
    min_i = std::min(min_i, cloud.intensity(i));
    max_i = std::max(max_i, cloud.intensity(i));
  }
  // KITTI remission is in [0, 1].
  EXPECT_GE(min_i, 0.0f);
  EXPECT_LE(max_i, 1.0f);
  EXPECT_GT(max_i, 0.5f);
  const Cloud via_dispatch = ReadCloud(test::DataFile("kitti/07/velodyne/000964.bin"));
  EXPECT_TRUE(SameBits(cloud, via_dispatch));
}

TEST(IoKittiBin, RealNuScenesSweep) {
  const std::string name =
      "nuscenes/n015-2018-07-24-11-22-45+0800__LIDAR_TOP__1532402927647951.pcd.bin";
  LPIR_REQUIRE_DATA(name);
  const Cloud cloud = ReadKittiBin(test::DataFile(name), BinLayout::kNuScenes5);
  ASSERT_EQ(cloud.size(), 34688u);
  ASSERT_EQ(cloud.ring.size(), 34688u);
  int32_t min_ring = 1000, max_ring = -1;
  float max_i = 0.0f;
  for (size_t i = 0; i < cloud.size(); ++i) {
    min_ring = std::min(min_ring, cloud.ring[i]);
    max_ring = std::max(max_ring, cloud.ring[i]);
    EXPECT_GE(cloud.intensity(i), 0.0f);
    max_i = std::max(max_i, cloud.intensity(i));
  }
  // HDL-32E: 32 rings; nuScenes intensity is 0..255.
  EXPECT_EQ(min_ring, 0);
  EXPECT_EQ(max_ring, 31);
  EXPECT_LE(max_i, 255.0f);
  EXPECT_GT(max_i, 1.0f);
}

}  // namespace
}  // namespace lpir
