// The parts of a ROS 1 bag both bag readers read (see ros1_bag_file.h).
#include "host/drive/ros1_bag_file.h"

#include <algorithm>

#include "host/drive/decompress.h"
#include "host/io/io_error.h"

namespace lpir::ros1 {

// The most an unfinished chunk is read to (a recorder closes its chunks at 768 KiB by default).
constexpr uint64_t kMaxUnfinishedBytes = uint64_t(1) << 30;

// The record of chunk data `d` at `pos` (at most d.size()), its lengths checked against the
// chunk, in this order: Broken(`at` + the problem) when the chunk ends inside its lengths or its
// header, when the header is malformed (Fields), or when the chunk ends inside its data.
ChunkRecord RecordInChunk(const std::vector<uint8_t>& d, size_t pos, const std::string& at) {
  if (d.size() - pos < 4) throw Broken(at + ": the chunk ends inside a record");
  const uint32_t header_len = LeU32(&d[pos]);
  if (header_len > d.size() - pos - 4 || d.size() - pos - 4 - header_len < 4)
    throw Broken(at + ": the chunk ends inside a record header");
  Fields fields(at, &d[pos + 4], header_len);
  const size_t data_pos = pos + 8 + header_len;
  const uint32_t data_len = LeU32(&d[data_pos - 4]);
  if (data_len > d.size() - data_pos) throw Broken(at + ": the chunk ends inside a record's data");
  return ChunkRecord{std::move(fields), data_pos, data_len};
}

void CheckMagic(const std::string& path, const ReadOnlyFile& file) {
  uint8_t head[kMagicSize] = {};
  const size_t n = size_t(std::min<uint64_t>(kMagicSize, file.size()));
  try {
    file.ReadInto(0, head, n);
  } catch (const Broken& e) {
    throw IoError(path, e.what());
  }
  const std::string got(reinterpret_cast<const char*>(head), n);
  if (got == kMagic) return;
  const std::string prefix = "#ROSBAG V";
  if (got.compare(0, prefix.size(), prefix) == 0) {
    const std::string version = got.substr(prefix.size(), got.find('\n') - prefix.size());
    throw IoError(path, "ROS bag version '" + version + "' is not supported (only 2.0)");
  }
  throw IoError(path, "not a ROS bag: it does not start with #ROSBAG V2.0");
}

Record ReadRecordAt(const ReadOnlyFile& file, uint64_t pos) {
  const uint64_t size = file.size();
  const std::string at = "byte " + std::to_string(pos);
  uint8_t len[4];
  if (pos > size || size - pos < 4) throw Broken(at + ": the file ends inside a record");
  file.ReadInto(pos, len, 4);
  const uint32_t header_len = LeU32(len);
  if (header_len > size - pos - 4 || size - pos - 4 - header_len < 4)
    throw Broken(at + ": the file ends inside a record header (" + std::to_string(header_len) +
                 " bytes claimed, " + std::to_string(size - pos - 4) + " left)");
  Record r;
  r.pos = pos;
  file.ReadInto(pos + 4 + header_len, len, 4);
  r.data_pos = pos + 8 + header_len;
  r.data_len = LeU32(len);
  r.data_truncated = r.data_len > size - r.data_pos;
  return r;
}

Fields ReadFields(const ReadOnlyFile& file, const Record& r, const std::string& at) {
  const uint32_t header_len = uint32_t(r.data_pos - r.pos - 8);
  const std::vector<uint8_t> header = file.Bytes(r.pos + 4, header_len);
  return Fields(at, header.data(), header.size());
}

std::vector<uint8_t> ReadData(const ReadOnlyFile& file, const Record& r) {
  if (r.data_truncated)
    throw Broken("byte " + std::to_string(r.pos) + ": the file ends inside the record's data (" +
                 std::to_string(r.data_len) + " bytes claimed, " +
                 std::to_string(file.size() - r.data_pos) + " left)");
  return file.Bytes(r.data_pos, r.data_len);
}

bool UnfinishedChunk(const ReadOnlyFile& file, const Record& r, const Fields& f, bool unindexed) {
  if (!unindexed || r.data_len != 0 || r.end() >= file.size()) return false;
  try {
    return f.Op() == kOpChunk && f.U32("size") == 0;
  } catch (const Broken&) {  // a malformed chunk header: damage where it is read
    return false;
  }
}

LoadedChunk LoadChunk(const ReadOnlyFile& file, uint64_t pos, const std::string& where,
                      bool unindexed) {
  LoadedChunk out;
  try {
    const Record r = ReadRecordAt(file, pos);
    const Fields f = ReadFields(file, r, where);
    if (f.Op() != kOpChunk)
      f.Fail("op is " + std::to_string(f.Op()) + ", not chunk 5 (the index points elsewhere)");
    const std::string& compression = f.String("compression");
    const uint32_t size = f.U32("size");
    if (compression != "none" && compression != "bz2" && compression != "lz4")
      f.Fail("unknown compression '" + compression + "'");
    const uint64_t left = file.size() - r.data_pos;
    if (UnfinishedChunk(file, r, f, unindexed)) {
      if (compression != "none")
        f.Fail("the chunk the recorder was writing when it died (its sizes never filled in), " +
               compression + "-compressed: its messages cannot be read");
      if (left > kMaxUnfinishedBytes)
        f.Fail("the chunk the recorder was writing when it died runs " + std::to_string(left) +
               " bytes to the end of the file, more than a recorder's chunk");
      out.data = file.Bytes(r.data_pos, left);
      return out;
    }
    if (compression == "none" && r.data_len != size)
      f.Fail("uncompressed chunk holds " + std::to_string(r.data_len) +
             " bytes, its size field says " + std::to_string(size));
    if (r.data_truncated) {
      if (compression == "none") out.data = file.Bytes(r.data_pos, left);
      f.Fail("the file ends inside the chunk's data (" + std::to_string(left) + " of " +
             std::to_string(r.data_len) + " bytes there: truncated)");
    }
    std::vector<uint8_t> data = file.Bytes(r.data_pos, r.data_len);
    if (compression == "none") {
      out.data = std::move(data);
    } else if (compression == "bz2") {
      out.data = DecompressBz2(where, data.data(), data.size(), size);
    } else {
      out.data = DecompressLz4Frame(where, data.data(), data.size(), size);
    }
  } catch (const Broken& e) {
    out.damage = e.what();
  } catch (const IoError& e) {  // the decompressors name `where`
    out.damage = e.what();
  }
  return out;
}

}  // namespace lpir::ros1
