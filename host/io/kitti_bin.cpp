// KITTI Velodyne .bin (4 float32 per point) and nuScenes .pcd.bin (5, the fifth the ring).
#include "host/io/kitti_bin.h"

#include <cstring>
#include <string>
#include <vector>

#include "host/io/file_bytes.h"
#include "host/io/io_error.h"
#include "host/io/point_fields.h"

namespace lpir {

namespace {

size_t FloatsPerPoint(BinLayout layout) { return layout == BinLayout::kNuScenes5 ? 5 : 4; }

}  // namespace

Cloud ReadKittiBin(const std::string& path, BinLayout layout) {
  const size_t stride = FloatsPerPoint(layout) * sizeof(float);
  auto check = [&](size_t size) {
    if (size == 0) throw IoError(path, "empty file");
    if (size % stride != 0) {
      throw IoError(path, "size " + std::to_string(size) + " bytes is not a whole number of " +
                              std::to_string(stride) + "-byte points");
    }
  };
  Cloud cloud;
  if (layout == BinLayout::kKitti4) {  // the file's bytes are the xyzi layout: read in place
    ReadFileInto(path, [&](size_t size) {
      check(size);
      cloud.xyzi.resize(size / sizeof(float));
      return reinterpret_cast<char*>(cloud.xyzi.data());
    });
    return cloud;
  }
  const std::vector<char> bytes = ReadFileBytes(path);
  check(bytes.size());
  const size_t n = bytes.size() / stride;
  cloud.xyzi.resize(4 * n);
  cloud.ring.resize(n);
  for (size_t i = 0; i < n; ++i) {
    const char* point = bytes.data() + i * stride;
    std::memcpy(&cloud.xyzi[4 * i], point, 4 * sizeof(float));
    float ring_value;
    std::memcpy(&ring_value, point + 4 * sizeof(float), sizeof(float));
    if (!RingFromValue(ring_value, &cloud.ring[i])) {
      throw IoError(path, "point " + std::to_string(i) + " has ring " + FloatText(ring_value) +
                              ", not a whole number >= 0");
    }
  }
  return cloud;
}

void WriteKittiBin(const std::string& path, const Cloud& cloud) {
  WriteKittiBin(path, cloud, BinLayout::kKitti4);
}

void WriteKittiBin(const std::string& path, const Cloud& cloud, BinLayout layout) {
  if (layout == BinLayout::kKitti4) {
    WriteFileBytes(path, cloud.xyzi.data(), cloud.xyzi.size() * sizeof(float));
    return;
  }
  const size_t n = cloud.size();
  if (cloud.ring.size() != n) {
    throw IoError(path, "cannot write the nuScenes layout: the cloud has " + std::to_string(n) +
                            " points but " + std::to_string(cloud.ring.size()) + " ring values");
  }
  std::vector<float> out(5 * n);
  for (size_t i = 0; i < n; ++i) {
    std::memcpy(&out[5 * i], &cloud.xyzi[4 * i], 4 * sizeof(float));
    out[5 * i + 4] = static_cast<float>(cloud.ring[i]);
  }
  WriteFileBytes(path, out.data(), out.size() * sizeof(float));
}

}  // namespace lpir
