// The chunk decompressions of host/drive/decompress.h: round trips through our compressors and
// through the libraries' own frame options (checksums, no content size), corrupt and truncated
// data, an expected size too small or too large, empty input, and CRC-32 check values.
#include <bzlib.h>
#include <gtest/gtest.h>
#include <lz4frame.h>
#include <zstd.h>

#include <cstring>
#include <functional>
#include <string>
#include <vector>

#include "host/drive/decompress.h"
#include "tests/io_alloc_tracker.h"
#include "tests/io_test_helpers.h"

namespace lpir {
namespace {

using test::ThrowsIoError;

using Decompress = std::vector<uint8_t> (*)(const std::string&, const uint8_t*, size_t, size_t);

// Bytes that compress (runs) mixed with bytes that do not (an LCG), `n` long.
std::vector<uint8_t> Sample(size_t n, bool compressible) {
  std::vector<uint8_t> out(n);
  uint32_t x = 12345;
  for (size_t i = 0; i < n; ++i) {
    x = x * 1103515245u + 12345u;
    out[i] = compressible ? uint8_t((i / 97) % 7) : uint8_t(x >> 24);
  }
  return out;
}

std::vector<uint8_t> Bz2(const std::vector<uint8_t>& data) {
  unsigned int n = unsigned(data.size() + data.size() / 100 + 600);
  std::vector<uint8_t> out(n);
  const uint8_t none = 0;  // bzlib refuses a null source, even of 0 bytes
  EXPECT_EQ(
      BZ2_bzBuffToBuffCompress(
          reinterpret_cast<char*>(out.data()), &n,
          const_cast<char*>(reinterpret_cast<const char*>(data.empty() ? &none : data.data())),
          unsigned(data.size()), 9, 0, 0),
      BZ_OK);
  out.resize(n);
  return out;
}

// zstd with a content checksum and no content size in the frame header.
std::vector<uint8_t> ZstdChecksummed(const std::vector<uint8_t>& data) {
  ZSTD_CCtx* cctx = ZSTD_createCCtx();
  ZSTD_CCtx_setParameter(cctx, ZSTD_c_checksumFlag, 1);
  ZSTD_CCtx_setParameter(cctx, ZSTD_c_contentSizeFlag, 0);
  std::vector<uint8_t> out(ZSTD_compressBound(data.size()));
  ZSTD_outBuffer o{out.data(), out.size(), 0};
  ZSTD_inBuffer in{data.data(), data.size(), 0};
  EXPECT_EQ(ZSTD_compressStream2(cctx, &o, &in, ZSTD_e_end), 0u);
  ZSTD_freeCCtx(cctx);
  out.resize(o.pos);
  return out;
}

// lz4 frame with block and content checksums, 64 KiB linked blocks, no content size.
std::vector<uint8_t> Lz4Checksummed(const std::vector<uint8_t>& data) {
  LZ4F_preferences_t prefs{};
  prefs.frameInfo.blockSizeID = LZ4F_max64KB;
  prefs.frameInfo.blockMode = LZ4F_blockLinked;
  prefs.frameInfo.contentChecksumFlag = LZ4F_contentChecksumEnabled;
  prefs.frameInfo.blockChecksumFlag = LZ4F_blockChecksumEnabled;
  std::vector<uint8_t> out(LZ4F_compressFrameBound(data.size(), &prefs));
  const size_t n = LZ4F_compressFrame(out.data(), out.size(), data.data(), data.size(), &prefs);
  EXPECT_FALSE(LZ4F_isError(n));
  out.resize(n);
  return out;
}

struct Codec {
  const char* name;
  const char* library;  // as the error messages name it
  Decompress decompress;
  std::function<std::vector<uint8_t>(const std::vector<uint8_t>&)> compress;
};

std::vector<Codec> Codecs() {
  return {
      {"zstd", "zstd", DecompressZstd,
       [](const std::vector<uint8_t>& d) { return CompressZstd(d.data(), d.size()); }},
      {"zstd_checksummed", "zstd", DecompressZstd, ZstdChecksummed},
      {"lz4", "lz4", DecompressLz4Frame,
       [](const std::vector<uint8_t>& d) { return CompressLz4Frame(d.data(), d.size()); }},
      {"lz4_checksummed", "lz4", DecompressLz4Frame, Lz4Checksummed},
      {"bz2", "bz2", DecompressBz2, Bz2},
  };
}

// Sizes around the decompressor's 1 MiB growth step and a tiny one.
const size_t kSizes[] = {1,
                         1000,
                         (size_t(1) << 20) - 1,
                         size_t(1) << 20,
                         (size_t(1) << 20) + 1,
                         3 * (size_t(1) << 20) + 17};

TEST(DriveDecompress, RoundTripsEverySizeAndCodec) {
  for (const Codec& c : Codecs()) {
    for (size_t n : kSizes) {
      for (bool compressible : {true, false}) {
        const std::vector<uint8_t> data = Sample(n, compressible);
        const std::vector<uint8_t> packed = c.compress(data);
        const std::vector<uint8_t> back = c.decompress("chunk", packed.data(), packed.size(), n);
        EXPECT_TRUE(back == data) << c.name << " size " << n << " compressible " << compressible;
      }
    }
  }
}

TEST(DriveDecompress, EmptyPayloadRoundTrips) {
  for (const Codec& c : Codecs()) {
    const std::vector<uint8_t> packed = c.compress({});
    EXPECT_TRUE(c.decompress("chunk", packed.data(), packed.size(), 0).empty()) << c.name;
  }
}

TEST(DriveDecompress, EmptyInputIsAnError) {
  for (const Codec& c : Codecs()) {
    for (size_t expected : {size_t(0), size_t(10)}) {
      const uint8_t none = 0;
      EXPECT_TRUE(ThrowsIoError([&] { c.decompress("x.mcap chunk 3", &none, 0, expected); },
                                "x.mcap chunk 3", {"ends inside"}))
          << c.name << " expected " << expected;
    }
  }
}

TEST(DriveDecompress, ExpectedSizeTooSmallOrTooLargeIsAnError) {
  for (const Codec& c : Codecs()) {
    for (size_t n : {size_t(5000), (size_t(1) << 20) + 3}) {
      const std::vector<uint8_t> data = Sample(n, true);
      const std::vector<uint8_t> packed = c.compress(data);
      EXPECT_TRUE(ThrowsIoError([&] { c.decompress("w", packed.data(), packed.size(), n - 1); },
                                "w", {"more than " + std::to_string(n - 1), c.library}))
          << c.name << " " << n;
      EXPECT_TRUE(ThrowsIoError([&] { c.decompress("w", packed.data(), packed.size(), n + 1); },
                                "w", {c.library}))
          << c.name << " " << n;
      EXPECT_TRUE(ThrowsIoError([&] { c.decompress("w", packed.data(), packed.size(), 0); }, "w",
                                {c.library}))
          << c.name << " " << n;
    }
  }
}

TEST(DriveDecompress, TrailingBytesAfterTheFrameAreAnError) {
  for (const Codec& c : Codecs()) {
    const std::vector<uint8_t> data = Sample(3000, false);
    std::vector<uint8_t> packed = c.compress(data);
    packed.push_back(0x42);
    EXPECT_TRUE(ThrowsIoError([&] { c.decompress("w", packed.data(), packed.size(), 3000); }, "w",
                              {c.library}))
        << c.name;
  }
}

TEST(DriveDecompress, TruncatedDataIsAnErrorAtEveryCut) {
  for (const Codec& c : Codecs()) {
    for (bool compressible : {true, false}) {
      const size_t n = 200000;
      const std::vector<uint8_t> data = Sample(n, compressible);
      const std::vector<uint8_t> packed = c.compress(data);
      const size_t step = std::max<size_t>(1, packed.size() / 300);
      for (size_t cut = 0; cut < packed.size();
           cut += (cut < 64 || packed.size() - cut < 64) ? 1 : step) {
        bool threw = false;
        try {
          c.decompress("t", packed.data(), cut, n);
        } catch (const IoError& e) {
          threw = std::string(e.what()).rfind("t: ", 0) == 0;
        }
        EXPECT_TRUE(threw) << c.name << " cut at " << cut << " of " << packed.size();
      }
    }
  }
}

TEST(DriveDecompress, CorruptDataIsAnErrorOrTheWrongSize) {
  // Flipping a byte makes the decoder fail or (where the format has no checksum) decode other
  // bytes; it never returns the original silently with the checksummed codecs, and never crashes.
  for (const Codec& c : Codecs()) {
    const size_t n = 100000;
    const std::vector<uint8_t> data = Sample(n, true);
    const std::vector<uint8_t> packed = c.compress(data);
    const bool checked = std::strstr(c.name, "checksummed") || std::strcmp(c.name, "bz2") == 0;
    size_t errors = 0, flips = 0;
    for (size_t at = 0; at < packed.size(); at += 1 + packed.size() / 200) {
      std::vector<uint8_t> bad = packed;
      bad[at] ^= 0x5A;
      ++flips;
      try {
        const std::vector<uint8_t> back = c.decompress("c", bad.data(), bad.size(), n);
        EXPECT_EQ(back.size(), n);
        if (checked) {
          EXPECT_TRUE(back == data) << c.name << " flip at " << at << " went unseen";
        }
      } catch (const IoError& e) {
        ++errors;
        EXPECT_EQ(std::string(e.what()).rfind("c: ", 0), 0u) << e.what();
      }
    }
    EXPECT_GT(errors, flips / 2) << c.name;
  }
}

TEST(DriveDecompress, HugeExpectedSizeCostsNothingUntilReal) {
  // A record claiming 1 TiB for 1000 real bytes: an error about the size, not an allocation.
  for (const Codec& c : Codecs()) {
    const std::vector<uint8_t> data = Sample(1000, true);
    const std::vector<uint8_t> packed = c.compress(data);
    const size_t largest = test::LargestAllocationDuring([&] {
      EXPECT_TRUE(
          ThrowsIoError([&] { c.decompress("h", packed.data(), packed.size(), size_t(1) << 40); },
                        "h", {c.library, "1000 bytes"}))
          << c.name;
    });
    EXPECT_LE(largest, size_t(4) << 20) << c.name;
  }
}

TEST(DriveDecompress, Crc32MatchesTheStandardCheckValue) {
  const char* check = "123456789";
  EXPECT_EQ(Crc32(reinterpret_cast<const uint8_t*>(check), 9), 0xCBF43926u);
  EXPECT_EQ(Crc32(nullptr, 0), 0u);
  // Continuing from a partial CRC equals one pass.
  const std::vector<uint8_t> data = Sample(10007, false);
  const uint32_t whole = Crc32(data.data(), data.size());
  EXPECT_EQ(Crc32(data.data() + 5000, data.size() - 5000, Crc32(data.data(), 5000)), whole);
  std::vector<uint8_t> flipped = data;
  flipped[777] ^= 1;
  EXPECT_NE(Crc32(flipped.data(), flipped.size()), whole);
}

}  // namespace
}  // namespace lpir
