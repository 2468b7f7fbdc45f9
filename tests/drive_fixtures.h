// The committed recorded-drive fixtures (tests/data/drives/, written by independent writers:
// scripts/make_drive_fixtures.sh) and what the drive tests share about them.
#pragma once
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "reference_cpu/cloud.h"
#include "tests/io_test_helpers.h"
#include "tests/test_util.h"

namespace lpir::test {

// What every fixture drive holds: the frames on this topic, frame i stamped kFirstStampNs + i x
// 100 ms (scripts/make_drive_fixtures.sh).
constexpr char kFixtureTopic[] = "/velodyne_points";
constexpr long long kFirstStampNs = 1600000000LL * 1000000000LL;
constexpr size_t kFixtureFrames = 3;

// tests/data/drives, or $LPIR_TEST_DATA_DIR/drives.
inline std::string DrivesDir() {
  return EnvOr("LPIR_TEST_DATA_DIR", LPIR_TEST_DATA_DIR) + std::string("/drives");
}

// "<DrivesDir>/frames/<i %06>": the .bin (float32 x y z intensity) and .ring (uint16 per point)
// of fixture frame i, without the extension.
inline std::string FixtureFrameBase(size_t i) {
  char name[16];
  std::snprintf(name, sizeof(name), "%06zu", i);
  return DrivesDir() + "/frames/" + name;
}

// "<DrivesDir>/narrow/<i %06>": fixture frame i cut to the 11.25 degrees ahead, as the drives
// of several files (bag folders, the killed ROS 1 bag) hold it.
inline std::string NarrowFrameBase(size_t i) {
  char name[16];
  std::snprintf(name, sizeof(name), "%06zu", i);
  return DrivesDir() + "/narrow/" + name;
}

// The frame at `base` as the writers wrote it: base.bin's floats and base.ring's uint16 values.
inline Cloud FrameAt(const std::string& base) {
  const std::string bin = ReadRaw(base + ".bin");
  const std::string ring = ReadRaw(base + ".ring");
  Cloud cloud;
  cloud.xyzi.resize(bin.size() / 4);
  std::memcpy(cloud.xyzi.data(), bin.data(), cloud.xyzi.size() * 4);
  for (size_t k = 0; k + 1 < ring.size(); k += 2)
    cloud.ring.push_back(int32_t(uint8_t(ring[k])) | int32_t(uint8_t(ring[k + 1])) << 8);
  return cloud;
}

// Fixture frame i, whole or narrow.
inline Cloud FixtureFrame(size_t i) { return FrameAt(FixtureFrameBase(i)); }
inline Cloud NarrowFrame(size_t i) { return FrameAt(NarrowFrameBase(i)); }

// The .label files in `dir`, by name ({} when it cannot be listed).
inline std::vector<std::string> LabelFiles(const std::string& dir) {
  std::vector<std::string> names;
  std::error_code ec;
  for (const auto& e : std::filesystem::directory_iterator(dir, ec))
    if (e.path().extension() == ".label") names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

}  // namespace lpir::test
