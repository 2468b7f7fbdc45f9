// The parts of an MCAP file both MCAP readers read (see mcap_file.h).
#include "host/drive/mcap_file.h"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <vector>

#include "host/drive/decompress.h"
#include "host/io/io_error.h"

namespace lpir::mcap {

Opening OpenFile(const std::string& path, const ReadOnlyFile& file) {
  uint8_t magic[kMagicSize] = {};
  if (file.size() < kMagicSize + kRecordPrefix) {
    throw IoError(path, "not an MCAP file: " + std::to_string(file.size()) +
                            " bytes, too short for the magic and a header record");
  }
  file.ReadInto(0, magic, sizeof(magic));
  if (std::memcmp(magic, kMagic, sizeof(magic)) != 0) {
    throw IoError(path, "not an MCAP file: the first 8 bytes are not the MCAP magic");
  }
  uint8_t op = 0;
  uint64_t length = 0;
  if (RecordAt(file, kMagicSize, &op, &length) != kWhole || op != kHeader) {
    throw IoError(path, "no intact header record after the magic");
  }
  // Its two strings; a header past 1 MiB is read no further than that.
  const std::vector<uint8_t> header =
      file.Bytes(kMagicSize + kRecordPrefix, std::min<uint64_t>(length, uint64_t(1) << 20));
  Opening opening;
  try {
    In in(header.data(), header.size());
    opening.profile = in.Str("header profile");
    in.Str("header library");
  } catch (const Malformed& e) {
    throw IoError(path, std::string("header record: ") + e.what());
  }
  opening.data_start = kMagicSize + kRecordPrefix + length;
  return opening;
}

RecordState RecordAt(const ReadOnlyFile& file, uint64_t pos, uint8_t* op, uint64_t* length) {
  if (pos == file.size()) return kEndOfFile;
  if (file.size() - pos < kRecordPrefix) return kCutPrefix;
  uint8_t prefix[kRecordPrefix];
  file.ReadInto(pos, prefix, sizeof(prefix));
  In in(prefix, sizeof(prefix));
  *op = in.U8("opcode");
  *length = in.U64("length");
  return *length > file.size() - pos - kRecordPrefix ? kCutContent : kWhole;
}

std::string ReadChunk(const std::string& where, const uint8_t* data, size_t size, bool cut,
                      const RecordVisitor& visit) {
  uint64_t uncompressed_size = 0, stored = 0;
  uint32_t crc = 0;
  std::string compression;
  const uint8_t* records = nullptr;
  try {
    In in(data, size);
    in.U64("message_start_time");
    in.U64("message_end_time");
    uncompressed_size = in.U64("uncompressed_size");
    crc = in.U32("uncompressed_crc");
    compression = in.Str("compression");
    stored = in.U64("records length");
    if (cut && stored > in.left()) {
      if (!compression.empty()) return where + ": its compressed records are cut";
      stored = in.left();
      uncompressed_size = stored;
      crc = 0;
    }
    records = in.Take(stored, "records");
  } catch (const Malformed& e) {
    return where + ": malformed chunk: " + e.what();
  }
  if (uncompressed_size > kMaxChunkBytes) {
    return where + ": the " + (compression.empty() ? std::string("uncompressed") : compression) +
           " chunk claims " + std::to_string(uncompressed_size) +
           " bytes uncompressed, more than the " + std::to_string(kMaxChunkBytes) +
           " this reader accepts";
  }
  std::vector<uint8_t> unpacked;
  const uint8_t* plain = records;
  size_t plain_size = size_t(stored);
  try {
    if (compression == "zstd") {
      unpacked = DecompressZstd(where, records, stored, size_t(uncompressed_size));
    } else if (compression == "lz4") {
      unpacked = DecompressLz4Frame(where, records, stored, size_t(uncompressed_size));
    } else if (!compression.empty()) {
      return where + ": unknown compression '" + compression + "'";
    } else if (stored != uncompressed_size) {
      return where + ": uncompressed records of " + std::to_string(stored) +
             " bytes, the chunk says " + std::to_string(uncompressed_size);
    }
  } catch (const IoError& e) {
    return std::string(e.what());  // "<where>: <library reason>"
  }
  if (!compression.empty()) {
    plain = unpacked.data();
    plain_size = unpacked.size();
  }
  if (crc != 0) {
    const uint32_t got = Crc32(plain, plain_size);
    if (got != crc) {
      char text[64];
      std::snprintf(text, sizeof(text), "CRC mismatch (records 0x%08x, the chunk says 0x%08x)", got,
                    crc);
      return where + ": " + text;
    }
  }
  size_t pos = 0;
  while (pos < plain_size) {
    if (plain_size - pos < kRecordPrefix) {
      return cut ? "" : where + ": a record prefix cut at chunk byte " + std::to_string(pos);
    }
    In prefix(plain + pos, kRecordPrefix);
    const uint8_t op = prefix.U8("opcode");
    const uint64_t length = prefix.U64("length");
    const size_t content = pos + kRecordPrefix;
    if (length > plain_size - content) {
      return cut ? ""
                 : where + ": a record of " + std::to_string(length) + " bytes at chunk byte " +
                       std::to_string(pos) + " overruns the chunk";
    }
    try {
      In r(plain + content, size_t(length));
      visit(op, &r);
    } catch (const Malformed& e) {
      return where + ": malformed record of opcode " + std::to_string(op) + " at chunk byte " +
             std::to_string(pos) + ": " + e.what();
    }
    pos = content + size_t(length);
  }
  return "";
}

std::string ChunkWhere(uint64_t number, uint64_t offset) {
  return "chunk " + std::to_string(number) + " at byte " + std::to_string(offset);
}

bool ScanRecord(const ReadOnlyFile& file, Scan* scan, std::initializer_list<uint8_t> read,
                const RecordVisitor& visit, std::string* damage) {
  damage->clear();
  uint8_t op = 0;
  uint64_t length = 0;
  const uint64_t pos = scan->pos;
  const RecordState state = RecordAt(file, pos, &op, &length);
  if (state == kEndOfFile) {
    *damage = "the file ends at byte " + std::to_string(pos) +
              " without a data end or footer record (truncated)";
    return false;
  }
  if (state == kCutPrefix) {
    *damage = "byte " + std::to_string(pos) + ": the file ends inside a record prefix (truncated)";
    return false;
  }
  const uint64_t content = pos + kRecordPrefix;
  const uint64_t left = file.size() - content;
  if (op == kChunk) {
    const uint64_t number = ++scan->chunks;
    const std::string where = ChunkWhere(number, pos);
    if (state == kCutContent) {
      // The bytes there are, bounded by the chunk limit: an uncompressed chunk's complete
      // messages before the cut are still read.
      const std::vector<uint8_t> bytes =
          file.Bytes(content, std::min<uint64_t>(left, kMaxChunkBytes + 4096));
      std::string problem = ReadChunk(where, bytes.data(), bytes.size(), true, visit);
      *damage = where + ": the file ends inside the chunk (" + std::to_string(length) + " bytes, " +
                std::to_string(left) + " left; truncated)" +
                (problem.empty() ? "" : "; " + problem.substr(where.size() + 2));
      return false;
    }
    const std::vector<uint8_t> bytes = file.Bytes(content, length);
    *damage = ReadChunk(where, bytes.data(), bytes.size(), false, visit);
    scan->pos = content + length;
    return true;
  }
  if (state == kCutContent) {
    *damage = "byte " + std::to_string(pos) + ": the file ends inside a record of opcode " +
              std::to_string(op) + " (" + std::to_string(length) + " bytes, " +
              std::to_string(left) + " left; truncated)";
    return false;
  }
  scan->pos = content + length;
  if (op == kDataEnd || op == kFooter) return false;
  if (std::find(read.begin(), read.end(), op) == read.end()) return true;
  const std::vector<uint8_t> bytes = file.Bytes(content, length);
  try {
    In r(bytes.data(), bytes.size());
    visit(op, &r);
  } catch (const Malformed& e) {
    *damage = "byte " + std::to_string(pos) + ": malformed record of opcode " + std::to_string(op) +
              ": " + e.what();
  }
  return true;
}

}  // namespace lpir::mcap
