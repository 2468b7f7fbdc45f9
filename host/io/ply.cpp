// PLY reader (format ascii 1.0 or binary_little_endian 1.0; the vertex element must come first and
// hold scalar properties) and writer. Point records are decoded by host/io/point_fields.
#include "host/io/ply.h"

#include <string>
#include <string_view>
#include <vector>

#include "host/io/file_bytes.h"
#include "host/io/io_error.h"
#include "host/io/point_fields.h"

namespace lpir {

namespace {

// The PLY scalar type names, both the classic and the sized spellings.
bool PlyScalarType(std::string_view name, ScalarType* out) {
  static const struct {
    const char* name;
    ScalarType type;
  } kTypes[] = {
      {"char", ScalarType::kI8},     {"int8", ScalarType::kI8},     {"uchar", ScalarType::kU8},
      {"uint8", ScalarType::kU8},    {"short", ScalarType::kI16},   {"int16", ScalarType::kI16},
      {"ushort", ScalarType::kU16},  {"uint16", ScalarType::kU16},  {"int", ScalarType::kI32},
      {"int32", ScalarType::kI32},   {"uint", ScalarType::kU32},    {"uint32", ScalarType::kU32},
      {"float", ScalarType::kF32},   {"float32", ScalarType::kF32}, {"double", ScalarType::kF64},
      {"float64", ScalarType::kF64},
  };
  for (const auto& t : kTypes) {
    if (name == t.name) {
      *out = t.type;
      return true;
    }
  }
  return false;
}

struct PlyElement {
  std::string name;
  uint64_t count = 0;
  std::vector<Column> properties;  // of the vertex element only; others are not looked at
};

struct PlyHeader {
  bool binary = false;
  std::vector<PlyElement> elements;
};

// Reads the header up to and including end_header; leaves the cursor after it.
PlyHeader ParseHeader(const std::string& path, LineCursor* cursor) {
  std::string_view line;
  if (!cursor->Next(&line) || line != "ply") {
    throw IoError(path, "not a PLY file (the first line is not 'ply')");
  }
  PlyHeader header;
  bool has_format = false;
  std::vector<std::string_view> tokens;
  while (true) {
    if (!cursor->Next(&line)) throw IoError(path, "header has no end_header line");
    SplitTokens(line, &tokens);
    if (tokens.empty()) continue;
    const std::string at = "line " + std::to_string(cursor->line_number()) + ": ";
    const std::string_view key = tokens[0];
    if (key == "comment" || key == "obj_info") continue;
    if (key == "end_header") break;
    if (key == "format") {
      if (has_format) throw IoError(path, at + "format given twice");
      if (tokens.size() != 3) throw IoError(path, at + "format needs a type and a version");
      if (tokens[1] == "binary_big_endian") {
        throw IoError(path, at + "format binary_big_endian is unsupported (convert to "
                                 "binary_little_endian or ascii)");
      }
      if (tokens[1] != "ascii" && tokens[1] != "binary_little_endian") {
        throw IoError(path, at + "unknown format " + Quote(tokens[1]));
      }
      if (tokens[2] != "1.0") {
        throw IoError(path, at + "unsupported format version " + Quote(tokens[2]));
      }
      header.binary = tokens[1] == "binary_little_endian";
      has_format = true;
    } else if (key == "element") {
      PlyElement element;
      if (tokens.size() != 3 || !ParseCount(tokens[2], &element.count)) {
        throw IoError(path, at + "element needs a name and a whole number count");
      }
      element.name = std::string(tokens[1]);
      header.elements.push_back(element);
    } else if (key == "property") {
      if (header.elements.empty()) throw IoError(path, at + "property before any element");
      // Only the properties of a leading vertex element matter.
      if (header.elements.size() > 1 || header.elements[0].name != "vertex") continue;
      PlyElement& element = header.elements.back();
      const std::string name(tokens.back());
      if (tokens.size() >= 2 && tokens[1] == "list") {
        throw IoError(path, at + "property " + Quote(name) + " of element " + Quote(element.name) +
                                " is a list (unsupported)");
      }
      if (tokens.size() != 3) throw IoError(path, at + "property needs a type and a name");
      Column column;
      column.name = name;
      if (!PlyScalarType(tokens[1], &column.type)) {
        throw IoError(path,
                      at + "property " + Quote(name) + " has unsupported type " + Quote(tokens[1]));
      }
      element.properties.push_back(column);
    } else {
      throw IoError(path, at + "unknown header keyword " + Quote(key));
    }
  }
  if (!has_format) throw IoError(path, "header has no format line");
  return header;
}

void AppendHeader(std::string* out, size_t n, bool ring, bool labels, bool binary) {
  *out += "ply\nformat ";
  *out += binary ? "binary_little_endian" : "ascii";
  *out += " 1.0\ncomment written by lpir-gseg\nelement vertex " + std::to_string(n) + "\n";
  *out += "property float x\nproperty float y\nproperty float z\nproperty float intensity\n";
  if (ring) *out += "property int ring\n";
  if (labels) *out += "property uchar label\n";
  *out += "end_header\n";
}

}  // namespace

Cloud ReadPly(const std::string& path, std::string* note) {
  const std::vector<char> bytes = ReadFileBytes(path);
  if (bytes.empty()) throw IoError(path, "empty file");
  LineCursor cursor(bytes.data(), bytes.size());
  const PlyHeader header = ParseHeader(path, &cursor);
  if (header.elements.empty() || header.elements[0].name != "vertex") {
    for (const PlyElement& element : header.elements) {
      if (element.name == "vertex") {
        throw IoError(path, "element " + Quote(header.elements[0].name) +
                                " comes before 'vertex' (unsupported)");
      }
    }
    throw IoError(path, "no 'vertex' element");
  }
  const PlyElement& vertex = header.elements[0];
  RecordLayout layout = MakeRecordLayout(path, vertex.properties, "property");
  NoteMissingIntensity(path, layout, note);
  layout.noun = "vertex";
  layout.noun_plural = "vertices";
  const bool vertex_only = header.elements.size() == 1;
  if (!header.binary) return DecodeAsciiRecords(path, &cursor, vertex.count, layout, vertex_only);
  return DecodeBinaryRecords(path, bytes.data() + cursor.offset(), cursor.bytes_left(),
                             vertex.count, layout, vertex_only);
}

void WritePly(const std::string& path, const Cloud& cloud, const Labels* labels, bool binary) {
  CheckWritable(path, cloud, labels);
  const size_t n = cloud.size();
  const bool ring = !cloud.ring.empty();
  std::string out;
  AppendHeader(&out, n, ring, labels != nullptr, binary);
  AppendRecords(&out, cloud, labels, binary);
  WriteFileBytes(path, out.data(), out.size());
}

}  // namespace lpir
