// The ROS 1 serialization of sensor_msgs/PointCloud2: little-endian, no alignment, in field order
//   Header  uint32 seq, time stamp (uint32 sec, uint32 nsec), string frame_id
//   uint32 height, uint32 width
//   PointField[] fields: uint32 count, each {string name, uint32 offset, uint8 datatype,
//                                            uint32 count}
//   bool is_bigendian, uint32 point_step, uint32 row_step, uint8[] data, bool is_dense
// where a string and an array are a uint32 length then the bytes, a bool is one byte 0 or 1.
// Parsing is strict: every length is checked against the bytes left before anything is allocated,
// a bool must be 0 or 1, and the message must end exactly after is_dense. A stamp of more than
// INT32_MAX seconds (after January 2038) is rejected: PointCloud2::stamp_sec is the int32 of ROS 2,
// and a wrapped negative stamp would be silent garbage.
#include <limits>
#include <stdexcept>

#include "host/drive/pointcloud2.h"
#include "host/io/io_error.h"

namespace lpir {
namespace {

// Reads the message front to back; every read names what it reads when the bytes run out.
class Ros1Cursor {
 public:
  Ros1Cursor(const std::string& where, const uint8_t* bytes, size_t size)
      : where_(where), bytes_(bytes), size_(size) {}

  uint32_t U32(const char* what) {
    Need(4, what);
    uint32_t v = uint32_t(bytes_[pos_]) | uint32_t(bytes_[pos_ + 1]) << 8 |
                 uint32_t(bytes_[pos_ + 2]) << 16 | uint32_t(bytes_[pos_ + 3]) << 24;
    pos_ += 4;
    return v;
  }
  uint8_t U8(const char* what) {
    Need(1, what);
    return bytes_[pos_++];
  }
  bool Bool(const char* what) {
    const size_t at = pos_;
    const uint8_t v = U8(what);
    if (v > 1) Fail(at, std::string(what) + " is " + std::to_string(v) + ", not a bool (0 or 1)");
    return v == 1;
  }
  std::string String(const char* what) {
    const size_t n = Length(1, what);
    std::string s(reinterpret_cast<const char*>(bytes_ + pos_), n);
    pos_ += n;
    return s;
  }
  // An array length, checked against the bytes left at `min_element_size` bytes an element.
  size_t Length(size_t min_element_size, const char* what) {
    const size_t at = pos_;
    const uint32_t n = U32(what);
    if (uint64_t(n) * min_element_size > size_ - pos_)
      Fail(at, std::string(what) + " claims " + std::to_string(n) + " elements, only " +
                   std::to_string(size_ - pos_) + " bytes are left");
    return n;
  }
  const uint8_t* Take(size_t n) {
    const uint8_t* p = bytes_ + pos_;
    pos_ += n;
    return p;
  }
  void End() {
    if (pos_ != size_)
      Fail(pos_, std::to_string(size_ - pos_) + " bytes after the end of the message");
  }
  size_t pos() const { return pos_; }
  [[noreturn]] void Fail(size_t at, const std::string& what) const {
    throw IoError(where_, "ROS 1 PointCloud2, byte " + std::to_string(at) + ": " + what);
  }

 private:
  void Need(size_t n, const char* what) const {
    if (size_ - pos_ < n)
      Fail(pos_,
           std::string("message ends inside ") + what + " (" + std::to_string(size_) + " bytes)");
  }

  const std::string& where_;
  const uint8_t* bytes_;
  size_t size_;
  size_t pos_ = 0;
};

void PutU32(std::vector<uint8_t>* out, uint32_t v) {
  for (int k = 0; k < 4; ++k) out->push_back(uint8_t(v >> (8 * k)));
}
void PutString(std::vector<uint8_t>* out, const std::string& s) {
  if (s.size() > std::numeric_limits<uint32_t>::max())
    throw std::invalid_argument("ROS 1 PointCloud2: a string longer than 4 GiB");
  PutU32(out, uint32_t(s.size()));
  out->insert(out->end(), s.begin(), s.end());
}

}  // namespace

PointCloud2 ParseRos1PointCloud2(const std::string& where, const uint8_t* bytes, size_t size) {
  Ros1Cursor in(where, bytes, size);
  PointCloud2 cloud;
  cloud.seq = in.U32("header.seq");
  const size_t sec_at = in.pos();
  const uint32_t sec = in.U32("header.stamp.sec");
  if (sec > uint32_t(std::numeric_limits<int32_t>::max()))
    in.Fail(sec_at, "header.stamp.sec " + std::to_string(sec) + " is past INT32_MAX");
  cloud.stamp_sec = int32_t(sec);
  cloud.stamp_nanosec = in.U32("header.stamp.nsec");
  cloud.frame_id = in.String("header.frame_id");
  cloud.height = in.U32("height");
  cloud.width = in.U32("width");
  // A PointField takes at least 13 bytes (empty name, offset, datatype, count).
  const size_t field_count = in.Length(13, "fields");
  cloud.fields.resize(field_count);
  for (PointField& f : cloud.fields) {
    f.name = in.String("fields[].name");
    f.offset = in.U32("fields[].offset");
    f.datatype = in.U8("fields[].datatype");
    f.count = in.U32("fields[].count");
  }
  cloud.is_bigendian = in.Bool("is_bigendian");
  cloud.point_step = in.U32("point_step");
  cloud.row_step = in.U32("row_step");
  const size_t data_size = in.Length(1, "data");
  const uint8_t* data = in.Take(data_size);
  cloud.data.assign(data, data + data_size);
  cloud.is_dense = in.Bool("is_dense");
  in.End();
  return cloud;
}

// std::invalid_argument for what ROS 1 cannot hold: a negative stamp_sec, a string or data of
// 4 GiB or more.
std::vector<uint8_t> SerializeRos1PointCloud2(const PointCloud2& cloud) {
  if (cloud.stamp_sec < 0)
    throw std::invalid_argument("ROS 1 PointCloud2: a negative stamp has no ROS 1 time");
  if (cloud.data.size() > std::numeric_limits<uint32_t>::max() ||
      cloud.fields.size() > std::numeric_limits<uint32_t>::max())
    throw std::invalid_argument("ROS 1 PointCloud2: data or fields of 4 GiB or more");
  std::vector<uint8_t> out;
  out.reserve(64 + cloud.frame_id.size() + 24 * cloud.fields.size() + cloud.data.size());
  PutU32(&out, cloud.seq);
  PutU32(&out, uint32_t(cloud.stamp_sec));
  PutU32(&out, cloud.stamp_nanosec);
  PutString(&out, cloud.frame_id);
  PutU32(&out, cloud.height);
  PutU32(&out, cloud.width);
  PutU32(&out, uint32_t(cloud.fields.size()));
  for (const PointField& f : cloud.fields) {
    PutString(&out, f.name);
    PutU32(&out, f.offset);
    out.push_back(f.datatype);
    PutU32(&out, f.count);
  }
  out.push_back(cloud.is_bigendian ? 1 : 0);
  PutU32(&out, cloud.point_step);
  PutU32(&out, cloud.row_step);
  PutU32(&out, uint32_t(cloud.data.size()));
  out.insert(out.end(), cloud.data.begin(), cloud.data.end());
  out.push_back(cloud.is_dense ? 1 : 0);
  return out;
}

}  // namespace lpir
