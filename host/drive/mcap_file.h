// The parts of an MCAP file that the topic reader (mcap_reader.cpp) and the whole-drive reader
// (mcap_content.cpp) read alike: the leading magic and header record, a record's prefix, and a
// chunk record's content (its header checked, its records decompressed and CRC-checked, then
// walked record by record).
#pragma once
#include <cstddef>
#include <cstdint>
#include <functional>
#include <initializer_list>
#include <string>

#include "host/drive/mcap_records.h"
#include "host/drive/read_only_file.h"

namespace lpir::mcap {

// The largest chunk a reader decompresses: a recorder's chunks are a few MiB; a claim past this
// is damage, not an allocation.
constexpr uint64_t kMaxChunkBytes = uint64_t(1) << 30;

// The leading magic and the header record: the header's profile and the first byte after it.
// IoError naming `path` for a file too short for them, another magic, a header record that is
// missing, cut or malformed.
struct Opening {
  std::string profile;
  uint64_t data_start = 0;
};
Opening OpenFile(const std::string& path, const ReadOnlyFile& file);

// The record prefix at `pos` (<= the file's size): whole, at the end of the file, or cut by it.
enum RecordState { kWhole, kEndOfFile, kCutPrefix, kCutContent };
RecordState RecordAt(const ReadOnlyFile& file, uint64_t pos, uint8_t* op, uint64_t* length);

// Receives each record inside a chunk: its opcode and content. May throw Malformed.
using RecordVisitor = std::function<void(uint8_t op, In* content)>;

// A chunk record's content [data, data + size): reads its header, decompresses its records,
// checks their CRC (when set), then gives each record to `visit` in order. `cut`: the content is
// the part of a chunk before the end of the file (an uncompressed chunk's whole records there are
// still visited). Returns the damage found, "<where>: <problem>" ("" when none): a malformed
// header, a chunk past kMaxChunkBytes, an unknown compression, a size or CRC mismatch, a record
// that overruns the chunk or that `visit` finds malformed; the records before it have been
// visited.
std::string ReadChunk(const std::string& where, const uint8_t* data, size_t size, bool cut,
                      const RecordVisitor& visit);

// "chunk N at byte P": how damage names a chunk (numbered from 1).
std::string ChunkWhere(uint64_t number, uint64_t offset);

// A walk of the records from the header on, one record a step (a file without a usable summary).
struct Scan {
  uint64_t pos = 0;     // the next record
  uint64_t chunks = 0;  // chunk records met so far
};
// One step of `scan`: the record at scan->pos, then scan->pos moves past it. A chunk's records go
// to `visit` (ReadChunk); a record outside chunks whose opcode is in `read` is read and given to
// `visit`, any other skipped unread. Returns false when the scan ends (a data end or footer
// record, the end of the file, a cut record). *damage: the step's damage ("" when none), a
// truncated file or record, a damaged chunk, a record `visit` finds malformed.
bool ScanRecord(const ReadOnlyFile& file, Scan* scan, std::initializer_list<uint8_t> read,
                const RecordVisitor& visit, std::string* damage);

}  // namespace lpir::mcap
