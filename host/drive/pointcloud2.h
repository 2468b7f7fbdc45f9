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

// Parses a CDR-serialized message (4-byte encapsulation header: CDR_BE {0,0} or CDR_LE {0,1},
// the two option bytes ignored; primitives aligned to their size relative to the byte after the
// header; a string's uint32 length counts its NUL, 0 reads as empty). Up to 7 bytes after
// is_dense are accepted as padding. IoError naming `where` for another encapsulation, a
// truncated message, a length or count that overruns the bytes left (checked before anything is
// allocated), a string without its NUL, a bool other than 0 or 1, or more trailing bytes.
PointCloud2 ParseCdrPointCloud2(const std::string& where, const uint8_t* bytes, size_t size);
std::vector<uint8_t> SerializeCdrPointCloud2(const PointCloud2& cloud);
// The ROS 1 serialization (little-endian, no alignment, header seq stamp frame_id).
PointCloud2 ParseRos1PointCloud2(const std::string& where, const uint8_t* bytes, size_t size);
std::vector<uint8_t> SerializeRos1PointCloud2(const PointCloud2& cloud);

// The points as a Cloud, row by row (point (r, c) at r x row_step + c x point_step): x, y, z
// (float32 or float64, count 1, read as float), the intensity under the best of
// IntensityNames() present (host/io/point_fields.h; any type, count 1, converted to float; 0
// when none), and ring when present (count 1,
// any integer type, or a float holding a whole number; every value must be in [0, INT32_MAX]).
// is_bigendian is honoured. Every point is kept (NaN included: the segmenter marks it invalid).
// IoError naming `where` when a field's datatype is not 1-8, a used field appears twice or has
// count != 1, x, y or z is missing or not a float type, or a ring value is not a whole number
// >= 0; and, when width x height > 0, when point_step is 0, a field's offset + size x count
// overruns point_step, row_step < width x point_step, or data does not hold exactly
// row_step x height bytes (extra bytes would mean the declared layout is not the data's). With
// no points only the fields are checked. Sizes are multiplied in 64 bits from 32-bit factors.
Cloud CloudFromPointCloud2(const std::string& where, const PointCloud2& cloud);

// What segment --format mcap|bag adds for a labelled message (docs/decisions/drives.md), each a
// PointCloud2 with the message's header (seq, stamp, frame_id), is_bigendian and is_dense:
//   labelled   every point, in order, with the message's height and width (an organised cloud
//              stays organised), its fields re-laid (AlignedFields) and a uint32 field `label`
//              (1 ground, 0 non-ground: the .label files' values) after them;
//   ground     the points labelled 1, in order, height 1, the re-laid fields without `label`;
//   nonground  the points labelled 0, likewise.
// Each field's bytes are copied unchanged (the message's byte order; bytes that no field covers
// are dropped), rows packed (row_step = width x point_step).
struct LabelledClouds {
  PointCloud2 labelled, ground, nonground;
};
// IoError naming `where` unless labels has one entry per point, for a message that has a `label`
// field already, for the layout errors CloudFromPointCloud2 reports when there are points, for
// fields whose sizes add up past point_step (they overlap), or when a row_step does not fit in 32
// bits.
LabelledClouds SplitByLabel(const std::string& where, const PointCloud2& cloud,
                            const Labels& labels);

// `fields` laid out again in the order listed, each at the next offset that is a multiple of its
// datatype's size, then `extra` fields of 4 bytes (uint32); *point_step: the end of the last one
// rounded up to the largest field size (4 at least), so that every field of every point stays
// aligned. (PointCloud2 fields have no alignment rule, and drivers pack them: a VLP-16's ring is a
// uint16 at 16 with a float time at 18.)
std::vector<PointField> AlignedFields(const std::vector<PointField>& fields,
                                      const std::vector<std::string>& extra, uint64_t* point_step);

}  // namespace lpir
