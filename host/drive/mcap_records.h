// The MCAP record layout that the reader and the writer share (MCAP specification, major version
// 0): the magic, the opcodes, and little-endian field encoders and decoders. A record is opcode
// (uint8), content length (uint64), content; a String or a Map/Array is prefixed by its uint32 byte
// length.
#pragma once
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

namespace lpir::mcap {

constexpr uint8_t kMagic[8] = {0x89, 'M', 'C', 'A', 'P', '0', '\r', '\n'};
constexpr size_t kMagicSize = sizeof(kMagic);
constexpr size_t kRecordPrefix = 9;    // opcode + uint64 content length
constexpr size_t kFooterContent = 20;  // summary_start, summary_offset_start, summary_crc
constexpr size_t kFooterCrcSpan = 25;  // the footer's bytes up to summary_crc: prefix + 16

enum Op : uint8_t {
  kHeader = 0x01,
  kFooter = 0x02,
  kSchema = 0x03,
  kChannel = 0x04,
  kMessage = 0x05,
  kChunk = 0x06,
  kMessageIndex = 0x07,
  kChunkIndex = 0x08,
  kAttachment = 0x09,
  kAttachmentIndex = 0x0A,
  kStatistics = 0x0B,
  kMetadata = 0x0C,
  kMetadataIndex = 0x0D,
  kSummaryOffset = 0x0E,
  kDataEnd = 0x0F,
};

// Little-endian field encoders appending to a byte buffer.
struct Out {
  std::vector<uint8_t> bytes;

  void U8(uint8_t v) { bytes.push_back(v); }
  void U16(uint16_t v) { Le(v, 2); }
  void U32(uint32_t v) { Le(v, 4); }
  void U64(uint64_t v) { Le(v, 8); }
  void Raw(const void* data, size_t size) {
    const auto* p = static_cast<const uint8_t*>(data);
    bytes.insert(bytes.end(), p, p + size);
  }
  void Str(const std::string& s) {
    U32(uint32_t(s.size()));
    Raw(s.data(), s.size());
  }
  // A Map<string, string>: its uint32 byte length, then each key and value.
  template <typename Pairs>
  void Map(const Pairs& entries) {
    Out map;
    for (const auto& [key, value] : entries) {
      map.Str(key);
      map.Str(value);
    }
    U32(uint32_t(map.bytes.size()));
    Raw(map.bytes.data(), map.bytes.size());
  }
  // A record: opcode, content length, content.
  void Record(uint8_t op, const Out& content) {
    U8(op);
    U64(content.bytes.size());
    Raw(content.bytes.data(), content.bytes.size());
  }

 private:
  void Le(uint64_t v, int n) {
    for (int i = 0; i < n; ++i) bytes.push_back(uint8_t(v >> (8 * i)));
  }
};

// Thrown by In when a field runs past the end of its record; the reader turns it into an IoError
// or a damage report naming the file and the place.
struct Malformed : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Little-endian field decoders over a record's content; each checks the bytes left first.
class In {
 public:
  In(const uint8_t* data, size_t size) : p_(data), left_(size) {}

  uint8_t U8(const char* field) { return uint8_t(Le(1, field)); }
  uint16_t U16(const char* field) { return uint16_t(Le(2, field)); }
  uint32_t U32(const char* field) { return uint32_t(Le(4, field)); }
  uint64_t U64(const char* field) { return Le(8, field); }
  std::string Str(const char* field) {
    const uint32_t n = U32(field);
    const uint8_t* p = Take(n, field);
    return std::string(reinterpret_cast<const char*>(p), n);
  }
  // `size` bytes, returned in place.
  const uint8_t* Take(uint64_t size, const char* field) {
    if (size > left_) {
      throw Malformed(std::string(field) + " needs " + std::to_string(size) +
                      " bytes, the record has " + std::to_string(left_) + " left");
    }
    const uint8_t* p = p_;
    p_ += size;
    left_ -= size;
    return p;
  }
  size_t left() const { return left_; }

 private:
  uint64_t Le(int n, const char* field) {
    const uint8_t* p = Take(uint64_t(n), field);
    uint64_t v = 0;
    for (int i = 0; i < n; ++i) v |= uint64_t(p[i]) << (8 * i);
    return v;
  }

  const uint8_t* p_;
  size_t left_;
};

}  // namespace lpir::mcap
