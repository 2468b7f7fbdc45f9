// sensor_msgs/PointCloud2: the message, its two serializations (ROS 2 CDR, ROS 1) and the
// decoding of its point records into a Cloud.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "reference_cpu/cloud.h"

namespace lpir {

// sensor_msgs/PointField datatype values.
enum PointFieldType : uint8_t {
  kPfInt8 = 1,
  kPfUint8 = 2,
  kPfInt16 = 3,
  kPfUint16 = 4,
  kPfInt32 = 5,
  kPfUint32 = 6,
  kPfFloat32 = 7,
  kPfFloat64 = 8,
};

struct PointField {
  std::string name;
  uint32_t offset = 0;
  uint8_t datatype = kPfFloat32;
  uint32_t count = 1;
};

struct PointCloud2 {
  // std_msgs/Header (ROS 1 adds seq, kept so that a ROS 1 message serializes back unchanged)
  uint32_t seq = 0;
  int32_t stamp_sec = 0;
  uint32_t stamp_nanosec = 0;
  std::string frame_id;
  uint32_t height = 1, width = 0;
  std::vector<PointField> fields;
  bool is_bigendian = false;
  uint32_t point_step = 0, row_step = 0;
  std::vector<uint8_t> data;
  bool is_dense = false;

  int64_t stamp_ns() const { return int64_t(stamp_sec) * 1000000000 + stamp_nanosec; }
};

// Parses a CDR-serialized message (4-byte encapsulation header: CDR_BE or CDR_LE, alignment
// relative to the byte after it). IoError naming `where` for a bad header, a truncated message or
// a length that overruns it.
PointCloud2 ParseCdrPointCloud2(const std::string& where, const uint8_t* bytes, size_t size);
// CDR_LE with the encapsulation header; ParseCdrPointCloud2 reads it back equal.
std::vector<uint8_t> SerializeCdrPointCloud2(const PointCloud2& cloud);
// The ROS 1 serialization (little-endian, no alignment, header seq stamp frame_id).
PointCloud2 ParseRos1PointCloud2(const std::string& where, const uint8_t* bytes, size_t size);
std::vector<uint8_t> SerializeRos1PointCloud2(const PointCloud2& cloud);

// The points as a Cloud, row by row, point_step bytes apart: x, y, z (float32 or float64, read
// as float), the first of intensity / reflectivity / i present (any numeric type, converted to
// float; 0 when none), and ring when present (any integer type, or a float holding a whole
// number >= 0). is_bigendian is honoured. IoError naming `where` when x, y or z is missing or is
// not a float type, a field overruns point_step, width x height overflows or data holds fewer
// than row_step x height bytes, row_step < width x point_step, or a ring value is not a whole
// number >= 0. Every point is kept (NaN included: the segmenter marks it invalid).
Cloud CloudFromPointCloud2(const std::string& where, const PointCloud2& cloud);

// `cloud` with a uint8 `label` field (1 ground, 0 non-ground) appended to every point record:
// point_step grows by one byte, the records are re-packed densely (row_step = width x
// point_step), everything else is kept. IoError naming `where` unless labels has one entry per
// point.
PointCloud2 AddLabelField(const std::string& where, const PointCloud2& cloud, const Labels& labels);

}  // namespace lpir
