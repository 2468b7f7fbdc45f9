// What every cloud reader must do with a file that is absent, empty, cut short or has a damaged
// header, as one typed test over the formats: PCD and PLY (ASCII and binary, a header that counts
// the points), KITTI .bin and nuScenes .pcd.bin (fixed-size points, no header). Each format's own
// malformed cases stay in tests/io_<format>_test.cpp.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "host/io/kitti_bin.h"
#include "host/io/pcd.h"
#include "host/io/ply.h"
#include "tests/io_test_helpers.h"
#include "tests/test_util.h"

namespace lpir {
namespace {

using test::ReturnsOrThrowsIoError;
using test::ThrowsIoError;
using test::WriteRaw;

// A format: its extension; Write(path, cloud, binary) and Read(path); kPointBytes, the bytes of
// a point in a headerless format (0: a header counts the points, so every cut is short); the
// words an error about a cut must hold; with a header (and an ASCII form), HeaderEnd(bytes),
// where it ends, and the bytes a mutation may put there.
struct Pcd {
  static constexpr const char* kExt = ".pcd";
  static constexpr size_t kPointBytes = 0;
  static void Write(const std::string& path, const Cloud& c, bool binary) {
    WritePcd(path, c, nullptr, binary);
  }
  static Cloud Read(const std::string& path) { return ReadPcd(path); }
  static size_t HeaderEnd(const std::string& bytes) { return bytes.find("DATA") + 12; }
  static std::vector<char> Mutations() {
    return {'\0', '\n', ' ', '9', '0', '-', 'F', 'x', '\xff'};
  }
  static std::vector<std::string> CutWords() { return {}; }
};

struct Ply {
  static constexpr const char* kExt = ".ply";
  static constexpr size_t kPointBytes = 0;
  static void Write(const std::string& path, const Cloud& c, bool binary) {
    WritePly(path, c, nullptr, binary);
  }
  static Cloud Read(const std::string& path) { return ReadPly(path); }
  static size_t HeaderEnd(const std::string& bytes) { return bytes.find("end_header") + 11; }
  static std::vector<char> Mutations() { return {'\0', '\n', ' ', '9', '0', '-', 'x', '\xff'}; }
  static std::vector<std::string> CutWords() { return {}; }
};

struct KittiBin {
  static constexpr const char* kExt = ".bin";
  static constexpr size_t kPointBytes = 16;
  static void Write(const std::string& path, const Cloud& c, bool) { WriteKittiBin(path, c); }
  static Cloud Read(const std::string& path) { return ReadKittiBin(path); }
  static std::vector<std::string> CutWords() { return {"not a whole number of 16-byte points"}; }
};

struct NuScenesBin {
  static constexpr const char* kExt = ".pcd.bin";
  static constexpr size_t kPointBytes = 20;
  static void Write(const std::string& path, const Cloud& c, bool) {
    WriteKittiBin(path, c, BinLayout::kNuScenes5);
  }
  static Cloud Read(const std::string& path) { return ReadKittiBin(path, BinLayout::kNuScenes5); }
  static std::vector<std::string> CutWords() { return {"20-byte points"}; }
};

template <class Format>
class IoTruncation : public ::testing::Test {
 protected:
  // The bytes of a 3-point cloud (rings included where the format keeps them) in `binary` form,
  // and the path a test writes its variants to.
  std::string Full(bool binary) {
    Format::Write(dir_.path + "/full" + Format::kExt, test::SampleCloud(3, true), binary);
    return test::ReadRaw(dir_.path + "/full" + Format::kExt);
  }
  std::string Path() const { return dir_.path + "/cut" + Format::kExt; }

 private:
  test::ScopedDir dir_;
};

struct FormatNames {
  template <class Format>
  static std::string GetName(int) {
    const std::string ext = Format::kExt;
    return ext == ".pcd"   ? "Pcd"
           : ext == ".ply" ? "Ply"
           : ext == ".bin" ? "KittiBin"
                           : "NuScenesBin";
  }
};

using Formats = ::testing::Types<Pcd, Ply, KittiBin, NuScenesBin>;
TYPED_TEST_SUITE(IoTruncation, Formats, FormatNames);

// The formats with a header and an ASCII form.
template <class Format>
class IoHeaderTruncation : public IoTruncation<Format> {};
using HeaderFormats = ::testing::Types<Pcd, Ply>;
TYPED_TEST_SUITE(IoHeaderTruncation, HeaderFormats, FormatNames);

TYPED_TEST(IoTruncation, MissingFile) {
  const std::string path = this->Path();
  EXPECT_TRUE(ThrowsIoError([&] { TypeParam::Read(path); }, path, {"no such file"}));
}

TYPED_TEST(IoTruncation, EmptyFile) {
  const std::string path = this->Path();
  WriteRaw(path, "");
  EXPECT_TRUE(ThrowsIoError([&] { TypeParam::Read(path); }, path, {"empty file"}));
}

// A header that counts the points makes every cut an error; without one, a cut at a whole
// number of points reads those points and any other cut is an error.
TYPED_TEST(IoTruncation, EveryTruncationOfABinaryFileIsAnErrorOrItsWholePoints) {
  const std::string bytes = this->Full(true), path = this->Path();
  size_t read = 0;
  for (size_t n = 1; n < bytes.size(); ++n) {
    WriteRaw(path, bytes.substr(0, n));
    if (TypeParam::kPointBytes && n % TypeParam::kPointBytes == 0) {
      ASSERT_EQ(TypeParam::Read(path).size(), n / TypeParam::kPointBytes) << "cut at " << n;
      ++read;
    } else {
      ASSERT_TRUE(ThrowsIoError([&] { TypeParam::Read(path); }, path, TypeParam::CutWords()))
          << "cut at " << n;
    }
  }
  EXPECT_EQ(read, TypeParam::kPointBytes ? 2u : 0u);
}

TYPED_TEST(IoHeaderTruncation, EveryTruncationOfAnAsciiFileIsAnErrorOrAWholeCloud) {
  const std::string bytes = this->Full(false), path = this->Path();
  size_t parsed = 0;
  for (size_t n = 0; n < bytes.size(); ++n) {
    WriteRaw(path, bytes.substr(0, n));
    ASSERT_TRUE(ReturnsOrThrowsIoError([&] {
      EXPECT_EQ(TypeParam::Read(path).size(), 3u);  // only a cut inside the last value parses
      ++parsed;
    })) << "cut at "
        << n;
  }
  EXPECT_LT(parsed, 8u);
}

TYPED_TEST(IoHeaderTruncation, MutatedHeadersNeverCrash) {
  const std::string path = this->Path();
  for (bool binary : {false, true}) {
    const std::string bytes = this->Full(binary);
    const size_t header_end = TypeParam::HeaderEnd(bytes);
    ASSERT_GT(header_end, 0u);
    for (size_t i = 0; i < header_end; ++i)
      for (char c : TypeParam::Mutations()) {
        std::string mutated = bytes;
        mutated[i] = c;
        WriteRaw(path, mutated);
        ASSERT_TRUE(ReturnsOrThrowsIoError([&] { TypeParam::Read(path); }))
            << "byte " << i << " = " << c;
      }
  }
}

}  // namespace
}  // namespace lpir
