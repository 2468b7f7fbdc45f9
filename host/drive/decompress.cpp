#include "host/drive/decompress.h"

#include <bzlib.h>
#include <lz4frame.h>
#include <zlib.h>
#include <zstd.h>

#include <algorithm>
#include <memory>
#include <stdexcept>

#include "host/io/io_error.h"

namespace lpir {
namespace {

// The output grows as the library fills it, never past `expected_size`: a header that claims a
// huge size costs memory only once the data really decompresses to it.
constexpr size_t kGrowStep = size_t(1) << 20;

// One call of a library's streaming decoder: decodes into dst[0, room) from the input left,
// sets *produced, returns true once the stream (frame) has ended; throws IoError on bad data.
struct Decoder {
  virtual ~Decoder() = default;
  virtual bool Step(uint8_t* dst, size_t room, size_t* produced) = 0;
  virtual size_t InputLeft() const = 0;
};

// Runs `decoder` to the end of its stream, the output growing by kGrowStep up to expected_size.
// Once expected_size bytes are out, it goes on into a 1-byte probe: a byte there means the data
// holds more than the record says; the stream ending without one means the size is exact (what
// is left of the stream then is its end mark or checksum). IoError naming `where` and `library`
// for data that ends inside the stream (the decoder asks for more and moves no byte), bytes after
// the stream's end, or a size other than expected_size.
std::vector<uint8_t> Run(const std::string& where, const char* library, Decoder* decoder,
                         size_t in_size, size_t expected_size) {
  std::vector<uint8_t> out(std::min(expected_size, std::max(kGrowStep, 4 * in_size)));
  size_t filled = 0;
  for (;;) {
    const bool at_limit = filled == expected_size;
    if (!at_limit && filled == out.size()) {
      out.resize(std::min(expected_size, out.size() + kGrowStep));
    }
    uint8_t probe = 0;
    const size_t in_before = decoder->InputLeft();
    size_t produced = 0;
    const bool ended = at_limit
                           ? decoder->Step(&probe, 1, &produced)
                           : decoder->Step(out.data() + filled, out.size() - filled, &produced);
    if (at_limit && produced > 0) {
      throw IoError(where, std::string(library) + " data decompresses to more than " +
                               std::to_string(expected_size) + " bytes, the record says " +
                               std::to_string(expected_size));
    }
    filled += produced;
    if (ended) break;
    if (produced == 0 && decoder->InputLeft() == in_before) {
      throw IoError(where, std::string(library) +
                               (in_before == 0 ? ": data ends inside a frame"
                                               : ": the decoder makes no progress (corrupt data)"));
    }
  }
  if (decoder->InputLeft() != 0) {
    throw IoError(where, std::string(library) + ": " + std::to_string(decoder->InputLeft()) +
                             " bytes follow the end of the compressed data");
  }
  if (filled != expected_size) {
    throw IoError(where, std::string(library) + " data decompresses to " + std::to_string(filled) +
                             " bytes, the record says " + std::to_string(expected_size));
  }
  out.resize(filled);
  return out;
}

class ZstdDecoder : public Decoder {
 public:
  ZstdDecoder(const std::string& where, const uint8_t* data, size_t size)
      : where_(where), stream_(ZSTD_createDStream(), ZSTD_freeDStream), in_{data, size, 0} {
    if (!stream_) throw IoError(where, "zstd: out of memory");
  }
  bool Step(uint8_t* dst, size_t room, size_t* produced) override {
    ZSTD_outBuffer o{dst, room, 0};
    const size_t r = ZSTD_decompressStream(stream_.get(), &o, &in_);
    if (ZSTD_isError(r)) throw IoError(where_, std::string("zstd: ") + ZSTD_getErrorName(r));
    *produced = o.pos;
    return r == 0;  // a frame ended and is flushed
  }
  size_t InputLeft() const override { return in_.size - in_.pos; }

 private:
  const std::string& where_;
  std::unique_ptr<ZSTD_DStream, size_t (*)(ZSTD_DStream*)> stream_;
  ZSTD_inBuffer in_;
};

class Lz4Decoder : public Decoder {
 public:
  Lz4Decoder(const std::string& where, const uint8_t* data, size_t size)
      : where_(where), ctx_(nullptr, LZ4F_freeDecompressionContext), data_(data), size_(size) {
    LZ4F_dctx* raw = nullptr;
    if (LZ4F_isError(LZ4F_createDecompressionContext(&raw, LZ4F_VERSION)))
      throw IoError(where, "lz4: out of memory");
    ctx_.reset(raw);
  }
  bool Step(uint8_t* dst, size_t room, size_t* produced) override {
    size_t in_room = size_ - pos_;
    const size_t r = LZ4F_decompress(ctx_.get(), dst, &room, data_ + pos_, &in_room, nullptr);
    if (LZ4F_isError(r)) throw IoError(where_, std::string("lz4: ") + LZ4F_getErrorName(r));
    pos_ += in_room;
    *produced = room;
    return r == 0;  // a frame ended
  }
  size_t InputLeft() const override { return size_ - pos_; }

 private:
  const std::string& where_;
  std::unique_ptr<LZ4F_dctx, size_t (*)(LZ4F_dctx*)> ctx_;
  const uint8_t* data_;
  size_t size_, pos_ = 0;
};

class Bz2Decoder : public Decoder {
 public:
  Bz2Decoder(const std::string& where, const uint8_t* data, size_t size)
      : where_(where), data_(data), size_(size) {
    if (BZ2_bzDecompressInit(&s_, 0, 0) != BZ_OK) throw IoError(where, "bz2: out of memory");
  }
  ~Bz2Decoder() override { BZ2_bzDecompressEnd(&s_); }
  bool Step(uint8_t* dst, size_t room, size_t* produced) override {
    // bzlib counts in unsigned int: feed and drain at most 1 GiB a call.
    const size_t in_now = std::min<size_t>(size_ - pos_, size_t(1) << 30);
    const size_t out_now = std::min<size_t>(room, size_t(1) << 30);
    s_.next_in = const_cast<char*>(reinterpret_cast<const char*>(data_ + pos_));
    s_.avail_in = unsigned(in_now);
    s_.next_out = reinterpret_cast<char*>(dst);
    s_.avail_out = unsigned(out_now);
    const int r = BZ2_bzDecompress(&s_);
    pos_ += in_now - s_.avail_in;
    *produced = out_now - s_.avail_out;
    if (r == BZ_STREAM_END) return true;
    if (r != BZ_OK) throw IoError(where_, "bz2: corrupt data (code " + std::to_string(r) + ")");
    return false;
  }
  size_t InputLeft() const override { return size_ - pos_; }

 private:
  const std::string& where_;
  bz_stream s_{};
  const uint8_t* data_;
  size_t size_, pos_ = 0;
};

}  // namespace

std::vector<uint8_t> DecompressZstd(const std::string& where, const uint8_t* data, size_t size,
                                    size_t expected_size) {
  ZstdDecoder decoder(where, data, size);
  return Run(where, "zstd", &decoder, size, expected_size);
}

std::vector<uint8_t> DecompressLz4Frame(const std::string& where, const uint8_t* data, size_t size,
                                        size_t expected_size) {
  Lz4Decoder decoder(where, data, size);
  return Run(where, "lz4", &decoder, size, expected_size);
}

std::vector<uint8_t> DecompressBz2(const std::string& where, const uint8_t* data, size_t size,
                                   size_t expected_size) {
  Bz2Decoder decoder(where, data, size);
  return Run(where, "bz2", &decoder, size, expected_size);
}

std::vector<uint8_t> CompressZstd(const uint8_t* data, size_t size) {
  std::vector<uint8_t> out(ZSTD_compressBound(size));
  const size_t n = ZSTD_compress(out.data(), out.size(), data, size, 3);
  if (ZSTD_isError(n)) throw std::runtime_error(std::string("zstd: ") + ZSTD_getErrorName(n));
  out.resize(n);
  return out;
}

std::vector<uint8_t> CompressLz4Frame(const uint8_t* data, size_t size) {
  LZ4F_preferences_t prefs{};  // roslz4 needs independent blocks and the content checksum
  prefs.frameInfo.blockMode = LZ4F_blockIndependent;
  prefs.frameInfo.contentChecksumFlag = LZ4F_contentChecksumEnabled;
  std::vector<uint8_t> out(LZ4F_compressFrameBound(size, &prefs));
  const size_t n = LZ4F_compressFrame(out.data(), out.size(), data, size, &prefs);
  if (LZ4F_isError(n)) throw std::runtime_error(std::string("lz4: ") + LZ4F_getErrorName(n));
  out.resize(n);
  return out;
}

uint32_t Crc32(const uint8_t* data, size_t size, uint32_t crc) {
  return uint32_t(crc32_z(crc, data, size));
}

}  // namespace lpir
