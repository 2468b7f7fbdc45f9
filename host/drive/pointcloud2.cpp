// sensor_msgs/PointCloud2 in ROS 2 CDR (XCDR1 plain CDR: primitives aligned to their size,
// counted from the byte after the 4-byte encapsulation header), and the decoding of its point
// records into a Cloud. The ROS 1 serialization is in pointcloud2_ros1.cpp.
#include "host/drive/pointcloud2.h"

#include <algorithm>
#include <cstring>
#include <limits>

#include "host/io/io_error.h"
#include "host/io/point_fields.h"

namespace lpir {

namespace {

constexpr size_t kCdrHeaderBytes = 4;
// Bytes after is_dense that a message may carry: padding up to the widest CDR alignment (8),
// which some middlewares append.
constexpr size_t kMaxTrailingBytes = 7;
// The fewest bytes one PointField takes in CDR: name length (4), offset (4), datatype (1),
// padding (3), count (4); every element starts 4-aligned, so this holds for each.
constexpr size_t kMinFieldBytes = 16;

// Reads CDR primitives from [bytes, bytes + size), every read checked against the bytes left.
class CdrCursor {
 public:
  CdrCursor(const std::string& where, const uint8_t* bytes, size_t size, bool big_endian)
      : where_(where), bytes_(bytes), size_(size), big_endian_(big_endian) {}

  uint8_t U8(const char* what) {
    Need(1, what);
    return bytes_[pos_++];
  }
  bool Bool(const char* what) {
    const uint8_t value = U8(what);
    if (value > 1) Fail(std::string(what) + " is " + std::to_string(value) + ", not 0 or 1");
    return value == 1;
  }
  uint32_t U32(const char* what) {
    Align(4, what);
    Need(4, what);
    const uint8_t* p = bytes_ + pos_;
    pos_ += 4;
    if (big_endian_)
      return uint32_t(p[0]) << 24 | uint32_t(p[1]) << 16 | uint32_t(p[2]) << 8 | p[3];
    return uint32_t(p[3]) << 24 | uint32_t(p[2]) << 16 | uint32_t(p[1]) << 8 | p[0];
  }
  // A CDR string: uint32 length counting the terminating NUL, the bytes, the NUL. A length of 0
  // (no NUL at all) reads as the empty string.
  std::string String(const char* what) {
    const uint32_t length = U32(what);
    if (length == 0) return std::string();
    if (length > Left()) {
      Fail(std::string(what) + " length " + std::to_string(length) + " overruns the message (" +
           std::to_string(Left()) + " bytes left)");
    }
    const char* text = reinterpret_cast<const char*>(bytes_ + pos_);
    pos_ += length;
    if (text[length - 1] != '\0') Fail(std::string(what) + " does not end with a NUL");
    return std::string(text, length - 1);
  }
  // The element count of a sequence whose elements take at least `min_element_bytes` each.
  uint32_t Count(const char* what, size_t min_element_bytes) {
    const uint32_t count = U32(what);
    if (count > Left() / min_element_bytes) {
      Fail(std::string(what) + " count " + std::to_string(count) + " overruns the message (" +
           std::to_string(Left()) + " bytes left)");
    }
    return count;
  }
  void Bytes(uint32_t count, std::vector<uint8_t>* out) {
    out->assign(bytes_ + pos_, bytes_ + pos_ + count);  // Count checked count <= Left()
    pos_ += count;
  }
  size_t Left() const { return size_ - pos_; }
  [[noreturn]] void Fail(const std::string& problem) const {
    throw IoError(where_, "PointCloud2 CDR: " + problem + " (byte " + std::to_string(pos_) + ")");
  }

 private:
  void Align(size_t n, const char* what) {
    const size_t pad = (n - (pos_ - kCdrHeaderBytes) % n) % n;
    Need(pad, what);
    pos_ += pad;
  }
  void Need(size_t n, const char* what) {
    if (n > Left()) {
      Fail(std::string("truncated in ") + what + " (" + std::to_string(Left()) + " bytes left, " +
           std::to_string(n) + " needed)");
    }
  }

  const std::string& where_;
  const uint8_t* bytes_;
  size_t size_;
  size_t pos_ = kCdrHeaderBytes;
  bool big_endian_;
};

// Appends CDR_LE primitives, aligned as CdrCursor reads them.
class CdrWriter {
 public:
  CdrWriter() : out_{0x00, 0x01, 0x00, 0x00} {}
  void U8(uint8_t value) { out_.push_back(value); }
  void U32(uint32_t value) {
    while ((out_.size() - kCdrHeaderBytes) % 4 != 0) out_.push_back(0);
    for (int shift = 0; shift < 32; shift += 8) out_.push_back(uint8_t(value >> shift));
  }
  void String(const std::string& text) {
    U32(uint32_t(text.size() + 1));
    out_.insert(out_.end(), text.begin(), text.end());
    out_.push_back(0);
  }
  std::vector<uint8_t> Take() { return std::move(out_); }

 private:
  std::vector<uint8_t> out_;
};

size_t PointFieldSize(uint8_t datatype) {
  switch (datatype) {
    case kPfInt8:
    case kPfUint8:
      return 1;
    case kPfInt16:
    case kPfUint16:
      return 2;
    case kPfInt32:
    case kPfUint32:
    case kPfFloat32:
      return 4;
    case kPfFloat64:
      return 8;
  }
  return 0;
}

const char* PointFieldTypeName(uint8_t datatype) {
  switch (datatype) {
    case kPfInt8:
      return "int8";
    case kPfUint8:
      return "uint8";
    case kPfInt16:
      return "int16";
    case kPfUint16:
      return "uint16";
    case kPfInt32:
      return "int32";
    case kPfUint32:
      return "uint32";
    case kPfFloat32:
      return "float32";
    case kPfFloat64:
      return "float64";
  }
  return "?";
}

// A T stored at p, big- or little-endian.
template <typename T, bool kBig>
T Load(const uint8_t* p) {
  uint8_t b[sizeof(T)];
  for (size_t k = 0; k < sizeof(T); ++k) b[k] = kBig ? p[sizeof(T) - 1 - k] : p[k];
  T value;
  std::memcpy(&value, b, sizeof(T));
  return value;
}
template <typename T, bool kBig>
double LoadDouble(const uint8_t* p) {
  return static_cast<double>(Load<T, kBig>(p));  // exact for every PointField type
}
template <typename T, bool kBig>
float LoadFloat(const uint8_t* p) {
  return static_cast<float>(Load<T, kBig>(p));  // float32: the very bits (NaN payloads kept)
}

// Reader<T, kBig>::get for ReaderFor: the loader of a stored T as double (ring) or float.
template <typename T, bool kBig>
struct DoubleReader {
  static constexpr double (*get)(const uint8_t*) = LoadDouble<T, kBig>;
};
template <typename T, bool kBig>
struct FloatReader {
  static constexpr float (*get)(const uint8_t*) = LoadFloat<T, kBig>;
};
using DoubleFn = double(const uint8_t*);
using FloatFn = float(const uint8_t*);

// The reader of one field's values, chosen once per message rather than per value (datatype
// already checked to be 1-8: anything else is float64).
template <typename R, template <typename, bool> class Reader>
R* ReaderFor(uint8_t datatype, bool big) {
  switch (datatype) {
    case kPfInt8:
      return big ? Reader<int8_t, true>::get : Reader<int8_t, false>::get;
    case kPfUint8:
      return big ? Reader<uint8_t, true>::get : Reader<uint8_t, false>::get;
    case kPfInt16:
      return big ? Reader<int16_t, true>::get : Reader<int16_t, false>::get;
    case kPfUint16:
      return big ? Reader<uint16_t, true>::get : Reader<uint16_t, false>::get;
    case kPfInt32:
      return big ? Reader<int32_t, true>::get : Reader<int32_t, false>::get;
    case kPfUint32:
      return big ? Reader<uint32_t, true>::get : Reader<uint32_t, false>::get;
    case kPfFloat32:
      return big ? Reader<float, true>::get : Reader<float, false>::get;
    default:
      return big ? Reader<double, true>::get : Reader<double, false>::get;
  }
}

// The fields that feed the Cloud; nullptr when absent (intensity, ring).
struct FieldRoles {
  const PointField* xyz[3] = {nullptr, nullptr, nullptr};
  const PointField* intensity = nullptr;
  const PointField* ring = nullptr;
};

// Checks every field's datatype and picks the roles: IoError naming `where` for a datatype
// outside 1-8, a used field (x, y, z, the intensity, ring) that appears twice or has count != 1,
// or x, y or z missing or not float32/float64. A ring of any type is accepted here; its values
// are checked per point.
FieldRoles AssignRoles(const std::string& where, const PointCloud2& cloud) {
  FieldRoles roles;
  int intensity_rank = -1;
  for (const PointField& field : cloud.fields)
    intensity_rank = BetterIntensityRank(intensity_rank, field.name);
  for (const PointField& field : cloud.fields) {
    if (PointFieldSize(field.datatype) == 0) {
      throw IoError(where, "PointCloud2 field " + Quote(field.name) + " has datatype " +
                               std::to_string(field.datatype) + ", not a PointField type (1-8)");
    }
    const PointField** slot = nullptr;
    if (field.name == "x") slot = &roles.xyz[0];
    if (field.name == "y") slot = &roles.xyz[1];
    if (field.name == "z") slot = &roles.xyz[2];
    if (field.name == "ring") slot = &roles.ring;
    if (intensity_rank >= 0 && IntensityRank(field.name) == intensity_rank) slot = &roles.intensity;
    if (!slot) continue;
    if (*slot) throw IoError(where, "PointCloud2 field " + Quote(field.name) + " appears twice");
    if (field.count != 1) {
      throw IoError(where, "PointCloud2 field " + Quote(field.name) + " has count " +
                               std::to_string(field.count) + "; it must be 1");
    }
    *slot = &field;
  }
  for (int axis = 0; axis < 3; ++axis) {
    const char* name = axis == 0 ? "x" : axis == 1 ? "y" : "z";
    const PointField* field = roles.xyz[axis];
    if (!field) throw IoError(where, std::string("PointCloud2 has no ") + Quote(name) + " field");
    if (field->datatype != kPfFloat32 && field->datatype != kPfFloat64) {
      throw IoError(where, std::string("PointCloud2 field ") + Quote(name) + " is " +
                               PointFieldTypeName(field->datatype) +
                               "; x, y and z must be float32 or float64");
    }
  }
  return roles;
}

// The byte layout checks both CloudFromPointCloud2 and SplitByLabel need before reading
// records, for a cloud of `points` > 0 points: IoError naming `where` for point_step 0, a field
// that overruns point_step, row_step < width x point_step, or data not holding exactly
// row_step x height bytes. Products are taken in 64 bits (from 32-bit factors: no overflow).
void CheckRecords(const std::string& where, const PointCloud2& cloud) {
  if (cloud.point_step == 0) throw IoError(where, "PointCloud2 point_step is 0 with points");
  for (const PointField& field : cloud.fields) {
    const uint64_t end =
        uint64_t(field.offset) + uint64_t(PointFieldSize(field.datatype)) * uint64_t(field.count);
    if (end > cloud.point_step) {
      throw IoError(where, "PointCloud2 field " + Quote(field.name) + " (offset " +
                               std::to_string(field.offset) + ", " + std::to_string(field.count) +
                               " x " + PointFieldTypeName(field.datatype) +
                               ") overruns point_step " + std::to_string(cloud.point_step));
    }
  }
  const uint64_t row_bytes = uint64_t(cloud.width) * cloud.point_step;
  if (cloud.row_step < row_bytes) {
    throw IoError(where, "PointCloud2 row_step " + std::to_string(cloud.row_step) + " < width " +
                             std::to_string(cloud.width) + " x point_step " +
                             std::to_string(cloud.point_step));
  }
  const uint64_t data_bytes = uint64_t(cloud.row_step) * cloud.height;
  if (cloud.data.size() != data_bytes) {
    throw IoError(where, "PointCloud2 data holds " + std::to_string(cloud.data.size()) +
                             " bytes; height " + std::to_string(cloud.height) + " x row_step " +
                             std::to_string(cloud.row_step) + " = " + std::to_string(data_bytes));
  }
}

}  // namespace

PointCloud2 ParseCdrPointCloud2(const std::string& where, const uint8_t* bytes, size_t size) {
  if (size < kCdrHeaderBytes) {
    throw IoError(where, "PointCloud2 CDR: " + std::to_string(size) +
                             " bytes, fewer than the 4-byte encapsulation header");
  }
  if (bytes[0] != 0x00 || bytes[1] > 0x01) {
    throw IoError(where, "PointCloud2 CDR: encapsulation " + std::to_string(bytes[0]) + "," +
                             std::to_string(bytes[1]) +
                             " is not plain CDR (0,0 big-endian or 0,1 little-endian)");
  }
  CdrCursor in(where, bytes, size, bytes[1] == 0x00);
  PointCloud2 cloud;
  cloud.stamp_sec = int32_t(in.U32("header.stamp.sec"));
  cloud.stamp_nanosec = in.U32("header.stamp.nanosec");
  cloud.frame_id = in.String("header.frame_id");
  cloud.height = in.U32("height");
  cloud.width = in.U32("width");
  const uint32_t fields = in.Count("fields", kMinFieldBytes);
  cloud.fields.resize(fields);
  for (PointField& field : cloud.fields) {
    field.name = in.String("field name");
    field.offset = in.U32("field offset");
    field.datatype = in.U8("field datatype");
    field.count = in.U32("field count");
  }
  cloud.is_bigendian = in.Bool("is_bigendian");
  cloud.point_step = in.U32("point_step");
  cloud.row_step = in.U32("row_step");
  in.Bytes(in.Count("data", 1), &cloud.data);
  cloud.is_dense = in.Bool("is_dense");
  if (in.Left() > kMaxTrailingBytes) {
    in.Fail(std::to_string(in.Left()) + " bytes after the message's end");
  }
  return cloud;
}

std::vector<uint8_t> SerializeCdrPointCloud2(const PointCloud2& cloud) {
  CdrWriter out;
  out.U32(uint32_t(cloud.stamp_sec));
  out.U32(cloud.stamp_nanosec);
  out.String(cloud.frame_id);
  out.U32(cloud.height);
  out.U32(cloud.width);
  out.U32(uint32_t(cloud.fields.size()));
  for (const PointField& field : cloud.fields) {
    out.String(field.name);
    out.U32(field.offset);
    out.U8(field.datatype);
    out.U32(field.count);
  }
  out.U8(cloud.is_bigendian ? 1 : 0);
  out.U32(cloud.point_step);
  out.U32(cloud.row_step);
  out.U32(uint32_t(cloud.data.size()));
  std::vector<uint8_t> bytes = out.Take();
  bytes.insert(bytes.end(), cloud.data.begin(), cloud.data.end());
  bytes.push_back(cloud.is_dense ? 1 : 0);
  return bytes;
}

Cloud CloudFromPointCloud2(const std::string& where, const PointCloud2& cloud) {
  const FieldRoles roles = AssignRoles(where, cloud);
  const uint64_t points = uint64_t(cloud.width) * cloud.height;
  Cloud out;
  if (points == 0) return out;
  CheckRecords(where, cloud);  // bounds points by data.size() / point_step
  const bool big = cloud.is_bigendian;
  FloatFn* const xyz_read[3] = {ReaderFor<FloatFn, FloatReader>(roles.xyz[0]->datatype, big),
                                ReaderFor<FloatFn, FloatReader>(roles.xyz[1]->datatype, big),
                                ReaderFor<FloatFn, FloatReader>(roles.xyz[2]->datatype, big)};
  const uint32_t xyz_at[3] = {roles.xyz[0]->offset, roles.xyz[1]->offset, roles.xyz[2]->offset};
  FloatFn* const intensity_read =
      roles.intensity ? ReaderFor<FloatFn, FloatReader>(roles.intensity->datatype, big) : nullptr;
  DoubleFn* const ring_read =
      roles.ring ? ReaderFor<DoubleFn, DoubleReader>(roles.ring->datatype, big) : nullptr;
  out.xyzi.resize(points * 4);
  if (roles.ring) out.ring.resize(points);
  // The layout drivers publish (x, y, z and intensity float32, little-endian: the host's, as Load
  // takes it) is read by plain copies, which compile to loads; any other by the field readers.
  const bool plain = !big && roles.intensity && roles.intensity->datatype == kPfFloat32 &&
                     roles.xyz[0]->datatype == kPfFloat32 && roles.xyz[1]->datatype == kPfFloat32 &&
                     roles.xyz[2]->datatype == kPfFloat32;
  const uint32_t intensity_at = roles.intensity ? roles.intensity->offset : 0;
  size_t i = 0;
  for (uint32_t row = 0; row < cloud.height; ++row) {
    const uint8_t* record = cloud.data.data() + uint64_t(row) * cloud.row_step;
    for (uint32_t col = 0; col < cloud.width; ++col, ++i, record += cloud.point_step) {
      float* xyzi = &out.xyzi[4 * i];
      if (plain) {
        std::memcpy(&xyzi[0], record + xyz_at[0], 4);
        std::memcpy(&xyzi[1], record + xyz_at[1], 4);
        std::memcpy(&xyzi[2], record + xyz_at[2], 4);
        std::memcpy(&xyzi[3], record + intensity_at, 4);
      } else {
        xyzi[0] = xyz_read[0](record + xyz_at[0]);
        xyzi[1] = xyz_read[1](record + xyz_at[1]);
        xyzi[2] = xyz_read[2](record + xyz_at[2]);
        xyzi[3] = intensity_read ? intensity_read(record + intensity_at) : 0.0f;
      }
      if (ring_read) {
        const double value = ring_read(record + roles.ring->offset);
        if (!RingFromValue(value, &out.ring[i])) {
          throw IoError(where, "PointCloud2 point " + std::to_string(i) + " has ring " +
                                   FloatText(value) + ", not a whole number >= 0");
        }
      }
    }
  }
  return out;
}

std::vector<PointField> AlignedFields(const std::vector<PointField>& fields,
                                      const std::vector<std::string>& extra, uint64_t* point_step) {
  std::vector<PointField> out;
  uint64_t at = 0, widest = 4;
  const auto place = [&](const PointField& field) {
    const uint64_t size = std::max<uint64_t>(PointFieldSize(field.datatype), 1);
    at = (at + size - 1) / size * size;
    out.push_back(PointField{field.name, uint32_t(at), field.datatype, field.count});
    at += size * field.count;
    widest = std::max(widest, size);
  };
  for (const PointField& field : fields) place(field);
  for (const std::string& name : extra) place(PointField{name, 0, kPfUint32, 1});
  *point_step = (at + widest - 1) / widest * widest;
  return out;
}

LabelledClouds SplitByLabel(const std::string& where, const PointCloud2& cloud,
                            const Labels& labels) {
  const uint64_t points = uint64_t(cloud.width) * cloud.height;
  if (labels.size() != points) {
    throw IoError(where, std::to_string(labels.size()) + " labels for a PointCloud2 of " +
                             std::to_string(points) + " points");
  }
  uint64_t declared = 0;  // the bytes the fields take a point
  for (const PointField& field : cloud.fields) {
    if (field.name == "label") throw IoError(where, "PointCloud2 already has a 'label' field");
    if (PointFieldSize(field.datatype) == 0) {
      throw IoError(where, "PointCloud2 field " + Quote(field.name) + " has datatype " +
                               std::to_string(field.datatype) + ", not a PointField type (1-8)");
    }
    declared += uint64_t(PointFieldSize(field.datatype)) * field.count;
  }
  if (points > 0) {
    CheckRecords(where, cloud);
    if (declared > cloud.point_step) {
      throw IoError(where, "PointCloud2 fields take " + std::to_string(declared) +
                               " bytes a point, more than point_step " +
                               std::to_string(cloud.point_step) + ": they overlap");
    }
  }
  uint64_t labelled_step = 0, plain_step = 0;
  const std::vector<PointField> labelled_fields =
      AlignedFields(cloud.fields, {"label"}, &labelled_step);
  const std::vector<PointField> plain_fields = AlignedFields(cloud.fields, {}, &plain_step);
  size_t ground = 0;
  for (uint8_t label : labels) ground += label == 1;
  const uint64_t widest_row = std::max(
      {uint64_t(cloud.width) * labelled_step, ground * plain_step, (points - ground) * plain_step});
  if (widest_row > std::numeric_limits<uint32_t>::max()) {
    throw IoError(where, "PointCloud2 with aligned fields and a label: a row of " +
                             std::to_string(widest_row) + " bytes does not fit in 32 bits");
  }
  LabelledClouds out;
  const auto shell = [&cloud](PointCloud2* c, const std::vector<PointField>& fields, uint64_t step,
                              uint32_t height, uint64_t width) {
    c->seq = cloud.seq;
    c->stamp_sec = cloud.stamp_sec;
    c->stamp_nanosec = cloud.stamp_nanosec;
    c->frame_id = cloud.frame_id;
    c->height = height;
    c->width = uint32_t(width);
    c->fields = fields;
    c->is_bigendian = cloud.is_bigendian;
    c->point_step = uint32_t(step);
    c->row_step = uint32_t(width * step);
    c->data.assign(size_t(width * step) * height, 0);
    c->is_dense = cloud.is_dense;
  };
  shell(&out.labelled, labelled_fields, labelled_step, cloud.height, cloud.width);
  shell(&out.ground, plain_fields, plain_step, 1, ground);
  shell(&out.nonground, plain_fields, plain_step, 1, points - ground);
  const size_t label_at = labelled_fields.back().offset;
  uint8_t* next[2] = {out.nonground.data.data(), out.ground.data.data()};
  size_t i = 0;
  for (uint32_t row = 0; row < cloud.height && points > 0; ++row) {
    const uint8_t* record = cloud.data.data() + uint64_t(row) * cloud.row_step;
    for (uint32_t col = 0; col < cloud.width; ++col, ++i, record += cloud.point_step) {
      uint8_t* labelled = out.labelled.data.data() + i * labelled_step;
      uint8_t*& split = next[labels[i] == 1];
      for (size_t k = 0; k < cloud.fields.size(); ++k) {
        const size_t bytes = PointFieldSize(cloud.fields[k].datatype) * cloud.fields[k].count;
        std::memcpy(labelled + labelled_fields[k].offset, record + cloud.fields[k].offset, bytes);
        std::memcpy(split + plain_fields[k].offset, record + cloud.fields[k].offset, bytes);
      }
      split += plain_step;
      const uint32_t label = labels[i] == 1 ? 1 : 0;
      for (int b = 0; b < 4; ++b)
        labelled[label_at + b] = uint8_t(label >> (8 * (cloud.is_bigendian ? 3 - b : b)));
    }
  }
  return out;
}

}  // namespace lpir
