// PCD: ASCII and binary round trips, files from other writers, every malformed-header case,
// hostile counts (cuts and damaged headers: tests/io_truncation_test.cpp).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "host/io/cloud_file.h"
#include "host/io/pcd.h"
#include "tests/io_alloc_tracker.h"
#include "tests/io_test_helpers.h"
#include "tests/test_util.h"

namespace lpir {
namespace {

using test::Bytes;
using test::SameBits;
using test::ThrowsIoError;
using test::WriteRaw;

// A header with the given field lines, for `points` points.
std::string Header(const std::string& fields, const std::string& sizes, const std::string& types,
                   const std::string& counts, const std::string& points, const std::string& data) {
  return "# .PCD v0.7 - Point Cloud Data file format\nVERSION 0.7\nFIELDS " + fields + "\nSIZE " +
         sizes + "\nTYPE " + types + "\nCOUNT " + counts + "\nWIDTH " + points +
         "\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS " + points + "\nDATA " + data + "\n";
}

std::string XyziHeader(const std::string& points, const std::string& data) {
  return Header("x y z intensity", "4 4 4 4", "F F F F", "1 1 1 1", points, data);
}

// Writes `text` to a fresh file and returns its path.
std::string Make(const std::string& text, const std::string& name = "a.pcd") {
  const std::string path = test::TempDir() + "/" + name;
  WriteRaw(path, text);
  return path;
}

TEST(IoPcd, BinaryRoundTripIsBitExactWithRing) {
  const std::string path = test::TempDir() + "/a.pcd";
  Cloud cloud = test::SampleCloud(200, true);
  cloud.xyzi[9] = std::numeric_limits<float>::quiet_NaN();
  cloud.xyzi[10] = std::numeric_limits<float>::infinity();
  cloud.ring[3] = 2147483647;
  WritePcd(path, cloud, nullptr, true);
  EXPECT_TRUE(SameBits(cloud, ReadPcd(path)));
}

TEST(IoPcd, BinaryRoundTripWithoutRing) {
  const std::string path = test::TempDir() + "/a.pcd";
  const Cloud cloud = test::SampleCloud(50, false);
  WritePcd(path, cloud, nullptr, true);
  const Cloud back = ReadPcd(path);
  EXPECT_TRUE(back.ring.empty());
  EXPECT_TRUE(SameBits(cloud, back));
}

TEST(IoPcd, AsciiRoundTripIsBitExactWithRing) {
  const std::string path = test::TempDir() + "/a.pcd";
  Cloud cloud = test::SampleCloud(200, true);
  cloud.xyzi[1] = std::numeric_limits<float>::denorm_min();
  cloud.xyzi[2] = -std::numeric_limits<float>::max();
  cloud.xyzi[3] = -0.0f;
  WritePcd(path, cloud, nullptr, false);
  EXPECT_NE(test::ReadRaw(path).find("DATA ascii\n"), std::string::npos);
  EXPECT_TRUE(SameBits(cloud, ReadPcd(path)));
}

TEST(IoPcd, AsciiNanAndInfAreRead) {
  const std::string path = Make(XyziHeader("2", "ascii") + "nan 1 2 3\n-inf inf NaN 0\n");
  const Cloud cloud = ReadPcd(path);
  ASSERT_EQ(cloud.size(), 2u);
  EXPECT_TRUE(std::isnan(cloud.x(0)));
  EXPECT_TRUE(std::isinf(cloud.x(1)) && cloud.x(1) < 0);
  EXPECT_TRUE(std::isinf(cloud.y(1)) && cloud.y(1) > 0);
  EXPECT_TRUE(std::isnan(cloud.z(1)));
}

TEST(IoPcd, LabelsAreWrittenAsUint8Field) {
  const std::string dir = test::TempDir();
  const Cloud cloud = test::SampleCloud(30, true);
  Labels labels(30);
  for (size_t i = 0; i < labels.size(); ++i) labels[i] = i % 3 == 0;
  WriteLabelledCloud(dir + "/l.pcd", cloud, labels);
  const std::string bytes = test::ReadRaw(dir + "/l.pcd");
  ASSERT_NE(bytes.find("FIELDS x y z intensity ring label\n"), std::string::npos);
  ASSERT_NE(bytes.find("TYPE F F F F I U\n"), std::string::npos);
  const size_t data = bytes.find("DATA binary\n") + 12;
  ASSERT_EQ(bytes.size() - data, 30u * 21u);
  for (size_t i = 0; i < 30; ++i) EXPECT_EQ(bytes[data + 21 * i + 20], char(labels[i]));
  EXPECT_TRUE(SameBits(cloud, ReadCloud(dir + "/l.pcd")));
  // The ASCII writer puts the label last on each line.
  WritePcd(dir + "/l_ascii.pcd", cloud, &labels, false);
  EXPECT_TRUE(SameBits(cloud, ReadPcd(dir + "/l_ascii.pcd")));
  EXPECT_NE(test::ReadRaw(dir + "/l_ascii.pcd").find(" 0 1\n"), std::string::npos);
}

TEST(IoPcd, WritingMismatchedLabelsIsAnError) {
  const std::string path = test::TempDir() + "/a.pcd";
  const Labels labels(4, 1);
  EXPECT_TRUE(ThrowsIoError([&] { WritePcd(path, test::SampleCloud(5, false), &labels, true); },
                            path, {"5 points", "4 labels"}));
}

TEST(IoPcd, BinaryFromOtherWritersWithSkippedFields) {
  // x as F8, a 3-float normal (COUNT 3), intensity as U2, ring as U1, a padding field.
  std::string text = Header("normal x y z intensity ring _", "4 8 4 4 2 1 1", "F F F F U U U",
                            "3 1 1 1 1 1 2", "2", "binary");
  for (int i = 0; i < 2; ++i) {
    text += Bytes<float>({9, 9, 9}) + Bytes<double>({1.5 + i}) + Bytes<float>({2.5f, -3.5f});
    text += Bytes<uint16_t>({uint16_t(1000 + i)}) + Bytes<uint8_t>({uint8_t(7 * i), 0xAA, 0xBB});
  }
  const Cloud cloud = ReadPcd(Make(text));
  ASSERT_EQ(cloud.size(), 2u);
  EXPECT_EQ(cloud.x(1), 2.5f);
  EXPECT_EQ(cloud.y(1), 2.5f);
  EXPECT_EQ(cloud.z(0), -3.5f);
  EXPECT_EQ(cloud.intensity(1), 1001.0f);
  EXPECT_EQ(cloud.ring, (std::vector<int32_t>{0, 7}));
}

TEST(IoPcd, AsciiFromOtherWritersWithSkippedFieldsAndCrLf) {
  std::string text =
      Header("x y z rgb normal ring", "4 4 4 4 4 2", "F F F F F I", "1 1 1 1 3 1", "2", "ascii");
  for (size_t p; (p = text.find("\n")) != std::string::npos && text[p - 1] != '\r';) {
    text.replace(p, 1, "\r\n");
  }
  text += "1 2 3 4.2e-38 0 0 1 5\r\n\r\n  +1.5\t-2 .5 0 0 0 1 12  \r\n";
  const Cloud cloud = ReadPcd(Make(text));
  ASSERT_EQ(cloud.size(), 2u);
  EXPECT_EQ(cloud.x(1), 1.5f);
  EXPECT_EQ(cloud.z(1), 0.5f);
  EXPECT_EQ(cloud.intensity(0), 0.0f);  // no intensity field
  EXPECT_EQ(cloud.ring, (std::vector<int32_t>{5, 12}));
}

TEST(IoPcd, IntensityUnderOtherNamesAndTheNoteWithout) {
  const std::string dir = test::TempDir();
  WriteRaw(dir + "/cc.pcd",
           Header("x y z scalar_Intensity", "4 4 4 4", "F F F F", "1 1 1 1", "1", "ascii") +
               "1 2 3 44\n");
  WriteRaw(dir + "/both.pcd", Header("remission x y z REFLECTIVITY", "4 4 4 4 2", "F F F F U",
                                     "1 1 1 1 1", "1", "ascii") +
                                  "7 1 2 3 65\n");
  WriteRaw(dir + "/none.pcd", Header("x y z", "4 4 4", "F F F", "1 1 1", "1", "ascii") + "1 2 3\n");
  std::string note = "stale";
  EXPECT_EQ(ReadPcd(dir + "/cc.pcd", &note).intensity(0), 44.0f);
  EXPECT_EQ(note, "");
  EXPECT_EQ(ReadCloud(dir + "/both.pcd", {}, &note).intensity(0), 65.0f);  // reflectivity wins
  EXPECT_EQ(note, "");
  EXPECT_EQ(ReadCloud(dir + "/none.pcd", {}, &note).intensity(0), 0.0f);
  EXPECT_EQ(note.find(dir + "/none.pcd has no intensity field ("), 0u) << note;
  // A KITTI .bin always has its intensity.
  WriteRaw(dir + "/scan.bin", Bytes<float>({1, 2, 3, 4}));
  EXPECT_EQ(ReadCloud(dir + "/scan.bin", {}, &note).intensity(0), 4.0f);
  EXPECT_EQ(note, "");
}

TEST(IoPcd, OrganisedWidthTimesHeight) {
  std::string text = XyziHeader("6", "ascii");
  text.replace(text.find("WIDTH 6"), 7, "WIDTH 3").replace(text.find("HEIGHT 1"), 8, "HEIGHT 2");
  for (int i = 0; i < 6; ++i) text += std::to_string(i) + " 0 0 0\n";
  EXPECT_EQ(ReadPcd(Make(text)).size(), 6u);
}

TEST(IoPcd, EmptyCloudIsValid) {
  const std::string path = test::TempDir() + "/a.pcd";
  WritePcd(path, Cloud{}, nullptr, true);
  EXPECT_EQ(ReadPcd(path).size(), 0u);
  WritePcd(path, Cloud{}, nullptr, false);
  EXPECT_EQ(ReadPcd(path).size(), 0u);
}

TEST(IoPcd, NotAPcdFile) {
  const std::string path = Make("ply\nformat ascii 1.0\n");
  EXPECT_TRUE(ThrowsIoError([&] { ReadPcd(path); }, path, {"line 1", "unknown header keyword"}));
}

TEST(IoPcd, HeaderWithoutData) {
  const std::string header = XyziHeader("1", "ascii");
  const std::string path = Make(header.substr(0, header.find("DATA")));
  EXPECT_TRUE(ThrowsIoError([&] { ReadPcd(path); }, path, {"no DATA line"}));
}

TEST(IoPcd, BinaryHeaderPromisesMorePointsThanTheFileHolds) {
  const std::string path = Make(XyziHeader("3", "binary") + Bytes<float>({1, 2, 3, 4, 5, 6, 7, 8}));
  EXPECT_TRUE(
      ThrowsIoError([&] { ReadPcd(path); }, path, {"header says 3 points but the data holds 2"}));
}

TEST(IoPcd, BinaryTruncatedMidPoint) {
  const std::string path = Make(XyziHeader("2", "binary") + Bytes<float>({1, 2, 3, 4, 5, 6}));
  EXPECT_TRUE(ThrowsIoError([&] { ReadPcd(path); }, path,
                            {"header says 2 points but the data holds 1", "24 bytes"}));
}

TEST(IoPcd, BinaryWithBytesBeyondThePoints) {
  const std::string path = Make(XyziHeader("1", "binary") + Bytes<float>({1, 2, 3, 4, 5}));
  EXPECT_TRUE(ThrowsIoError([&] { ReadPcd(path); }, path, {"20 bytes", "more than the 1 points"}));
}

TEST(IoPcd, BinaryWithZerosAfterThePointsAsPcl113WritesIt) {
  const std::string points = Bytes<float>({1, 2, 3, 4});
  EXPECT_EQ(ReadPcd(Make(XyziHeader("1", "binary") + points + std::string(4080, '\0'))).z(0), 3.0f);
  const std::string path =
      Make(XyziHeader("1", "binary") + points + std::string(100, '\0') + "\x01");
  EXPECT_TRUE(ThrowsIoError([&] { ReadPcd(path); }, path, {"117 bytes", "more than the 1 points"}));
}

TEST(IoPcd, AsciiHeaderPromisesMorePointsThanTheFileHolds) {
  std::string text = XyziHeader("1000", "ascii");
  for (int i = 0; i < 999; ++i) text += "1 2 3 4\n";
  const std::string path = Make(text);
  EXPECT_TRUE(ThrowsIoError([&] { ReadPcd(path); }, path,
                            {"header says 1000 points but the data holds 999"}));
}

TEST(IoPcd, AsciiMoreLinesThanPoints) {
  const std::string path = Make(XyziHeader("1", "ascii") + "1 2 3 4\n5 6 7 8\n");
  EXPECT_TRUE(ThrowsIoError([&] { ReadPcd(path); }, path, {"line 13", "more data after the 1"}));
}

TEST(IoPcd, AsciiGarbageTokenNamesTheLine) {
  const std::string path = Make(XyziHeader("2", "ascii") + "1 2 3 4\n5 6 x7 8\n");
  EXPECT_TRUE(ThrowsIoError([&] { ReadPcd(path); }, path,
                            {"line 13", "'x7' is not a valid float32 value for 'z'"}));
}

TEST(IoPcd, AsciiNumberWithTrailingJunk) {
  const std::string path = Make(XyziHeader("1", "ascii") + "1 2 3 4,5\n");
  EXPECT_TRUE(ThrowsIoError([&] { ReadPcd(path); }, path, {"line 12", "'4,5'"}));
}

TEST(IoPcd, AsciiWrongNumberOfValues) {
  const std::string path = Make(XyziHeader("1", "ascii") + "1 2 3\n");
  EXPECT_TRUE(ThrowsIoError([&] { ReadPcd(path); }, path, {"line 12 has 3 values, expected 4"}));
}

TEST(IoPcd, AsciiIntegerFieldWithFraction) {
  const std::string path =
      Make(Header("x y z ring", "4 4 4 2", "F F F U", "1 1 1 1", "1", "ascii") + "1 2 3 4.5\n");
  EXPECT_TRUE(ThrowsIoError([&] { ReadPcd(path); }, path, {"'4.5'", "uint16", "'ring'"}));
}

TEST(IoPcd, AsciiIntegerOutOfRange) {
  const std::string path =
      Make(Header("x y z ring", "4 4 4 1", "F F F U", "1 1 1 1", "1", "ascii") + "1 2 3 256\n");
  EXPECT_TRUE(ThrowsIoError([&] { ReadPcd(path); }, path, {"'256'", "uint8"}));
}

TEST(IoPcd, NegativeRing) {
  const std::string path = Make(
      Header("x y z ring", "4 4 4 4", "F F F I", "1 1 1 1", "2", "ascii") + "1 2 3 4\n1 2 3 -1\n");
  EXPECT_TRUE(ThrowsIoError([&] { ReadPcd(path); }, path, {"point 1 has ring -1"}));
}

TEST(IoPcd, FractionalFloatRing) {
  const std::string path =
      Make(Header("x y z ring", "4 4 4 4", "F F F F", "1 1 1 1", "1", "binary") +
           Bytes<float>({1, 2, 3, 0.25f}));
  EXPECT_TRUE(ThrowsIoError([&] { ReadPcd(path); }, path, {"point 0 has ring 0.25"}));
}

TEST(IoPcd, MissingX) {
  const std::string path =
      Make(Header("y z intensity", "4 4 4", "F F F", "1 1 1", "1", "ascii") + "1 2 3\n");
  EXPECT_TRUE(ThrowsIoError([&] { ReadPcd(path); }, path, {"no 'x' field"}));
}

TEST(IoPcd, DuplicateX) {
  const std::string path =
      Make(Header("x y z x", "4 4 4 4", "F F F F", "1 1 1 1", "1", "ascii") + "1 2 3 4\n");
  EXPECT_TRUE(ThrowsIoError([&] { ReadPcd(path); }, path, {"field 'x' appears twice"}));
}

TEST(IoPcd, CountOtherThanOneForAFieldWeRead) {
  const std::string path =
      Make(Header("x y z", "4 4 4", "F F F", "2 1 1", "1", "ascii") + "1 2 3 4\n");
  EXPECT_TRUE(ThrowsIoError([&] { ReadPcd(path); }, path, {"field 'x' has COUNT 2"}));
}

TEST(IoPcd, CountZero) {
  const std::string path =
      Make(Header("x y z n", "4 4 4 4", "F F F F", "1 1 1 0", "1", "ascii") + "1 2 3\n");
  EXPECT_TRUE(ThrowsIoError([&] { ReadPcd(path); }, path, {"field 'n' has COUNT '0'"}));
}

TEST(IoPcd, UnknownDataKind) {
  const std::string path = Make(XyziHeader("1", "hex"));
  EXPECT_TRUE(ThrowsIoError([&] { ReadPcd(path); }, path,
                            {"unknown DATA 'hex'", "ascii, binary or binary_compressed"}));
}

TEST(IoPcd, BadTypeSizeCombination) {
  const std::string path =
      Make(Header("x y z", "4 2 4", "F F F", "1 1 1", "1", "ascii") + "1 2 3\n");
  EXPECT_TRUE(ThrowsIoError([&] { ReadPcd(path); }, path,
                            {"field 'y' has unsupported TYPE 'F' with SIZE '2'"}));
}

TEST(IoPcd, UnknownTypeLetter) {
  const std::string path =
      Make(Header("x y z", "4 4 4", "F F Q", "1 1 1", "1", "ascii") + "1 2 3\n");
  EXPECT_TRUE(ThrowsIoError([&] { ReadPcd(path); }, path, {"field 'z'", "TYPE 'Q'"}));
}

TEST(IoPcd, SizeListShorterThanFields) {
  const std::string path = Make(Header("x y z", "4 4", "F F F", "1 1 1", "1", "ascii") + "1 2 3\n");
  EXPECT_TRUE(ThrowsIoError([&] { ReadPcd(path); }, path, {"SIZE has 2 values but FIELDS has 3"}));
}

TEST(IoPcd, PointsDisagreesWithWidthTimesHeight) {
  std::string text = XyziHeader("2", "ascii") + "1 2 3 4\n1 2 3 4\n";
  text.replace(text.find("POINTS 2"), 8, "POINTS 3");
  const std::string path = Make(text);
  EXPECT_TRUE(ThrowsIoError([&] { ReadPcd(path); }, path, {"POINTS 3", "WIDTH x HEIGHT = 2"}));
}

TEST(IoPcd, KeywordGivenTwice) {
  std::string text = XyziHeader("1", "ascii") + "1 2 3 4\n";
  text.replace(text.find("HEIGHT 1\n"), 9, "HEIGHT 1\nWIDTH 1\n");
  const std::string path = Make(text);
  EXPECT_TRUE(ThrowsIoError([&] { ReadPcd(path); }, path, {"line 9", "WIDTH given twice"}));
}

TEST(IoPcd, BadWidth) {
  std::string text = XyziHeader("1", "ascii") + "1 2 3 4\n";
  text.replace(text.find("WIDTH 1"), 7, "WIDTH -1");
  const std::string path = Make(text);
  EXPECT_TRUE(ThrowsIoError([&] { ReadPcd(path); }, path, {"line 7", "WIDTH needs one whole"}));
}

TEST(IoPcd, HostileBinaryPointCountDoesNotAllocate) {
  const std::string path = Make(XyziHeader("99999999999", "binary") + std::string(32, '\0'));
  const size_t largest = test::LargestAllocationDuring([&] {
    EXPECT_TRUE(ThrowsIoError([&] { ReadPcd(path); }, path,
                              {"header says 99999999999 points but the data holds 2"}));
  });
  EXPECT_LT(largest, 64u * 1024u);
}

TEST(IoPcd, HostileAsciiPointCountDoesNotAllocate) {
  const std::string path = Make(XyziHeader("99999999999", "ascii") + "1 2 3 4\n");
  const size_t largest = test::LargestAllocationDuring([&] {
    EXPECT_TRUE(ThrowsIoError([&] { ReadPcd(path); }, path,
                              {"header says 99999999999 points but the data holds 1"}));
  });
  EXPECT_LT(largest, 64u * 1024u);
}

TEST(IoPcd, HostileCountDoesNotOverflowTheRecordSize) {
  const std::string path =
      Make(Header("x y z pad", "4 4 4 8", "F F F F", "1 1 1 4611686018427387904", "1", "binary") +
           std::string(64, '\0'));
  EXPECT_TRUE(ThrowsIoError([&] { ReadPcd(path); }, path, {"'pad'", "too large"}));
}

TEST(IoPcd, HostileCountInAsciiNeedsThatManyValues) {
  const std::string path = Make(
      Header("x y z pad", "4 4 4 4", "F F F F", "1 1 1 99999999999", "1", "ascii") + "1 2 3 4\n");
  const size_t largest = test::LargestAllocationDuring([&] {
    EXPECT_TRUE(
        ThrowsIoError([&] { ReadPcd(path); }, path, {"has 4 values, expected 100000000002"}));
  });
  EXPECT_LT(largest, 64u * 1024u);
}

TEST(IoPcd, HostileWidthTimesHeightOverflow) {
  std::string text = XyziHeader("1", "binary");
  text.replace(text.find("WIDTH 1"), 7, "WIDTH 4294967296")
      .replace(text.find("HEIGHT 1"), 8, "HEIGHT 4294967296");
  const std::string path = Make(text);
  EXPECT_TRUE(ThrowsIoError([&] { ReadPcd(path); }, path, {"too many points"}));
}

TEST(IoPcd, HostileCountBeyondUint64) {
  const std::string path = Make(XyziHeader("184467440737095516160", "binary"));
  EXPECT_TRUE(ThrowsIoError([&] { ReadPcd(path); }, path, {"WIDTH needs one whole number"}));
}

}  // namespace
}  // namespace lpir
