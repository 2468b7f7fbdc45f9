// The parts of a ROS 1 bag (format 2.0) that the topic reader (ros1_bag_reader.cpp) and the
// whole-drive reader (ros1_bag_content.cpp) read alike: the magic, the op codes, a record's
// header fields, a record's place in the file or inside a chunk, a chunk decompressed. Integers are
// little-endian; a time is uint32 sec, uint32 nsec.
#pragma once
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "host/drive/read_only_file.h"

namespace lpir::ros1 {

constexpr char kMagic[] = "#ROSBAG V2.0\n";
constexpr size_t kMagicSize = sizeof(kMagic) - 1;

enum Op : uint8_t {
  kOpMessage = 0x02,
  kOpBagHeader = 0x03,
  kOpIndexData = 0x04,
  kOpChunk = 0x05,
  kOpChunkInfo = 0x06,
  kOpConnection = 0x07,
};

// A damaged or malformed part; what() says where (without the file name) and what.
class Broken : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

inline uint32_t LeU32(const uint8_t* p) {
  return uint32_t(p[0]) | uint32_t(p[1]) << 8 | uint32_t(p[2]) << 16 | uint32_t(p[3]) << 24;
}
inline uint64_t LeU64(const uint8_t* p) {
  return uint64_t(LeU32(p)) | uint64_t(LeU32(p + 4)) << 32;
}
// A ROS time (uint32 sec, uint32 nsec) in nanoseconds.
inline uint64_t TimeNs(const uint8_t* p) { return uint64_t(LeU32(p)) * 1000000000u + LeU32(p + 4); }

// The fields of a record header (or of a connection header): name=value, each name once.
class Fields {
 public:
  // Throws Broken(`at` + problem) for a field running past `size`, one without '=' or a name
  // given twice.
  Fields(const std::string& at, const uint8_t* p, size_t size) : at_(at) {
    size_t pos = 0;
    while (pos < size) {
      if (size - pos < 4) Fail("header ends inside a field length");
      const uint32_t len = LeU32(p + pos);
      pos += 4;
      if (len > size - pos)
        Fail("header field of " + std::to_string(len) + " bytes runs past the header's end");
      const std::string field(reinterpret_cast<const char*>(p + pos), len);
      pos += len;
      const size_t eq = field.find('=');
      if (eq == std::string::npos) Fail("header field without '='");
      std::string name = field.substr(0, eq);
      for (const auto& f : fields_)
        if (f.first == name) Fail("header field '" + name + "' given twice");
      fields_.emplace_back(std::move(name), field.substr(eq + 1));
    }
  }

  bool Has(const std::string& name) const { return Find(name) != nullptr; }
  // Every field in the order stored.
  const std::vector<std::pair<std::string, std::string>>& all() const { return fields_; }
  const std::string& String(const std::string& name) const {
    const std::string* v = Find(name);
    if (!v) Fail("header has no '" + name + "' field");
    return *v;
  }
  uint8_t Op() const { return Sized(String("op"), "op", 1)[0]; }
  uint32_t U32(const std::string& name) const { return LeU32(Sized(String(name), name, 4)); }
  uint64_t U64(const std::string& name) const { return LeU64(Sized(String(name), name, 8)); }
  uint64_t Time(const std::string& name) const { return TimeNs(Sized(String(name), name, 8)); }

  [[noreturn]] void Fail(const std::string& what) const { throw Broken(at_ + ": " + what); }

 private:
  const std::string* Find(const std::string& name) const {
    for (const auto& f : fields_)
      if (f.first == name) return &f.second;
    return nullptr;
  }
  const uint8_t* Sized(const std::string& value, const std::string& name, size_t size) const {
    if (value.size() != size)
      Fail("header field '" + name + "' has " + std::to_string(value.size()) + " bytes, not " +
           std::to_string(size));
    return reinterpret_cast<const uint8_t*>(value.data());
  }

  std::string at_;
  std::vector<std::pair<std::string, std::string>> fields_;
};

// A record inside decompressed chunk data: its header's fields and where its data lies.
struct ChunkRecord {
  Fields fields;
  size_t data_pos = 0;
  uint32_t data_len = 0;
};

// The record of chunk data `d` at `pos` (at most d.size()), its lengths checked against the
// chunk, in this order: Broken(`at` + the problem) when the chunk ends inside its lengths or its
// header, when the header is malformed (Fields), or when the chunk ends inside its data.
ChunkRecord RecordInChunk(const std::vector<uint8_t>& d, size_t pos, const std::string& at);

// A record's place in the file and its header.
struct Record {
  uint64_t pos = 0;       // of header_len
  uint64_t data_pos = 0;  // of the data, after data_len
  uint32_t data_len = 0;
  bool data_truncated = false;  // the data runs past the end of the file
  uint64_t end() const { return data_pos + data_len; }
};

// IoError naming `path` unless the file starts with the bag 2.0 magic (another version is named).
void CheckMagic(const std::string& path, const ReadOnlyFile& file);

// The record at `pos`: its lengths checked against the file. Broken when the file ends inside
// header_len, the header or data_len; a data_len past the end sets data_truncated.
Record ReadRecordAt(const ReadOnlyFile& file, uint64_t pos);
// The record's header fields (Broken, prefixed with `at`, when malformed).
Fields ReadFields(const ReadOnlyFile& file, const Record& r, const std::string& at);
// The record's data; Broken when it runs past the end of the file.
std::vector<uint8_t> ReadData(const ReadOnlyFile& file, const Record& r);

// True for the chunk a recorder was writing when it died, in a bag without an index
// (`unindexed`: index_pos 0, what a recorder leaves as NAME.bag.active): a chunk record whose size
// and data length are still the zeros written before its data, with bytes after it (a finished
// chunk holds at least one message).
bool UnfinishedChunk(const ReadOnlyFile& file, const Record& r, const Fields& f, bool unindexed);

struct LoadedChunk {
  std::vector<uint8_t> data;  // uncompressed (of a truncated uncompressed chunk: what is there)
  std::string damage;         // empty when whole
};
// The chunk record at `pos` decompressed (none, bz2, lz4); its damage ("<where>: <problem>") when
// it is not a chunk record, has an unknown compression, a size that disagrees, data cut by the end
// of the file or that does not decompress. In an `unindexed` bag an unfinished chunk
// (UnfinishedChunk) is taken to run to the end of the file, as a truncated one: its data when
// uncompressed (at most 1 GiB), else damage.
LoadedChunk LoadChunk(const ReadOnlyFile& file, uint64_t pos, const std::string& where,
                      bool unindexed);

}  // namespace lpir::ros1
