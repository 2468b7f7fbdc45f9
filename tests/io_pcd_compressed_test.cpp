// PCD DATA binary_compressed: PCL's own files (tests/data/clouds/, written by
// tools/cloud_fixtures/make_cloud_fixtures.sh) read to the same points as their binary twins;
// hand-made files for padding and multi-count fields and empty clouds; every size the data can lie
// about, cuts of PCL's file and flipped bytes in its stream.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <string>

#include "host/io/cloud_file.h"
#include "host/io/pcd.h"
#include "tests/cloud_fixtures.h"
#include "tests/io_alloc_tracker.h"
#include "tests/io_test_helpers.h"
#include "tests/test_util.h"

namespace lpir {
namespace {

std::string Make(const std::string& bytes) {
  const std::string path = test::TempDir() + "/c.pcd";
  test::WriteRaw(path, bytes);
  return path;
}

std::string Header(const std::string& fields, const std::string& sizes, const std::string& types,
                   const std::string& counts, const std::string& width) {
  return "VERSION 0.7\nFIELDS " + fields + "\nSIZE " + sizes + "\nTYPE " + types + "\nCOUNT " +
         counts + "\nWIDTH " + width + "\nHEIGHT 1\nPOINTS " + width + "\nDATA binary_compressed\n";
}

std::string XyzHeader(const std::string& width) {
  return Header("x y z", "4 4 4", "F F F", "1 1 1", width);
}

// `bytes` as an LZF stream of literal runs only, which any LZF decoder reads back.
std::string LzfLiterals(const std::string& bytes) {
  std::string out;
  for (size_t at = 0; at < bytes.size(); at += 32) {
    const size_t n = std::min<size_t>(32, bytes.size() - at);
    out += char(n - 1);
    out += bytes.substr(at, n);
  }
  return out;
}

// The body after the header: the two sizes and the stream.
std::string Body(const std::string& stream, uint32_t decompressed) {
  return test::Bytes<uint32_t>({uint32_t(stream.size()), decompressed}) + stream;
}

TEST(IoPcdCompressed, PclFileReadsAsItsBinaryTwin) {
  const Cloud compressed = ReadPcd(test::CloudFixture("pcl_binary_compressed.pcd"));
  const Cloud binary = ReadPcd(test::CloudFixture("pcl_binary.pcd"));
  EXPECT_TRUE(test::SameBits(compressed, binary));
  EXPECT_TRUE(
      test::SameBits(compressed, ReadCloud(test::CloudFixture("pcl_binary_compressed.pcd"))));
  // What the script wrote: 16 rings of 40 columns, row by row, every 37th point from the 5th NaN.
  ASSERT_EQ(compressed.size(), 640u);
  ASSERT_EQ(compressed.ring.size(), 640u);
  size_t nan = 0;
  for (size_t i = 0; i < 640; ++i) {
    const size_t ring = i / 40, col = i % 40;
    EXPECT_EQ(compressed.ring[i], int32_t(ring)) << i;
    EXPECT_EQ(compressed.intensity(i), float((ring * 13 + col * 7) % 256)) << i;
    const bool no_return = i % 37 == 5;
    nan += std::isnan(compressed.x(i));
    EXPECT_EQ(std::isnan(compressed.z(i)), no_return) << i;
    if (!no_return) {
      EXPECT_LE(compressed.x(i), 12.0f + 1e-4f) << i;  // the wall 12 m ahead
    }
  }
  EXPECT_EQ(nan, 18u);
}

TEST(IoPcdCompressed, FieldsStoredOneAfterAnotherWithPaddingAndCounts) {
  // Three points: a 3-float normal (COUNT 3), x as F8, y z, intensity as U2, ring as U1 and
  // 2 bytes of padding "_", which the binary form stores in every record and the compressed
  // form not at all.
  const std::string fields = "normal x y z intensity ring _";
  const std::string sizes = "4 8 4 4 2 1 1", types = "F F F F U U U", counts = "3 1 1 1 1 1 2";
  std::string records, normal, x, yz_y, yz_z, intensity, ring;
  for (int i = 0; i < 3; ++i) {
    const std::string n = test::Bytes<float>({0.5f * i, -1.0f, 2.0f});
    const std::string xi = test::Bytes<double>({1.5 + i});
    const std::string yi = test::Bytes<float>({2.5f - i}), zi = test::Bytes<float>({-3.5f * i});
    const std::string ii = test::Bytes<uint16_t>({uint16_t(1000 + i)}),
                      ri = test::Bytes<uint8_t>({uint8_t(7 * i)});
    records += n + xi + yi + zi + ii + ri + test::Bytes<uint8_t>({0xAA, 0xBB});
    normal += n;
    x += xi;
    yz_y += yi;
    yz_z += zi;
    intensity += ii;
    ring += ri;
  }
  std::string binary_header = Header(fields, sizes, types, counts, "3");
  binary_header.replace(binary_header.find("binary_compressed"), 17, "binary");
  const std::string dir = test::TempDir();
  test::WriteRaw(dir + "/b.pcd", binary_header + records);
  const std::string soa = normal + x + yz_y + yz_z + intensity + ring;
  test::WriteRaw(dir + "/c.pcd", Header(fields, sizes, types, counts, "3") +
                                     Body(LzfLiterals(soa), uint32_t(soa.size())));
  const Cloud cloud = ReadPcd(dir + "/c.pcd");
  EXPECT_TRUE(test::SameBits(cloud, ReadPcd(dir + "/b.pcd")));
  ASSERT_EQ(cloud.size(), 3u);
  EXPECT_EQ(cloud.x(2), 3.5f);
  EXPECT_EQ(cloud.z(1), -3.5f);
  EXPECT_EQ(cloud.intensity(1), 1001.0f);
  EXPECT_EQ(cloud.ring[2], 14);
}

TEST(IoPcdCompressed, EmptyCloudAsPclWritesIt) {
  const Cloud cloud = ReadPcd(Make(XyzHeader("0") + Body("", 0)));
  EXPECT_EQ(cloud.size(), 0u);
}

TEST(IoPcdCompressed, ZerosAfterTheStreamAreAllowedOtherBytesNot) {
  const std::string points = test::Bytes<float>({1, 2, 3});
  const std::string body = Body(LzfLiterals(points), 12);
  EXPECT_EQ(ReadPcd(Make(XyzHeader("1") + body + std::string(3000, '\0'))).y(0), 2.0f);
  const std::string path = Make(XyzHeader("1") + body + std::string(5, '\0') + "x");
  EXPECT_TRUE(test::ThrowsIoError([&] { ReadPcd(path); }, path,
                                  {"binary_compressed", "6 bytes after the 13 compressed bytes"}));
}

TEST(IoPcdCompressed, FewerBytesThanTheTwoSizes) {
  const std::string path = Make(XyzHeader("1") + std::string(7, '\0'));
  EXPECT_TRUE(test::ThrowsIoError([&] { ReadPcd(path); }, path,
                                  {"7 bytes after the header", "two 4-byte sizes"}));
}

TEST(IoPcdCompressed, DecompressedSizeDisagreesWithTheHeader) {
  const std::string path = Make(XyzHeader("2") + Body(LzfLiterals(std::string(12, '\0')), 12));
  EXPECT_TRUE(test::ThrowsIoError([&] { ReadPcd(path); }, path,
                                  {"decompresses to 12 bytes", "2 points of 12 bytes take 24"}));
}

TEST(IoPcdCompressed, CompressedSizeBeyondTheFile) {
  std::string body = Body(LzfLiterals(test::Bytes<float>({1, 2, 3})), 12);
  body.resize(body.size() - 2);
  const std::string path = Make(XyzHeader("1") + body);
  EXPECT_TRUE(test::ThrowsIoError([&] { ReadPcd(path); }, path,
                                  {"holds 13 compressed bytes", "the file has 11", "cut short"}));
}

TEST(IoPcdCompressed, NoCompressedBytesForSomePoints) {
  const std::string path = Make(XyzHeader("1") + Body("", 12));
  EXPECT_TRUE(
      test::ThrowsIoError([&] { ReadPcd(path); }, path, {"no compressed bytes for 1 points"}));
}

TEST(IoPcdCompressed, AStreamThatDoesNotDecode) {
  // A back reference as the first instruction reaches before the output.
  const std::string path = Make(XyzHeader("1") + Body(std::string("\x20\x00", 2), 12));
  EXPECT_TRUE(
      test::ThrowsIoError([&] { ReadPcd(path); }, path, {"LZF data, byte 0", "before the start"}));
  const std::string short_stream = Make(XyzHeader("1") + Body(LzfLiterals("12345678"), 12));
  EXPECT_TRUE(test::ThrowsIoError([&] { ReadPcd(short_stream); }, short_stream,
                                  {"decodes to 8 bytes, not the 12"}));
}

TEST(IoPcdCompressed, HostilePointCountDoesNotAllocate) {
  // 100,000,000 points of 12 bytes claimed by 9 bytes of stream: LZF cannot expand that far.
  const std::string path =
      Make(XyzHeader("100000000") + Body(LzfLiterals("12345678"), 1200000000u));
  const size_t largest = test::LargestAllocationDuring([&] {
    EXPECT_TRUE(test::ThrowsIoError([&] { ReadPcd(path); }, path,
                                    {"9 compressed bytes cannot hold the 1200000000 bytes"}));
  });
  EXPECT_LT(largest, 64u * 1024u);
}

TEST(IoPcdCompressed, MorePointsThanTheSizesCanHold) {
  const std::string path = Make(XyzHeader("1000000000") + Body("", 0));
  EXPECT_TRUE(test::ThrowsIoError([&] { ReadPcd(path); }, path, {"32-bit sizes"}));
}

// The stream of PCL's file ends at `end`; the rest is PCL's zero padding.
size_t StreamEnd(const std::string& bytes) {
  const size_t data = bytes.find("DATA binary_compressed\n") + 23;
  uint32_t compressed;
  std::memcpy(&compressed, bytes.data() + data, 4);
  return data + 8 + compressed;
}

TEST(IoPcdCompressed, CutsOfPclsFileAreErrorsUpToTheStreamsEnd) {
  const std::string bytes = test::ReadRaw(test::CloudFixture("pcl_binary_compressed.pcd"));
  const Cloud whole = ReadPcd(test::CloudFixture("pcl_binary_compressed.pcd"));
  const size_t end = StreamEnd(bytes);
  ASSERT_LT(end, bytes.size());
  const std::string path = test::TempDir() + "/cut.pcd";
  const size_t stream = bytes.find("DATA binary_compressed\n") + 23 + 8;
  // Every cut in the header and the sizes and near the stream's end, every 13th in between.
  for (size_t n = 0; n <= end + 16; n += n < stream || n + 40 > end ? 1 : 13) {
    test::WriteRaw(path, bytes.substr(0, n));
    if (n < end) {
      ASSERT_TRUE(test::ThrowsIoError([&] { ReadPcd(path); }, path, {})) << "cut at " << n;
    } else {
      ASSERT_TRUE(test::SameBits(ReadPcd(path), whole)) << "cut at " << n;
    }
  }
}

TEST(IoPcdCompressed, FlippedStreamBytesNeverCrash) {
  const std::string bytes = test::ReadRaw(test::CloudFixture("pcl_binary_compressed.pcd"));
  const size_t stream = bytes.find("DATA binary_compressed\n") + 23 + 8;
  const std::string path = test::TempDir() + "/flipped.pcd";
  size_t errors = 0;
  for (size_t i = stream; i < stream + 600; ++i) {
    for (uint8_t mask : {0x01, 0x20, 0x80, 0xff}) {
      std::string flipped = bytes;
      flipped[i] = char(uint8_t(flipped[i]) ^ mask);
      test::WriteRaw(path, flipped);
      ASSERT_TRUE(test::ReturnsOrThrowsIoError([&] {
        try {
          EXPECT_EQ(ReadPcd(path).size(), 640u);
        } catch (const IoError&) {
          ++errors;
          throw;
        }
      })) << "byte "
          << i << " ^ " << int(mask);
    }
  }
  EXPECT_GT(errors, 0u);  // a flipped control byte changes the length decoded
}

}  // namespace
}  // namespace lpir
