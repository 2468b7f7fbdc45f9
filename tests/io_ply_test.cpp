// PLY: ASCII and binary round trips, files from other writers, every malformed-header case,
// hostile counts, and the real HDL-32E and OS1 scans (cuts and damaged headers:
// tests/io_truncation_test.cpp).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "host/io/cloud_file.h"
#include "host/io/kitti_bin.h"
#include "host/io/ply.h"
#include "tests/cloud_fixtures.h"
#include "tests/io_alloc_tracker.h"
#include "tests/io_test_helpers.h"
#include "tests/test_util.h"

namespace lpir {
namespace {

using test::Bytes;
using test::SameBits;
using test::ThrowsIoError;
using test::WriteRaw;

// "ply", the format line, one vertex element with `properties` (lines after "property "), end.
std::string Header(const std::string& format, const std::string& count,
                   const std::vector<std::string>& properties, const std::string& extra = "") {
  std::string text = "ply\nformat " + format + " 1.0\ncomment test\nelement vertex " + count + "\n";
  for (const std::string& p : properties) text += "property " + p + "\n";
  return text + extra + "end_header\n";
}

std::string XyzHeader(const std::string& format, const std::string& count) {
  return Header(format, count, {"float x", "float y", "float z"});
}

std::string Make(const std::string& text, const std::string& name = "a.ply") {
  const std::string path = test::TempDir() + "/" + name;
  WriteRaw(path, text);
  return path;
}

TEST(IoPly, BinaryRoundTripIsBitExactWithRing) {
  const std::string path = test::TempDir() + "/a.ply";
  Cloud cloud = test::SampleCloud(200, true);
  cloud.xyzi[9] = std::numeric_limits<float>::quiet_NaN();
  cloud.xyzi[10] = -std::numeric_limits<float>::infinity();
  WritePly(path, cloud, nullptr, true);
  EXPECT_NE(test::ReadRaw(path).find("format binary_little_endian 1.0\n"), std::string::npos);
  EXPECT_TRUE(SameBits(cloud, ReadPly(path)));
}

TEST(IoPly, BinaryRoundTripWithoutRing) {
  const std::string path = test::TempDir() + "/a.ply";
  const Cloud cloud = test::SampleCloud(50, false);
  WritePly(path, cloud, nullptr, true);
  const Cloud back = ReadPly(path);
  EXPECT_TRUE(back.ring.empty());
  EXPECT_TRUE(SameBits(cloud, back));
}

TEST(IoPly, AsciiRoundTripIsBitExactWithRing) {
  const std::string path = test::TempDir() + "/a.ply";
  Cloud cloud = test::SampleCloud(200, true);
  cloud.xyzi[1] = std::numeric_limits<float>::denorm_min();
  cloud.xyzi[2] = std::numeric_limits<float>::max();
  cloud.xyzi[3] = -0.0f;
  WritePly(path, cloud, nullptr, false);
  EXPECT_NE(test::ReadRaw(path).find("format ascii 1.0\n"), std::string::npos);
  EXPECT_TRUE(SameBits(cloud, ReadPly(path)));
}

TEST(IoPly, AsciiNanAndInfAreRead) {
  const std::string path = Make(XyzHeader("ascii", "1") + "nan -inf inf\n");
  const Cloud cloud = ReadPly(path);
  ASSERT_EQ(cloud.size(), 1u);
  EXPECT_TRUE(std::isnan(cloud.x(0)));
  EXPECT_TRUE(std::isinf(cloud.y(0)) && cloud.y(0) < 0);
  EXPECT_TRUE(std::isinf(cloud.z(0)) && cloud.z(0) > 0);
}

TEST(IoPly, LabelsAreWrittenAsUcharProperty) {
  const std::string dir = test::TempDir();
  const Cloud cloud = test::SampleCloud(30, false);
  Labels labels(30);
  for (size_t i = 0; i < labels.size(); ++i) labels[i] = i % 4 == 1;
  WriteLabelledCloud(dir + "/l.ply", cloud, labels);
  const std::string bytes = test::ReadRaw(dir + "/l.ply");
  ASSERT_NE(bytes.find("property float intensity\nproperty uchar label\nend_header\n"),
            std::string::npos);
  const size_t data = bytes.find("end_header\n") + 11;
  ASSERT_EQ(bytes.size() - data, 30u * 17u);
  for (size_t i = 0; i < 30; ++i) EXPECT_EQ(bytes[data + 17 * i + 16], char(labels[i]));
  EXPECT_TRUE(SameBits(cloud, ReadCloud(dir + "/l.ply")));
  WritePly(dir + "/l_ascii.ply", cloud, &labels, false);
  EXPECT_TRUE(SameBits(cloud, ReadPly(dir + "/l_ascii.ply")));
}

TEST(IoPly, WritingMismatchedRingIsAnError) {
  const std::string path = test::TempDir() + "/a.ply";
  Cloud cloud = test::SampleCloud(5, true);
  cloud.ring.pop_back();
  EXPECT_TRUE(ThrowsIoError([&] { WritePly(path, cloud, nullptr, true); }, path,
                            {"5 points", "4 ring values"}));
}

TEST(IoPly, EveryScalarTypeNameIsRead) {
  const std::vector<std::string> names = {"char",  "uchar",  "short",   "ushort", "int",   "uint",
                                          "float", "double", "int8",    "uint8",  "int16", "uint16",
                                          "int32", "uint32", "float32", "float64"};
  for (const std::string& type : names) {
    const std::string path =
        Make(Header("ascii", "2",
                    {"double x", "float y", "float z", type + " intensity", type + " ring"}) +
             "1 2 3 4 5\n6 7 8 100 0\n");
    const Cloud cloud = ReadPly(path);
    ASSERT_EQ(cloud.size(), 2u) << type;
    EXPECT_EQ(cloud.intensity(1), 100.0f) << type;
    EXPECT_EQ(cloud.ring, (std::vector<int32_t>{5, 0})) << type;
  }
}

TEST(IoPly, BinaryFromOtherWritersSkipsPropertiesAndLaterElements) {
  // ring as float, intensity as ushort, x as double, skipped uint and uchar, then a face element.
  std::string text = Header(
      "binary_little_endian", "2",
      {"uint t", "double x", "float y", "float z", "ushort intensity", "uchar flags", "float ring"},
      "element face 1\nproperty list uchar int vertex_indices\n");
  for (int i = 0; i < 2; ++i) {
    text += Bytes<uint32_t>({77}) + Bytes<double>({-1.25 * i}) + Bytes<float>({2, 3});
    text += Bytes<uint16_t>({uint16_t(60000 + i)}) + Bytes<uint8_t>({9}) + Bytes<float>({31.0f});
  }
  text += Bytes<uint8_t>({3}) + Bytes<int32_t>({0, 1, 0});
  const Cloud cloud = ReadPly(Make(text));
  ASSERT_EQ(cloud.size(), 2u);
  EXPECT_EQ(cloud.x(1), -1.25f);
  EXPECT_EQ(cloud.z(1), 3.0f);
  EXPECT_EQ(cloud.intensity(1), 60001.0f);
  EXPECT_EQ(cloud.ring, (std::vector<int32_t>{31, 31}));
}

TEST(IoPly, AsciiLaterElementsAreIgnored) {
  const std::string path = Make(Header("ascii", "2", {"float x", "float y", "float z"},
                                       "element face 1\nproperty list uchar int vertex_indices\n") +
                                "1 2 3\n4 5 6\n3 0 1 1\n");
  EXPECT_EQ(ReadPly(path).size(), 2u);
}

TEST(IoPly, IntensityUnderTheNamesOtherWritersUse) {
  // CloudCompare writes scalar_Intensity; Ouster reflectivity; KITTI converters remission.
  for (const char* name :
       {"intensity", "Intensity", "INTENSITY", "scalar_intensity", "scalar_Intensity",
        "reflectivity", "Reflectivity", "remission", "i", "I"}) {
    const std::string path = Make(
        Header("ascii", "1",
               {"float x", "float y", "float z", "float other", std::string("float ") + name}) +
        "1 2 3 9 187\n");
    std::string note = "stale";
    EXPECT_EQ(ReadPly(path, &note).intensity(0), 187.0f) << name;
    EXPECT_EQ(note, "") << name;
  }
}

TEST(IoPly, CloudComparesScalarIntensityIsTheIntensity) {
  // CloudCompare wrote the scan's valid points; PCL the whole scan, NaN no-returns included.
  std::string note = "stale";
  const Cloud cc = ReadPly(test::CloudFixture("cloudcompare.ply"), &note);
  EXPECT_EQ(note, "");
  const Cloud pcl = ReadCloud(test::CloudFixture("pcl_binary.pcd"));
  size_t k = 0;
  for (size_t i = 0; i < pcl.size(); ++i) {
    if (std::isnan(pcl.x(i))) continue;
    ASSERT_LT(k, cc.size());
    for (int v = 0; v < 4; ++v) ASSERT_EQ(cc.xyzi[4 * k + v], pcl.xyzi[4 * i + v]) << i << " " << v;
    ++k;
  }
  EXPECT_EQ(k, cc.size());
  EXPECT_EQ(k, 622u);
}

TEST(IoPly, TheBestIntensityNameWinsWhateverTheOrder) {
  // Best first: intensity, scalar_intensity, reflectivity, remission, i.
  const std::vector<std::string> names = {"i", "remission", "reflectivity", "scalar_Intensity",
                                          "intensity"};
  for (size_t best = 0; best < names.size(); ++best) {
    std::vector<std::string> properties = {"float x", "float y", "float z"};
    std::string values = "1 2 3";
    for (size_t k = 0; k <= best; ++k) {  // names[best] is the best one present
      properties.push_back("float " + names[k]);
      values += " " + std::to_string(10 * k + 5);
    }
    const std::string path = Make(Header("ascii", "1", properties) + values + "\n");
    EXPECT_EQ(ReadPly(path).intensity(0), float(10 * best + 5)) << names[best];
  }
}

TEST(IoPly, TwoColumnsOfTheBestIntensityNameAreAnError) {
  const std::string path =
      Make(Header("ascii", "1",
                  {"float x", "float y", "float z", "float Intensity", "float intensity"}) +
           "1 2 3 4 5\n");
  EXPECT_TRUE(ThrowsIoError([&] { ReadPly(path); }, path, {"'intensity' appears twice"}));
}

TEST(IoPly, NoIntensityReadsZeroWithANote) {
  const std::string path = Make(XyzHeader("ascii", "1") + "1 2 3\n");
  std::string note;
  EXPECT_EQ(ReadPly(path, &note).intensity(0), 0.0f);
  EXPECT_EQ(note.find(path), 0u) << note;
  for (const char* word :
       {"has no intensity field", "scalar_intensity", "remission", "any case", "intensity 0"}) {
    EXPECT_NE(note.find(word), std::string::npos) << note;
  }
  std::string through_read_cloud;
  ReadCloud(path, {}, &through_read_cloud);
  EXPECT_EQ(through_read_cloud, note);
}

TEST(IoPly, CrLfHeaderAndComments) {
  const std::string path = Make(
      "ply\r\nformat ascii 1.0\r\ncomment made on Windows\r\nobj_info x\r\n"
      "element vertex 1\r\nproperty float x\r\nproperty float y\r\nproperty float z\r\n"
      "end_header\r\n1 2 3\r\n");
  EXPECT_EQ(ReadPly(path).z(0), 3.0f);
}

TEST(IoPly, NotAPlyFile) {
  const std::string path = Make("VERSION 0.7\n");
  EXPECT_TRUE(ThrowsIoError([&] { ReadPly(path); }, path, {"not a PLY file"}));
}

TEST(IoPly, BigEndianIsUnsupported) {
  const std::string path = Make(XyzHeader("binary_big_endian", "1") + std::string(12, '\0'));
  EXPECT_TRUE(ThrowsIoError([&] { ReadPly(path); }, path, {"binary_big_endian", "unsupported"}));
}

TEST(IoPly, UnknownFormat) {
  const std::string path = Make(XyzHeader("binary_middle_endian", "1"));
  EXPECT_TRUE(ThrowsIoError([&] { ReadPly(path); }, path,
                            {"line 2", "unknown format 'binary_middle_endian'"}));
}

TEST(IoPly, UnsupportedVersion) {
  std::string text = XyzHeader("ascii", "1") + "1 2 3\n";
  text.replace(text.find("1.0"), 3, "2.0");
  const std::string path = Make(text);
  EXPECT_TRUE(ThrowsIoError([&] { ReadPly(path); }, path, {"unsupported format version '2.0'"}));
}

TEST(IoPly, NoFormatLine) {
  const std::string path = Make("ply\nelement vertex 0\nproperty float x\nend_header\n");
  EXPECT_TRUE(ThrowsIoError([&] { ReadPly(path); }, path, {"no format line"}));
}

TEST(IoPly, NoEndHeader) {
  const std::string header = XyzHeader("ascii", "1");
  const std::string path = Make(header.substr(0, header.find("end_header")));
  EXPECT_TRUE(ThrowsIoError([&] { ReadPly(path); }, path, {"no end_header"}));
}

TEST(IoPly, UnsupportedPropertyType) {
  const std::string path =
      Make(Header("binary_little_endian", "1", {"float x", "float128 y", "float z"}));
  EXPECT_TRUE(ThrowsIoError([&] { ReadPly(path); }, path,
                            {"line 6", "property 'y' has unsupported type 'float128'"}));
}

TEST(IoPly, ListPropertyInVertex) {
  const std::string path =
      Make(Header("ascii", "1", {"float x", "float y", "float z", "list uchar float normals"}) +
           "1 2 3 0\n");
  EXPECT_TRUE(ThrowsIoError([&] { ReadPly(path); }, path,
                            {"property 'normals' of element 'vertex' is a list"}));
}

TEST(IoPly, MissingVertexElement) {
  const std::string path = Make(
      "ply\nformat ascii 1.0\nelement face 1\nproperty list uchar int i\nend_header\n3 0 1 2\n");
  EXPECT_TRUE(ThrowsIoError([&] { ReadPly(path); }, path, {"no 'vertex' element"}));
}

TEST(IoPly, ElementBeforeVertex) {
  const std::string path = Make(
      "ply\nformat ascii 1.0\nelement camera 1\nproperty float f\nelement vertex 1\n"
      "property float x\nproperty float y\nproperty float z\nend_header\n1\n1 2 3\n");
  EXPECT_TRUE(ThrowsIoError([&] { ReadPly(path); }, path,
                            {"element 'camera' comes before 'vertex'", "unsupported"}));
}

TEST(IoPly, MissingY) {
  const std::string path = Make(Header("ascii", "1", {"float x", "float z"}) + "1 2\n");
  EXPECT_TRUE(ThrowsIoError([&] { ReadPly(path); }, path, {"no 'y' property"}));
}

TEST(IoPly, DuplicateRing) {
  const std::string path =
      Make(Header("ascii", "1", {"float x", "float y", "float z", "int ring", "int ring"}) +
           "1 2 3 4 5\n");
  EXPECT_TRUE(ThrowsIoError([&] { ReadPly(path); }, path, {"property 'ring' appears twice"}));
}

TEST(IoPly, PropertyBeforeElement) {
  const std::string path = Make("ply\nformat ascii 1.0\nproperty float x\nend_header\n");
  EXPECT_TRUE(ThrowsIoError([&] { ReadPly(path); }, path, {"line 3", "property before any"}));
}

TEST(IoPly, BinaryHeaderClaimsMoreVerticesThanPresent) {
  const std::string path =
      Make(XyzHeader("binary_little_endian", "3") + Bytes<float>({1, 2, 3, 4, 5, 6, 7}));
  EXPECT_TRUE(ThrowsIoError([&] { ReadPly(path); }, path,
                            {"header says 3 vertices but the data holds 2", "28 bytes"}));
}

TEST(IoPly, BinaryWithBytesBeyondTheVertices) {
  const std::string path =
      Make(XyzHeader("binary_little_endian", "1") + Bytes<float>({1, 2, 3, 4}));
  EXPECT_TRUE(ThrowsIoError([&] { ReadPly(path); }, path, {"16 bytes", "more than the 1"}));
}

TEST(IoPly, AsciiHeaderClaimsMoreVerticesThanPresent) {
  std::string text = XyzHeader("ascii", "1000");
  for (int i = 0; i < 999; ++i) text += "1 2 3\n";
  const std::string path = Make(text);
  EXPECT_TRUE(ThrowsIoError([&] { ReadPly(path); }, path,
                            {"header says 1000 vertices but the data holds 999"}));
}

TEST(IoPly, AsciiGarbageTokenNamesTheLine) {
  const std::string path = Make(XyzHeader("ascii", "2") + "1 2 3\n4 five 6\n");
  EXPECT_TRUE(ThrowsIoError([&] { ReadPly(path); }, path,
                            {"line 10", "'five' is not a valid float32 value for 'y'"}));
}

TEST(IoPly, AsciiWrongNumberOfValues) {
  const std::string path = Make(XyzHeader("ascii", "1") + "1 2 3 4\n");
  EXPECT_TRUE(ThrowsIoError([&] { ReadPly(path); }, path, {"line 9 has 4 values, expected 3"}));
}

TEST(IoPly, FractionalFloatRing) {
  const std::string path =
      Make(Header("binary_little_endian", "1", {"float x", "float y", "float z", "float ring"}) +
           Bytes<float>({1, 2, 3, 1.5f}));
  EXPECT_TRUE(ThrowsIoError([&] { ReadPly(path); }, path, {"vertex 0 has ring 1.5"}));
}

TEST(IoPly, NegativeIntegerRing) {
  const std::string path =
      Make(Header("ascii", "2", {"float x", "float y", "float z", "short ring"}) +
           "1 2 3 1\n1 2 3 -2\n");
  EXPECT_TRUE(ThrowsIoError([&] { ReadPly(path); }, path, {"vertex 1 has ring -2"}));
}

TEST(IoPly, HostileBinaryVertexCountDoesNotAllocate) {
  const std::string path =
      Make(XyzHeader("binary_little_endian", "99999999999") + std::string(24, '\0'));
  const size_t largest = test::LargestAllocationDuring([&] {
    EXPECT_TRUE(ThrowsIoError([&] { ReadPly(path); }, path,
                              {"header says 99999999999 vertices but the data holds 2"}));
  });
  EXPECT_LT(largest, 64u * 1024u);
}

TEST(IoPly, HostileAsciiVertexCountDoesNotAllocate) {
  const std::string path = Make(XyzHeader("ascii", "18446744073709551615") + "1 2 3\n");
  const size_t largest = test::LargestAllocationDuring([&] {
    EXPECT_TRUE(ThrowsIoError([&] { ReadPly(path); }, path,
                              {"header says 18446744073709551615 vertices but the data holds 1"}));
  });
  EXPECT_LT(largest, 64u * 1024u);
}

TEST(IoPly, HostileCountBeyondUint64) {
  const std::string path = Make(XyzHeader("ascii", "18446744073709551616"));
  EXPECT_TRUE(ThrowsIoError([&] { ReadPly(path); }, path, {"line 4", "whole number count"}));
}

TEST(IoPly, RealHdl32eScans) {
  LPIR_REQUIRE_DATA("hdl32e/source.ply");
  LPIR_REQUIRE_DATA("hdl32e/target.ply");
  const Cloud source = ReadPly(test::DataFile("hdl32e/source.ply"));
  ASSERT_EQ(source.size(), 69792u);
  EXPECT_TRUE(source.ring.empty());
  float max_i = 0.0f;
  for (size_t i = 0; i < source.size(); ++i) {
    ASSERT_GE(source.intensity(i), 0.0f);
    ASSERT_EQ(source.intensity(i), std::floor(source.intensity(i)));  // whole numbers
    max_i = std::max(max_i, source.intensity(i));
  }
  EXPECT_EQ(max_i, 187.0f);  // scalar_intensity 0..187 in this recording
  EXPECT_EQ(ReadCloud(test::DataFile("hdl32e/target.ply")).size(), 69088u);
}

TEST(IoPly, RealOusterOs1Scan) {
  const std::string name = "rellis3d/os1/frame000104-1581624663_170.ply";
  LPIR_REQUIRE_DATA(name);
  const Cloud cloud = ReadPly(test::DataFile(name));
  ASSERT_EQ(cloud.size(), 131072u);
  ASSERT_EQ(cloud.ring.size(), 131072u);
  // Stored column by column: 2048 columns of the 64 beams in order.
  for (size_t i = 0; i < cloud.size(); ++i) ASSERT_EQ(cloud.ring[i], int32_t(i % 64)) << i;
  size_t no_return = 0;
  float max_i = 0.0f;
  for (size_t i = 0; i < cloud.size(); ++i) {
    no_return += cloud.x(i) == 0.0f && cloud.y(i) == 0.0f && cloud.z(i) == 0.0f;
    max_i = std::max(max_i, cloud.intensity(i));
  }
  EXPECT_EQ(no_return, 53364u);
  EXPECT_EQ(max_i, 754.0f);  // raw OS1 intensity, not normalised
}

TEST(IoPly, RealOusterPlyMatchesTheBinOfTheSameScan) {
  const std::string ply = "rellis3d/os1/frame000104-1581624663_170.ply";
  LPIR_REQUIRE_DATA(ply);
  LPIR_REQUIRE_DATA("rellis3d/os1/000104.bin");
  const Cloud a = ReadPly(test::DataFile(ply));
  const Cloud b = ReadKittiBin(test::DataFile("rellis3d/os1/000104.bin"));
  ASSERT_EQ(a.size(), b.size());
  for (size_t i = 0; i < a.size(); ++i) {
    ASSERT_EQ(a.x(i), b.x(i)) << i;
    ASSERT_EQ(a.y(i), b.y(i)) << i;
    ASSERT_EQ(a.z(i), b.z(i)) << i;
    // The .bin stores intensity / 65535.
    ASSERT_NEAR(a.intensity(i) / 65535.0f, b.intensity(i), 1e-7f) << i;
  }
}

}  // namespace
}  // namespace lpir
