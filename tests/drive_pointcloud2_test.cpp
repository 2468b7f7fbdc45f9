// sensor_msgs/PointCloud2 (host/drive/pointcloud2.h): CDR parsing and serialization, decoding
// of every field layout into a Cloud, the rejections, and the label field added for output.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "host/drive/pointcloud2.h"
#include "host/io/io_error.h"
#include "tests/io_test_helpers.h"

namespace lpir {
namespace {

using test::SameBits;
using test::ThrowsIoError;

const std::string kWhere = "drive.db3 message 7";

size_t TypeSize(uint8_t type) {
  switch (type) {
    case kPfInt8:
    case kPfUint8:
      return 1;
    case kPfInt16:
    case kPfUint16:
      return 2;
    case kPfFloat64:
      return 8;
    default:
      return 4;
  }
}

// Stores `value` converted to `type` at p, byte-swapped when big-endian. Integer types take it
// through int64_t, whose conversion to a narrower type wraps (a negative value into an unsigned
// field is defined that way, not by the float conversion).
void Store(uint8_t* p, uint8_t type, double value, bool big) {
  uint8_t b[8] = {};
  switch (type) {
    case kPfInt8: {
      const int8_t v = int8_t(int64_t(value));
      std::memcpy(b, &v, 1);
      break;
    }
    case kPfUint8: {
      const uint8_t v = uint8_t(int64_t(value));
      std::memcpy(b, &v, 1);
      break;
    }
    case kPfInt16: {
      const int16_t v = int16_t(int64_t(value));
      std::memcpy(b, &v, 2);
      break;
    }
    case kPfUint16: {
      const uint16_t v = uint16_t(int64_t(value));
      std::memcpy(b, &v, 2);
      break;
    }
    case kPfInt32: {
      const int32_t v = int32_t(int64_t(value));
      std::memcpy(b, &v, 4);
      break;
    }
    case kPfUint32: {
      const uint32_t v = uint32_t(int64_t(value));
      std::memcpy(b, &v, 4);
      break;
    }
    case kPfFloat32: {
      const float v = float(value);
      std::memcpy(b, &v, 4);
      break;
    }
    case kPfFloat64:
      std::memcpy(b, &value, 8);
      break;
  }
  const size_t n = TypeSize(type);
  for (size_t k = 0; k < n; ++k) p[k] = big ? b[n - 1 - k] : b[k];
}

struct FieldSpec {
  std::string name;
  uint8_t type;
};

// A cloud of width x height points whose fields are laid out in order with `gap` unused bytes
// before each, `row_pad` bytes after each row, values value(point, field index).
PointCloud2 MakeCloud(const std::vector<FieldSpec>& specs, uint32_t width, uint32_t height,
                      uint32_t gap, uint32_t row_pad, bool big,
                      const std::function<double(size_t, size_t)>& value) {
  PointCloud2 cloud;
  cloud.width = width;
  cloud.height = height;
  cloud.is_bigendian = big;
  uint32_t offset = 0;
  for (const FieldSpec& spec : specs) {
    offset += gap;
    cloud.fields.push_back(PointField{spec.name, offset, spec.type, 1});
    offset += uint32_t(TypeSize(spec.type));
  }
  cloud.point_step = offset + gap;
  cloud.row_step = width * cloud.point_step + row_pad;
  cloud.data.assign(size_t(cloud.row_step) * height, 0xAB);
  size_t point = 0;
  for (uint32_t r = 0; r < height; ++r) {
    for (uint32_t c = 0; c < width; ++c, ++point) {
      uint8_t* record = cloud.data.data() + r * cloud.row_step + c * cloud.point_step;
      for (size_t f = 0; f < specs.size(); ++f) {
        Store(record + cloud.fields[f].offset, specs[f].type, value(point, f), big);
      }
    }
  }
  return cloud;
}

::testing::AssertionResult SameMessage(const PointCloud2& a, const PointCloud2& b) {
  if (a.stamp_sec != b.stamp_sec || a.stamp_nanosec != b.stamp_nanosec)
    return ::testing::AssertionFailure() << "stamps differ";
  if (a.frame_id != b.frame_id) return ::testing::AssertionFailure() << "frame_id differs";
  if (a.height != b.height || a.width != b.width) return ::testing::AssertionFailure() << "size";
  if (a.fields.size() != b.fields.size()) return ::testing::AssertionFailure() << "field count";
  for (size_t i = 0; i < a.fields.size(); ++i) {
    const PointField &x = a.fields[i], &y = b.fields[i];
    if (x.name != y.name || x.offset != y.offset || x.datatype != y.datatype || x.count != y.count)
      return ::testing::AssertionFailure() << "field " << i << " differs";
  }
  if (a.is_bigendian != b.is_bigendian || a.is_dense != b.is_dense)
    return ::testing::AssertionFailure() << "flags differ";
  if (a.point_step != b.point_step || a.row_step != b.row_step)
    return ::testing::AssertionFailure() << "steps differ";
  if (a.data != b.data) return ::testing::AssertionFailure() << "data differs";
  return ::testing::AssertionSuccess();
}

// An independent CDR writer for the tests (either byte order, alignment from byte 4).
class TestCdr {
 public:
  explicit TestCdr(bool big) : big_(big), out_{0x00, uint8_t(big ? 0x00 : 0x01), 0x00, 0x00} {}
  TestCdr& U8(uint8_t v) {
    out_.push_back(v);
    return *this;
  }
  TestCdr& U32(uint32_t v) {
    while ((out_.size() - 4) % 4) out_.push_back(0);
    for (int k = 0; k < 4; ++k) out_.push_back(uint8_t(v >> (big_ ? 24 - 8 * k : 8 * k)));
    return *this;
  }
  TestCdr& Str(const std::string& s) {
    U32(uint32_t(s.size() + 1));
    out_.insert(out_.end(), s.begin(), s.end());
    out_.push_back(0);
    return *this;
  }
  TestCdr& Raw(const std::vector<uint8_t>& bytes) {
    out_.insert(out_.end(), bytes.begin(), bytes.end());
    return *this;
  }
  std::vector<uint8_t> bytes() const { return out_; }

 private:
  bool big_;
  std::vector<uint8_t> out_;
};

// The CDR of `cloud` written by TestCdr.
std::vector<uint8_t> TestSerialize(const PointCloud2& cloud, bool big) {
  TestCdr cdr(big);
  cdr.U32(uint32_t(cloud.stamp_sec)).U32(cloud.stamp_nanosec).Str(cloud.frame_id);
  cdr.U32(cloud.height).U32(cloud.width).U32(uint32_t(cloud.fields.size()));
  for (const PointField& f : cloud.fields)
    cdr.Str(f.name).U32(f.offset).U8(f.datatype).U32(f.count);
  cdr.U8(cloud.is_bigendian).U32(cloud.point_step).U32(cloud.row_step);
  cdr.U32(uint32_t(cloud.data.size())).Raw(cloud.data).U8(cloud.is_dense);
  return cdr.bytes();
}

PointCloud2 Parse(const std::vector<uint8_t>& bytes) {
  return ParseCdrPointCloud2(kWhere, bytes.data(), bytes.size());
}

PointCloud2 SmallCloud() {
  PointCloud2 cloud =
      MakeCloud({{"x", kPfFloat32},
                 {"y", kPfFloat32},
                 {"z", kPfFloat32},
                 {"intensity", kPfFloat32},
                 {"ring", kPfUint16}},
                5, 1, 0, 0, false, [](size_t p, size_t f) { return f == 4 ? p % 3 : 0.5 * p - f; });
  cloud.stamp_sec = 1700000000;
  cloud.stamp_nanosec = 123456789;
  cloud.frame_id = "velodyne";
  cloud.is_dense = true;
  return cloud;
}

TEST(DrivePointCloud2, SerializeThenParseIsEqualForEveryFrameIdLength) {
  for (size_t length = 0; length < 9; ++length) {
    PointCloud2 cloud = SmallCloud();
    cloud.frame_id = std::string(length, 'f');
    cloud.stamp_sec = -3;  // negative seconds survive the uint32 on the wire
    cloud.is_dense = length % 2 == 0;
    const PointCloud2 back = Parse(SerializeCdrPointCloud2(cloud));
    EXPECT_TRUE(SameMessage(cloud, back)) << "frame_id length " << length;
    EXPECT_EQ(back.stamp_ns(), int64_t(-3) * 1000000000 + 123456789);
  }
}

TEST(DrivePointCloud2, SerializeMatchesAnIndependentLittleEndianWriter) {
  const PointCloud2 cloud = SmallCloud();
  EXPECT_EQ(SerializeCdrPointCloud2(cloud), TestSerialize(cloud, false));
}

TEST(DrivePointCloud2, ParsesBigEndianCdr) {
  const PointCloud2 cloud = SmallCloud();
  const std::vector<uint8_t> big = TestSerialize(cloud, true);
  ASSERT_EQ(big[1], 0x00);
  EXPECT_TRUE(SameMessage(cloud, Parse(big)));
}

TEST(DrivePointCloud2, AcceptsUpToSevenPaddingBytesAfterTheMessage) {
  std::vector<uint8_t> bytes = SerializeCdrPointCloud2(SmallCloud());
  for (int pad = 1; pad <= 7; ++pad) {
    bytes.push_back(0);
    EXPECT_TRUE(SameMessage(SmallCloud(), Parse(bytes))) << pad;
  }
  bytes.push_back(0);
  EXPECT_TRUE(ThrowsIoError([&] { Parse(bytes); }, kWhere, {"8 bytes after"}));
}

TEST(DrivePointCloud2, EveryTruncationIsAnIoError) {
  PointCloud2 cloud = SmallCloud();
  cloud.fields.push_back(PointField{"t", 0, kPfUint8, 1});  // a field of odd name length
  const std::vector<uint8_t> bytes = SerializeCdrPointCloud2(cloud);
  for (size_t n = 0; n < bytes.size(); ++n) {
    const std::vector<uint8_t> cut(bytes.begin(), bytes.begin() + long(n));
    EXPECT_TRUE(ThrowsIoError([&] { ParseCdrPointCloud2(kWhere, cut.data(), n); }, kWhere, {}))
        << n << " of " << bytes.size() << " bytes";
  }
}

TEST(DrivePointCloud2, RejectsOtherEncapsulations) {
  std::vector<uint8_t> bytes = SerializeCdrPointCloud2(SmallCloud());
  for (uint8_t kind : {0x02, 0x03, 0x06, 0x07, 0x0a}) {
    bytes[1] = kind;
    EXPECT_TRUE(ThrowsIoError([&] { Parse(bytes); }, kWhere, {"encapsulation", "not plain CDR"}));
  }
  bytes[0] = 0x01;
  bytes[1] = 0x01;
  EXPECT_TRUE(ThrowsIoError([&] { Parse(bytes); }, kWhere, {"encapsulation"}));
}

TEST(DrivePointCloud2, RejectsLengthsThatOverrunTheMessage) {
  // A frame_id length beyond the bytes: refused before any allocation.
  TestCdr frame(false);
  frame.U32(0).U32(0).U32(0xFFFFFFF0u).Raw({'a', 'b', 0});
  EXPECT_TRUE(ThrowsIoError([&] { Parse(frame.bytes()); }, kWhere,
                            {"header.frame_id length 4294967280 overruns"}));
  // Four billion fields in a few bytes.
  TestCdr fields(false);
  fields.U32(0).U32(0).Str("f").U32(1).U32(1).U32(0xFFFFFFFFu).Raw(std::vector<uint8_t>(64, 0));
  EXPECT_TRUE(ThrowsIoError([&] { Parse(fields.bytes()); }, kWhere, {"fields count", "overruns"}));
  // A data sequence longer than what is left.
  std::vector<uint8_t> bytes = SerializeCdrPointCloud2(SmallCloud());
  const size_t data_count_at = bytes.size() - 1 - SmallCloud().data.size() - 4;
  bytes[data_count_at] += 2;
  EXPECT_TRUE(ThrowsIoError([&] { Parse(bytes); }, kWhere, {"data count", "overruns"}));
}

TEST(DrivePointCloud2, RejectsAStringWithoutItsNulAndABoolOtherThan0Or1) {
  TestCdr no_nul(false);
  no_nul.U32(0).U32(0).U32(2).Raw({'a', 'b'});
  EXPECT_TRUE(ThrowsIoError([&] { Parse(no_nul.bytes()); }, kWhere, {"frame_id", "NUL"}));
  std::vector<uint8_t> bytes = SerializeCdrPointCloud2(SmallCloud());
  bytes.back() = 2;  // is_dense
  EXPECT_TRUE(ThrowsIoError([&] { Parse(bytes); }, kWhere, {"is_dense is 2"}));
}

TEST(DrivePointCloud2, AZeroStringLengthReadsAsEmpty) {
  TestCdr cdr(false);
  cdr.U32(1).U32(2).U32(0);  // frame_id with no NUL at all
  cdr.U32(1).U32(0).U32(0).U8(0).U32(0).U32(0).U32(0).U8(1);
  const PointCloud2 cloud = Parse(cdr.bytes());
  EXPECT_EQ(cloud.frame_id, "");
  EXPECT_EQ(cloud.stamp_nanosec, 2u);
  EXPECT_TRUE(cloud.is_dense);
}

// Expected Cloud value of a field value: `value` stored as `type` and read back.
double AsStored(uint8_t type, double value) {
  uint8_t b[8];
  Store(b, type, value, false);
  switch (type) {
    case kPfInt8:
      return int8_t(b[0]);
    case kPfUint8:
      return b[0];
    case kPfInt16: {
      int16_t v;
      std::memcpy(&v, b, 2);
      return v;
    }
    case kPfUint16: {
      uint16_t v;
      std::memcpy(&v, b, 2);
      return v;
    }
    case kPfFloat32: {
      float f;
      std::memcpy(&f, b, 4);
      return f;
    }
    default:
      return value;
  }
}

TEST(DrivePointCloud2, DecodesEveryFieldLayout) {
  struct Intensity {
    const char* name;
    uint8_t type;
  };
  const Intensity intensities[] = {{"", 0},
                                   {"intensity", kPfUint8},
                                   {"intensity", kPfUint16},
                                   {"intensity", kPfFloat32},
                                   {"intensity", kPfInt8},
                                   {"reflectivity", kPfUint16},
                                   {"i", kPfFloat64}};
  const uint8_t rings[] = {0, kPfUint16, kPfUint8, kPfFloat32, kPfInt32, kPfFloat64};
  for (uint8_t xyz : {kPfFloat32, kPfFloat64}) {
    for (const Intensity& intensity : intensities) {
      for (uint8_t ring : rings) {
        for (uint32_t height : {1u, 3u}) {
          for (bool big : {false, true}) {
            SCOPED_TRACE(::testing::Message()
                         << "xyz " << int(xyz) << " intensity " << intensity.name << "/"
                         << int(intensity.type) << " ring " << int(ring) << " height " << height
                         << " big " << big);
            // z first, a skipped field between: offsets are read, not assumed.
            std::vector<FieldSpec> specs = {{"z", xyz}, {"t", kPfUint32}, {"x", xyz}, {"y", xyz}};
            if (intensity.type) specs.push_back({intensity.name, intensity.type});
            if (ring) specs.push_back({"ring", ring});
            const auto value = [&](size_t p, size_t f) -> double {
              const std::string& name = specs[f].name;
              if (name == "ring") return double((p * 7) % 128);
              if (name == intensity.name)
                return intensity.type == kPfInt8 ? -double(p % 100) : double(p % 200) + 0.5;
              return 0.25 * double(p) - 3.0 * double(f) + (name == "x" ? 1e-3 : 0.0);
            };
            const uint32_t width = 6;
            const PointCloud2 msg = MakeCloud(specs, width, height, height == 3 ? 1 : 0,
                                              height == 3 ? 5 : 0, big, value);
            const Cloud cloud = CloudFromPointCloud2(kWhere, msg);
            ASSERT_EQ(cloud.size(), size_t(width) * height);
            ASSERT_EQ(cloud.ring.size(), ring ? cloud.size() : 0u);
            for (size_t p = 0; p < cloud.size(); ++p) {
              EXPECT_EQ(cloud.z(p), float(value(p, 0)));
              EXPECT_EQ(cloud.x(p), float(value(p, 2)));
              EXPECT_EQ(cloud.y(p), float(value(p, 3)));
              EXPECT_EQ(cloud.intensity(p),
                        intensity.type ? float(AsStored(intensity.type, value(p, 4))) : 0.0f);
              if (ring) {
                EXPECT_EQ(cloud.ring[p], int32_t((p * 7) % 128));
              }
            }
          }
        }
      }
    }
  }
}

TEST(DrivePointCloud2, IntensityIsTheBestOfTheIntensityNamesPresent) {
  // Field f of point p holds 10 f + p; x, y, z are fields 0-2, the candidates 3 on. The names of
  // IntensityNames() in any case, as the PCD and PLY readers take them.
  const auto value = [](size_t p, size_t f) { return double(10 * f + p); };
  const struct {
    std::vector<std::string> names;
    float intensity;  // of point 1
  } cases[] = {{{"i", "reflectivity", "intensity"}, 51.0f},
               {{"i", "reflectivity"}, 41.0f},
               {{"Remission", "scalar_Intensity"}, 41.0f}};
  for (const auto& c : cases) {
    std::vector<FieldSpec> specs = {{"x", kPfFloat32}, {"y", kPfFloat32}, {"z", kPfFloat32}};
    for (const std::string& name : c.names) specs.push_back({name, kPfFloat32});
    const PointCloud2 msg = MakeCloud(specs, 2, 1, 0, 0, false, value);
    EXPECT_EQ(CloudFromPointCloud2(kWhere, msg).intensity(1), c.intensity) << c.names.back();
  }
}

TEST(DrivePointCloud2, KeepsNanPointsBitForBit) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const PointCloud2 msg =
      MakeCloud({{"x", kPfFloat32}, {"y", kPfFloat32}, {"z", kPfFloat32}}, 3, 1, 0, 0, false,
                [&](size_t p, size_t) { return p == 1 ? double(nan) : 1.0; });
  const Cloud cloud = CloudFromPointCloud2(kWhere, msg);
  ASSERT_EQ(cloud.size(), 3u);
  EXPECT_TRUE(std::isnan(cloud.x(1)));
  EXPECT_EQ(cloud.x(2), 1.0f);
}

PointCloud2 Xyz() {
  return MakeCloud({{"x", kPfFloat32}, {"y", kPfFloat32}, {"z", kPfFloat32}}, 4, 2, 0, 0, false,
                   [](size_t p, size_t f) { return double(p + f); });
}

TEST(DrivePointCloud2, RejectsFieldsThatDoNotHoldXyz) {
  PointCloud2 msg = Xyz();
  msg.fields[1].name = "v";
  EXPECT_TRUE(ThrowsIoError([&] { CloudFromPointCloud2(kWhere, msg); }, kWhere, {"no 'y'"}));
  msg = Xyz();
  msg.fields[2].datatype = kPfUint32;
  EXPECT_TRUE(ThrowsIoError([&] { CloudFromPointCloud2(kWhere, msg); }, kWhere,
                            {"'z' is uint32", "float32 or float64"}));
  msg = Xyz();
  msg.fields[0].count = 2;
  EXPECT_TRUE(ThrowsIoError([&] { CloudFromPointCloud2(kWhere, msg); }, kWhere, {"count 2"}));
  msg = Xyz();
  msg.fields.push_back(msg.fields[0]);
  EXPECT_TRUE(ThrowsIoError([&] { CloudFromPointCloud2(kWhere, msg); }, kWhere, {"twice"}));
  msg = Xyz();
  msg.fields.push_back(PointField{"pad", 0, 9, 1});
  EXPECT_TRUE(ThrowsIoError([&] { CloudFromPointCloud2(kWhere, msg); }, kWhere, {"datatype 9"}));
  msg = Xyz();
  msg.fields.clear();
  msg.width = msg.height = 0;
  msg.data.clear();
  EXPECT_TRUE(ThrowsIoError([&] { CloudFromPointCloud2(kWhere, msg); }, kWhere, {"no 'x'"}));
}

TEST(DrivePointCloud2, RejectsLayoutsThatOverrunTheData) {
  PointCloud2 msg = Xyz();
  msg.fields[2].offset = 9;  // 9 + 4 > point_step 12
  EXPECT_TRUE(ThrowsIoError([&] { CloudFromPointCloud2(kWhere, msg); }, kWhere,
                            {"'z'", "overruns point_step 12"}));
  msg = Xyz();
  msg.fields.push_back(PointField{"normal", 4, kPfFloat32, 3});  // 4 + 12 > 12
  EXPECT_TRUE(
      ThrowsIoError([&] { CloudFromPointCloud2(kWhere, msg); }, kWhere, {"'normal'", "overruns"}));
  msg = Xyz();
  msg.fields.push_back(PointField{"huge", 0xFFFFFFF0u, kPfFloat64, 0xFFFFFFFFu});
  EXPECT_TRUE(ThrowsIoError([&] { CloudFromPointCloud2(kWhere, msg); }, kWhere, {"overruns"}));
  msg = Xyz();
  msg.point_step = 0;
  EXPECT_TRUE(
      ThrowsIoError([&] { CloudFromPointCloud2(kWhere, msg); }, kWhere, {"point_step is 0"}));
  msg = Xyz();
  msg.row_step = 47;
  EXPECT_TRUE(ThrowsIoError([&] { CloudFromPointCloud2(kWhere, msg); }, kWhere,
                            {"row_step 47 < width 4 x point_step 12"}));
  msg = Xyz();
  msg.data.pop_back();
  EXPECT_TRUE(ThrowsIoError([&] { CloudFromPointCloud2(kWhere, msg); }, kWhere,
                            {"data holds 95 bytes", "= 96"}));
  msg = Xyz();
  msg.data.push_back(0);
  EXPECT_TRUE(
      ThrowsIoError([&] { CloudFromPointCloud2(kWhere, msg); }, kWhere, {"data holds 97 bytes"}));
  // 2^64 - 2^33 + 1 points and no data: refused by size, before anything is allocated.
  msg = Xyz();
  msg.width = msg.height = 0xFFFFFFFFu;
  msg.row_step = 0xFFFFFFFFu;
  msg.point_step = 1;
  msg.fields = {{"x", 0, kPfFloat32, 1}, {"y", 0, kPfFloat32, 1}, {"z", 0, kPfFloat32, 1}};
  EXPECT_TRUE(ThrowsIoError([&] { CloudFromPointCloud2(kWhere, msg); }, kWhere, {"overruns"}));
  msg.point_step = 4;
  EXPECT_TRUE(ThrowsIoError([&] { CloudFromPointCloud2(kWhere, msg); }, kWhere, {"row_step"}));
  msg.width = 1;
  EXPECT_TRUE(
      ThrowsIoError([&] { CloudFromPointCloud2(kWhere, msg); }, kWhere, {"data holds 96 bytes"}));
}

TEST(DrivePointCloud2, AnEmptyCloudChecksOnlyItsFields) {
  PointCloud2 msg = Xyz();
  msg.width = 0;
  msg.point_step = msg.row_step = 0;
  msg.data.clear();
  EXPECT_EQ(CloudFromPointCloud2(kWhere, msg).size(), 0u);
}

TEST(DrivePointCloud2, RejectsRingsThatAreNotWholeNumbersAtLeast0) {
  for (double bad : {-1.0, 1.5, std::nan(""), 3e9}) {
    for (uint8_t type : {kPfFloat32, kPfFloat64, kPfInt8, kPfInt32, kPfUint32}) {
      if (type != kPfFloat32 && type != kPfFloat64 && (std::isnan(bad) || bad == 1.5)) continue;
      if ((type == kPfInt8 || type == kPfInt32) && bad > 0) continue;  // not representable
      if (type == kPfUint32 && bad < 0) continue;
      SCOPED_TRACE(::testing::Message() << bad << " as " << int(type));
      const PointCloud2 msg =
          MakeCloud({{"x", kPfFloat32}, {"y", kPfFloat32}, {"z", kPfFloat32}, {"ring", type}}, 3, 1,
                    0, 0, false, [&](size_t p, size_t f) { return f == 3 && p == 2 ? bad : 1.0; });
      EXPECT_TRUE(ThrowsIoError([&] { CloudFromPointCloud2(kWhere, msg); }, kWhere,
                                {"point 2 has ring", "not a whole number"}));
    }
  }
}

// The bytes of field `f` of point i of `c` (rows of row_step, points of point_step).
std::string FieldBytes(const PointCloud2& c, const PointField& f, size_t i) {
  const size_t row = i / c.width, col = i % c.width;
  const uint8_t* at = c.data.data() + row * c.row_step + col * c.point_step + f.offset;
  return std::string(reinterpret_cast<const char*>(at), TypeSize(f.datatype) * f.count);
}

TEST(DrivePointCloud2, SplitByLabelAlignsEveryFieldAndSplitsThePointsByLabel) {
  for (bool big : {false, true}) {
    SCOPED_TRACE(big ? "big-endian" : "little-endian");
    // Organised 5 x 3, a gap byte before each field and row padding: nothing is aligned.
    PointCloud2 msg = MakeCloud(
        {{"x", kPfFloat32},
         {"y", kPfFloat32},
         {"z", kPfFloat32},
         {"intensity", kPfUint16},
         {"ring", kPfUint8},
         {"t", kPfFloat64}},
        5, 3, 1, 3, big, [](size_t p, size_t f) { return f == 4 ? double(p % 16) : 0.5 * p + f; });
    msg.seq = 7;
    msg.stamp_sec = 1700000000;
    msg.stamp_nanosec = 5;
    msg.frame_id = "os_lidar";
    msg.is_dense = true;
    Labels labels(15);
    for (size_t i = 0; i < labels.size(); ++i) labels[i] = uint8_t(i % 3 == 0);
    const LabelledClouds out = SplitByLabel(kWhere, msg, labels);

    // Each field at the next multiple of its size, the uint32 label after them, the step a
    // multiple of the widest (float64): 0 4 8 12 14 16, label 24, step 32.
    const PointCloud2& l = out.labelled;
    ASSERT_EQ(l.fields.size(), msg.fields.size() + 1);
    const uint32_t offsets[] = {0, 4, 8, 12, 14, 16, 24};
    for (size_t k = 0; k < l.fields.size(); ++k) {
      EXPECT_EQ(l.fields[k].offset, offsets[k]) << l.fields[k].name;
      EXPECT_EQ(l.fields[k].offset % TypeSize(l.fields[k].datatype), 0u) << l.fields[k].name;
    }
    EXPECT_EQ(l.fields.back().name, "label");
    EXPECT_EQ(l.fields.back().datatype, kPfUint32);
    EXPECT_EQ(l.fields.back().count, 1u);
    EXPECT_EQ(l.point_step, 32u);
    EXPECT_EQ(l.height, 3u);
    EXPECT_EQ(l.width, 5u);
    EXPECT_EQ(l.row_step, 5u * 32u);
    EXPECT_EQ(l.data.size(), size_t(l.row_step) * 3);
    for (size_t i = 0; i < labels.size(); ++i) {
      for (size_t k = 0; k < msg.fields.size(); ++k)
        EXPECT_EQ(FieldBytes(l, l.fields[k], i), FieldBytes(msg, msg.fields[k], i)) << i;
      const std::string label = FieldBytes(l, l.fields.back(), i);
      const uint32_t value = big ? uint32_t(uint8_t(label[3])) | uint32_t(uint8_t(label[0])) << 24
                                 : uint32_t(uint8_t(label[0])) | uint32_t(uint8_t(label[3])) << 24;
      EXPECT_EQ(value, labels[i]) << i;
    }
    EXPECT_TRUE(SameBits(CloudFromPointCloud2(kWhere, l), CloudFromPointCloud2(kWhere, msg)));

    // ground: the points labelled 1 in order, nonground the others; the same fields, no label.
    for (const bool ground : {true, false}) {
      const PointCloud2& part = ground ? out.ground : out.nonground;
      ASSERT_EQ(part.fields.size(), msg.fields.size());
      for (size_t k = 0; k < part.fields.size(); ++k) EXPECT_EQ(part.fields[k].offset, offsets[k]);
      EXPECT_EQ(part.point_step, 24u);
      EXPECT_EQ(part.height, 1u);
      EXPECT_EQ(part.row_step, part.width * 24u);
      EXPECT_EQ(part.data.size(), part.row_step);
      size_t j = 0;
      for (size_t i = 0; i < labels.size(); ++i) {
        if ((labels[i] == 1) != ground) continue;
        ASSERT_LT(j, part.width);
        for (size_t k = 0; k < msg.fields.size(); ++k)
          EXPECT_EQ(FieldBytes(part, part.fields[k], j), FieldBytes(msg, msg.fields[k], i));
        ++j;
      }
      EXPECT_EQ(j, part.width);
    }
    EXPECT_EQ(out.ground.width, 5u);
    for (const PointCloud2* c : {&out.labelled, &out.ground, &out.nonground}) {
      EXPECT_EQ(c->seq, 7u);
      EXPECT_EQ(c->stamp_ns(), msg.stamp_ns());
      EXPECT_EQ(c->frame_id, "os_lidar");
      EXPECT_EQ(c->is_bigendian, big);
      EXPECT_TRUE(c->is_dense);
      // Through CDR and back, unchanged.
      EXPECT_TRUE(SameMessage(*c, Parse(SerializeCdrPointCloud2(*c))));
    }
  }
}

TEST(DrivePointCloud2, SplitByLabelRejectsWrongCountsASecondLabelAndOverlappingFields) {
  const PointCloud2 msg = Xyz();
  EXPECT_TRUE(ThrowsIoError([&] { SplitByLabel(kWhere, msg, Labels(7)); }, kWhere,
                            {"7 labels", "8 points"}));
  const PointCloud2 labelled = SplitByLabel(kWhere, msg, Labels(8, 1)).labelled;
  EXPECT_TRUE(ThrowsIoError([&] { SplitByLabel(kWhere, labelled, Labels(8, 1)); }, kWhere,
                            {"already has a 'label' field"}));
  PointCloud2 short_data = msg;
  short_data.data.resize(10);
  EXPECT_TRUE(ThrowsIoError([&] { SplitByLabel(kWhere, short_data, Labels(8)); }, kWhere,
                            {"data holds 10 bytes"}));
  PointCloud2 overlap = msg;
  overlap.fields.push_back(PointField{"rgb", 8, kPfFloat32, 1});
  EXPECT_TRUE(ThrowsIoError([&] { SplitByLabel(kWhere, overlap, Labels(8)); }, kWhere,
                            {"16 bytes a point", "point_step 12", "overlap"}));
  PointCloud2 bad_type = msg;
  bad_type.fields[1].datatype = 9;
  EXPECT_TRUE(
      ThrowsIoError([&] { SplitByLabel(kWhere, bad_type, Labels(8)); }, kWhere, {"datatype 9"}));
  PointCloud2 empty = msg;
  empty.width = 0;
  empty.data.clear();
  const LabelledClouds none = SplitByLabel(kWhere, empty, Labels());
  EXPECT_EQ(none.labelled.data.size() + none.ground.data.size() + none.nonground.data.size(), 0u);
  EXPECT_EQ(none.labelled.fields.back().name, "label");
}

}  // namespace
}  // namespace lpir
