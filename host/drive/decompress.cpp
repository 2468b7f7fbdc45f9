#include "host/drive/decompress.h"

#include <bzlib.h>
#include <lz4frame.h>
#include <zstd.h>

#include <algorithm>
#include <array>
#include <memory>
#include <stdexcept>

#include "host/io/io_error.h"

namespace lpir {
namespace {

// The output grows as the library fills it, never past `expected_size`: a header that claims a
// huge size costs memory only once the data really decompresses to it.
constexpr size_t kGrowStep = size_t(1) << 20;

void Grow(std::vector<uint8_t>* out, size_t filled, size_t expected_size) {
  if (out->size() - filled == 0) out->resize(std::min(expected_size, out->size() + kGrowStep));
}

std::vector<uint8_t> StartOutput(size_t size, size_t expected_size) {
  std::vector<uint8_t> out;
  out.resize(std::min(expected_size, std::max(kGrowStep, 4 * size)));
  return out;
}

[[noreturn]] void SizeMismatch(const std::string& where, const char* what, size_t got,
                               size_t expected) {
  throw IoError(
      where, std::string(what) + " data decompresses to " +
                 (got > expected ? "more than " + std::to_string(expected) : std::to_string(got)) +
                 " bytes, the record says " + std::to_string(expected));
}

}  // namespace

std::vector<uint8_t> DecompressZstd(const std::string& where, const uint8_t* data, size_t size,
                                    size_t expected_size) {
  std::unique_ptr<ZSTD_DStream, size_t (*)(ZSTD_DStream*)> stream(ZSTD_createDStream(),
                                                                  ZSTD_freeDStream);
  if (!stream) throw IoError(where, "zstd: out of memory");
  std::vector<uint8_t> out = StartOutput(size, expected_size);
  ZSTD_inBuffer in{data, size, 0};
  size_t filled = 0;
  for (;;) {
    ZSTD_outBuffer o{out.data(), out.size(), filled};
    const size_t r = ZSTD_decompressStream(stream.get(), &o, &in);
    if (ZSTD_isError(r)) throw IoError(where, std::string("zstd: ") + ZSTD_getErrorName(r));
    filled = o.pos;
    if (r == 0) break;  // a frame ended
    if (in.pos == in.size && filled < out.size())
      throw IoError(where, "zstd: data ends inside a frame");
    if (filled == expected_size) SizeMismatch(where, "zstd", filled + 1, expected_size);
    Grow(&out, filled, expected_size);
  }
  if (in.pos != in.size || filled != expected_size)
    SizeMismatch(where, "zstd", in.pos != in.size ? expected_size + 1 : filled, expected_size);
  out.resize(filled);
  return out;
}

std::vector<uint8_t> DecompressLz4Frame(const std::string& where, const uint8_t* data, size_t size,
                                        size_t expected_size) {
  LZ4F_dctx* raw = nullptr;
  if (LZ4F_isError(LZ4F_createDecompressionContext(&raw, LZ4F_VERSION)))
    throw IoError(where, "lz4: out of memory");
  std::unique_ptr<LZ4F_dctx, size_t (*)(LZ4F_dctx*)> ctx(raw, LZ4F_freeDecompressionContext);
  std::vector<uint8_t> out = StartOutput(size, expected_size);
  size_t in_pos = 0, filled = 0;
  for (;;) {
    size_t out_room = out.size() - filled, in_room = size - in_pos;
    const size_t r = LZ4F_decompress(ctx.get(), out.data() + filled, &out_room, data + in_pos,
                                     &in_room, nullptr);
    if (LZ4F_isError(r)) throw IoError(where, std::string("lz4: ") + LZ4F_getErrorName(r));
    in_pos += in_room;
    filled += out_room;
    if (r == 0) break;  // a frame ended
    if (in_pos == size && out_room == 0) throw IoError(where, "lz4: data ends inside a frame");
    if (filled == out.size()) {
      if (filled == expected_size) SizeMismatch(where, "lz4", filled + 1, expected_size);
      Grow(&out, filled, expected_size);
    }
  }
  if (in_pos != size || filled != expected_size)
    SizeMismatch(where, "lz4", in_pos != size ? expected_size + 1 : filled, expected_size);
  out.resize(filled);
  return out;
}

std::vector<uint8_t> DecompressBz2(const std::string& where, const uint8_t* data, size_t size,
                                   size_t expected_size) {
  bz_stream s{};
  if (BZ2_bzDecompressInit(&s, 0, 0) != BZ_OK) throw IoError(where, "bz2: out of memory");
  std::unique_ptr<bz_stream, int (*)(bz_stream*)> guard(&s, BZ2_bzDecompressEnd);
  std::vector<uint8_t> out = StartOutput(size, expected_size);
  s.next_in = const_cast<char*>(reinterpret_cast<const char*>(data));
  s.avail_in = 0;
  size_t in_pos = 0, filled = 0;
  for (;;) {
    // bzlib counts in unsigned int: feed and drain at most 1 GiB a call.
    const size_t in_now = std::min<size_t>(size - in_pos, size_t(1) << 30);
    const size_t out_now = std::min<size_t>(out.size() - filled, size_t(1) << 30);
    s.next_in = const_cast<char*>(reinterpret_cast<const char*>(data + in_pos));
    s.avail_in = unsigned(in_now);
    s.next_out = reinterpret_cast<char*>(out.data() + filled);
    s.avail_out = unsigned(out_now);
    const int r = BZ2_bzDecompress(&s);
    in_pos += in_now - s.avail_in;
    filled += out_now - s.avail_out;
    if (r == BZ_STREAM_END) break;
    if (r != BZ_OK) throw IoError(where, "bz2: corrupt data (code " + std::to_string(r) + ")");
    if (in_pos == size && s.avail_out != 0) throw IoError(where, "bz2: data ends inside a stream");
    if (filled == out.size()) {
      if (filled == expected_size) SizeMismatch(where, "bz2", filled + 1, expected_size);
      Grow(&out, filled, expected_size);
    }
  }
  if (in_pos != size || filled != expected_size)
    SizeMismatch(where, "bz2", in_pos != size ? expected_size + 1 : filled, expected_size);
  out.resize(filled);
  return out;
}

std::vector<uint8_t> CompressZstd(const uint8_t* data, size_t size) {
  std::vector<uint8_t> out(ZSTD_compressBound(size));
  const size_t n = ZSTD_compress(out.data(), out.size(), data, size, 3);
  if (ZSTD_isError(n)) throw std::runtime_error(std::string("zstd: ") + ZSTD_getErrorName(n));
  out.resize(n);
  return out;
}

std::vector<uint8_t> CompressLz4Frame(const uint8_t* data, size_t size) {
  LZ4F_preferences_t prefs{};
  prefs.frameInfo.contentSize = size;
  std::vector<uint8_t> out(LZ4F_compressFrameBound(size, &prefs));
  const size_t n = LZ4F_compressFrame(out.data(), out.size(), data, size, &prefs);
  if (LZ4F_isError(n)) throw std::runtime_error(std::string("lz4: ") + LZ4F_getErrorName(n));
  out.resize(n);
  return out;
}

uint32_t Crc32(const uint8_t* data, size_t size, uint32_t crc) {
  static const auto table = [] {
    std::array<uint32_t, 256> t{};
    for (uint32_t i = 0; i < 256; ++i) {
      uint32_t c = i;
      for (int k = 0; k < 8; ++k) c = (c & 1) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
      t[i] = c;
    }
    return t;
  }();
  crc = ~crc;
  for (size_t i = 0; i < size; ++i) crc = table[(crc ^ data[i]) & 0xFF] ^ (crc >> 8);
  return ~crc;
}

}  // namespace lpir
