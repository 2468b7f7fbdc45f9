// PCD v0.7 reader (DATA ascii, binary or binary_compressed) and writer. The header is parsed
// strictly; the point records are decoded by host/io/point_fields.
#include "host/io/pcd.h"

#include <cstring>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "host/io/file_bytes.h"
#include "host/io/io_error.h"
#include "host/io/lzf.h"
#include "host/io/point_fields.h"

namespace lpir {

namespace {

// The PCD type for a TYPE letter and a SIZE; false for combinations PCD does not define.
bool PcdScalarType(std::string_view type, uint64_t size, ScalarType* out) {
  static const struct {
    const char* type;
    uint64_t size;
    ScalarType scalar;
  } kTypes[] = {
      {"F", 4, ScalarType::kF32}, {"F", 8, ScalarType::kF64}, {"U", 1, ScalarType::kU8},
      {"U", 2, ScalarType::kU16}, {"U", 4, ScalarType::kU32}, {"U", 8, ScalarType::kU64},
      {"I", 1, ScalarType::kI8},  {"I", 2, ScalarType::kI16}, {"I", 4, ScalarType::kI32},
      {"I", 8, ScalarType::kI64},
  };
  for (const auto& t : kTypes) {
    if (type == t.type && size == t.size) {
      *out = t.scalar;
      return true;
    }
  }
  return false;
}

struct PcdHeader {
  std::vector<std::string_view> fields, sizes, types, counts;
  uint64_t width = 0, height = 1, points = 0;
  bool has_width = false, has_points = false;
  std::string_view data;  // ascii, binary, binary_compressed
  size_t data_line = 0;   // line number of the DATA line
};

// Reads the header lines up to and including DATA; leaves the cursor after it.
PcdHeader ParseHeader(const std::string& path, LineCursor* cursor) {
  PcdHeader header;
  std::set<std::string> seen;
  std::vector<std::string_view> tokens;
  std::string_view line;
  while (header.data.empty()) {
    if (!cursor->Next(&line)) throw IoError(path, "header has no DATA line");
    SplitTokens(line, &tokens);
    if (tokens.empty() || tokens[0][0] == '#') continue;
    const std::string at = "line " + std::to_string(cursor->line_number()) + ": ";
    const std::string key(tokens[0]);
    const std::vector<std::string_view> values(tokens.begin() + 1, tokens.end());
    if (!seen.insert(key).second) throw IoError(path, at + key + " given twice");
    auto count_value = [&](uint64_t* out) {
      if (values.size() != 1 || !ParseCount(values[0], out)) {
        throw IoError(path, at + key + " needs one whole number >= 0");
      }
    };
    if (key == "VERSION") {
      if (values.size() != 1) throw IoError(path, at + "VERSION needs one value");
    } else if (key == "FIELDS") {
      header.fields = values;
    } else if (key == "SIZE") {
      header.sizes = values;
    } else if (key == "TYPE") {
      header.types = values;
    } else if (key == "COUNT") {
      header.counts = values;
    } else if (key == "WIDTH") {
      count_value(&header.width);
      header.has_width = true;
    } else if (key == "HEIGHT") {
      count_value(&header.height);
    } else if (key == "POINTS") {
      count_value(&header.points);
      header.has_points = true;
    } else if (key == "VIEWPOINT") {
      double ignored;
      bool ok = values.size() == 7;
      for (std::string_view v : values) ok = ok && ParseScalarToken(v, ScalarType::kF64, &ignored);
      if (!ok) throw IoError(path, at + "VIEWPOINT needs 7 numbers");
    } else if (key == "DATA") {
      if (values.size() != 1) throw IoError(path, at + "DATA needs one value");
      header.data = values[0];
      header.data_line = cursor->line_number();
    } else {
      throw IoError(path, at + "unknown header keyword " + Quote(key));
    }
  }
  return header;
}

// The columns the header declares, checked field by field.
std::vector<Column> HeaderColumns(const std::string& path, const PcdHeader& header) {
  if (header.fields.empty()) throw IoError(path, "header has no FIELDS line");
  if (header.sizes.empty()) throw IoError(path, "header has no SIZE line");
  if (header.types.empty()) throw IoError(path, "header has no TYPE line");
  const size_t n = header.fields.size();
  auto check_length = [&](const std::vector<std::string_view>& values, const char* key) {
    if (values.size() != n) {
      throw IoError(path, std::string(key) + " has " + std::to_string(values.size()) +
                              " values but FIELDS has " + std::to_string(n));
    }
  };
  check_length(header.sizes, "SIZE");
  check_length(header.types, "TYPE");
  if (!header.counts.empty()) check_length(header.counts, "COUNT");
  std::vector<Column> columns(n);
  for (size_t f = 0; f < n; ++f) {
    Column& column = columns[f];
    column.name = std::string(header.fields[f]);
    uint64_t size = 0;
    if (!ParseCount(header.sizes[f], &size) ||
        !PcdScalarType(header.types[f], size, &column.type)) {
      throw IoError(path, "field " + Quote(column.name) + " has unsupported TYPE " +
                              Quote(header.types[f]) + " with SIZE " + Quote(header.sizes[f]) +
                              " (supported: F 4/8, U and I 1/2/4/8)");
    }
    if (!header.counts.empty() &&
        (!ParseCount(header.counts[f], &column.count) || column.count == 0)) {
      throw IoError(path, "field " + Quote(column.name) + " has COUNT " + Quote(header.counts[f]) +
                              "; it must be a whole number >= 1");
    }
  }
  return columns;
}

// PCL 1.13's writer leaves zero bytes after the data (the file is page-aligned past it): `size`
// less those when every byte after the `needed` ones is 0, else `size` (an error then names the
// extra bytes).
size_t WithoutZeroPadding(const char* data, size_t size, size_t needed) {
  if (needed == 0 || size <= needed) return size;
  for (size_t i = needed; i < size; ++i) {
    if (data[i] != 0) return size;
  }
  return needed;
}

uint32_t LoadU32(const char* p) {
  uint32_t value;
  std::memcpy(&value, p, sizeof(value));
  return value;
}

// DATA binary_compressed as PCL writes it: uint32 compressed size, uint32 decompressed size,
// then that many bytes of LZF (host/io/lzf.h) holding the fields one after another (all points'
// values of the first field, then of the second, ...; fields named "_", padding, are not
// stored), then zero bytes to the end of the file at most. The sizes are checked against the
// header's points and the file's length, and the decompressed size against the most LZF can
// give, before anything is allocated; the fields are then put back point after point and decoded
// as DATA binary.
Cloud DecodeCompressed(const std::string& path, const char* data, size_t size, uint64_t points,
                       const RecordLayout& layout) {
  if (size < 8) {
    throw IoError(path, "DATA binary_compressed: " + std::to_string(size) +
                            " bytes after the header, fewer than its two 4-byte sizes");
  }
  const uint32_t compressed = LoadU32(data), decompressed = LoadU32(data + 4);
  // Bytes a point takes in the stream: its record less the padding fields.
  size_t stored_bytes = 0;
  for (const Column& column : layout.columns) {
    if (column.name != "_") stored_bytes += ScalarSize(column.type) * column.count;
  }
  if (stored_bytes != 0 && points > UINT32_MAX / stored_bytes) {
    throw IoError(path, "DATA binary_compressed: " + std::to_string(points) + " points of " +
                            std::to_string(stored_bytes) +
                            " bytes are more than its 32-bit sizes can hold");
  }
  const size_t needed = size_t(points) * stored_bytes;
  if (decompressed != needed) {
    throw IoError(path, "DATA binary_compressed: the data says it decompresses to " +
                            std::to_string(decompressed) + " bytes, but the header's " +
                            std::to_string(points) + " points of " + std::to_string(stored_bytes) +
                            " bytes take " + std::to_string(needed));
  }
  const size_t body = size - 8;
  if (compressed > body) {
    throw IoError(path, "DATA binary_compressed: the data says it holds " +
                            std::to_string(compressed) + " compressed bytes, but the file has " +
                            std::to_string(body) + " after the sizes (cut short?)");
  }
  if (WithoutZeroPadding(data + 8, body, compressed) != compressed) {
    throw IoError(path, "DATA binary_compressed: " + std::to_string(body - compressed) +
                            " bytes after the " + std::to_string(compressed) +
                            " compressed bytes the data says it holds");
  }
  if (compressed == 0 && needed != 0) {
    throw IoError(path, "DATA binary_compressed: no compressed bytes for " +
                            std::to_string(points) + " points");
  }
  if (needed / kLzfMaxExpansion > compressed) {
    throw IoError(path, "DATA binary_compressed: " + std::to_string(compressed) +
                            " compressed bytes cannot hold the " + std::to_string(needed) +
                            " bytes of the header's " + std::to_string(points) + " points");
  }
  std::vector<uint8_t> fields(needed);
  LzfDecompress(path, reinterpret_cast<const uint8_t*>(data) + 8, compressed, fields.data(),
                needed);
  // Field after field to point after point; padding fields stay 0.
  std::vector<char> records(size_t(points) * layout.record_bytes, 0);
  size_t from = 0, offset = 0;
  for (const Column& column : layout.columns) {
    const size_t bytes = ScalarSize(column.type) * column.count;
    if (column.name != "_") {
      for (size_t i = 0; i < points; ++i, from += bytes) {
        std::memcpy(records.data() + i * layout.record_bytes + offset, fields.data() + from, bytes);
      }
    }
    offset += bytes;
  }
  return DecodeBinaryRecords(path, records.data(), records.size(), size_t(points), layout, true);
}

}  // namespace

Cloud ReadPcd(const std::string& path, std::string* note) {
  const std::vector<char> bytes = ReadFileBytes(path);
  if (bytes.empty()) throw IoError(path, "empty file");
  LineCursor cursor(bytes.data(), bytes.size());
  const PcdHeader header = ParseHeader(path, &cursor);
  const bool binary = header.data == "binary";
  const bool compressed = header.data == "binary_compressed";
  if (!binary && !compressed && header.data != "ascii") {
    throw IoError(path, "line " + std::to_string(header.data_line) + ": unknown DATA " +
                            Quote(header.data) + " (expected ascii, binary or binary_compressed)");
  }
  RecordLayout layout = MakeRecordLayout(path, HeaderColumns(path, header), "field");
  if (!header.has_width) throw IoError(path, "header has no WIDTH line");
  if (header.height != 0 && header.width > SIZE_MAX / header.height) {
    throw IoError(path, "WIDTH " + std::to_string(header.width) + " x HEIGHT " +
                            std::to_string(header.height) + " is too many points");
  }
  const uint64_t points = header.width * header.height;
  if (header.has_points && header.points != points) {
    throw IoError(path, "POINTS " + std::to_string(header.points) +
                            " is not WIDTH x HEIGHT = " + std::to_string(points));
  }
  NoteMissingIntensity(path, layout, note);
  const char* data = bytes.data() + cursor.offset();
  const size_t size = cursor.bytes_left();
  if (compressed) return DecodeCompressed(path, data, size, points, layout);
  if (!binary) return DecodeAsciiRecords(path, &cursor, points, layout, true);
  const size_t needed = points <= SIZE_MAX / layout.record_bytes ? points * layout.record_bytes : 0;
  return DecodeBinaryRecords(path, data, WithoutZeroPadding(data, size, needed), points, layout,
                             true);
}

void WritePcd(const std::string& path, const Cloud& cloud, const Labels* labels, bool binary) {
  CheckWritable(path, cloud, labels);
  const size_t n = cloud.size();
  const bool ring = !cloud.ring.empty();
  std::string out = "# .PCD v0.7 - Point Cloud Data file format\nVERSION 0.7\n";
  out += std::string("FIELDS x y z intensity") + (ring ? " ring" : "") + (labels ? " label" : "");
  out += std::string("\nSIZE 4 4 4 4") + (ring ? " 4" : "") + (labels ? " 1" : "");
  out += std::string("\nTYPE F F F F") + (ring ? " I" : "") + (labels ? " U" : "");
  out += std::string("\nCOUNT 1 1 1 1") + (ring ? " 1" : "") + (labels ? " 1" : "");
  out += "\nWIDTH " + std::to_string(n) + "\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS " +
         std::to_string(n) + "\nDATA " + (binary ? "binary\n" : "ascii\n");
  AppendRecords(&out, cloud, labels, binary);
  WriteFileBytes(path, out.data(), out.size());
}

}  // namespace lpir
