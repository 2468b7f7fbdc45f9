// Scalar types, point-record decoding and ASCII number tokens shared by the PCD and PLY readers.
#include "host/io/point_fields.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstring>
#include <limits>
#include <type_traits>

#include "host/io/io_error.h"

namespace lpir {

static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__,
              "the binary readers copy little-endian file values straight into memory");

namespace {

template <typename T>
T Load(const char* p) {
  T value;
  std::memcpy(&value, p, sizeof(T));
  return value;
}

// A whole decimal integer token that fits in T.
template <typename T>
bool ParseInteger(std::string_view token, double* value) {
  using Wide = std::conditional_t<std::is_signed_v<T>, int64_t, uint64_t>;
  Wide parsed = 0;
  auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), parsed);
  if (ec != std::errc() || end != token.data() + token.size()) return false;
  if (parsed < static_cast<Wide>(std::numeric_limits<T>::min()) ||
      parsed > static_cast<Wide>(std::numeric_limits<T>::max())) {
    return false;
  }
  *value = static_cast<double>(parsed);
  return true;
}

bool ParseFloat(std::string_view token, ScalarType type, double* value) {
  const char* begin = token.data();
  const char* end = token.data() + token.size();
  if (type == ScalarType::kF64) {
    double parsed = 0.0;
    auto [stop, ec] = std::from_chars(begin, end, parsed);
    if (ec != std::errc() || stop != end) return false;
    *value = parsed;
    return true;
  }
  float parsed = 0.0f;
  auto [stop, ec] = std::from_chars(begin, end, parsed);
  if (ec == std::errc() && stop == end) {
    *value = parsed;
    return true;
  }
  if (ec != std::errc::result_out_of_range) return false;
  // Out of float range: accept underflow (rounds towards 0), reject overflow.
  double wide = 0.0;
  auto [wide_stop, wide_ec] = std::from_chars(begin, end, wide);
  if (wide_ec != std::errc() || wide_stop != end || !(std::fabs(wide) < 1.0)) return false;
  *value = static_cast<float>(wide);
  return true;
}

// `intensity_rank`: the IntensityRank that marks the intensity column (-1: none).
ColumnRole RoleOf(const std::string& name, int intensity_rank) {
  if (name == "x") return ColumnRole::kX;
  if (name == "y") return ColumnRole::kY;
  if (name == "z") return ColumnRole::kZ;
  if (name == "ring") return ColumnRole::kRing;
  if (intensity_rank >= 0 && IntensityRank(name) == intensity_rank) return ColumnRole::kIntensity;
  return ColumnRole::kSkip;
}

double ReadScalar(const char* p, ScalarType type) {
  switch (type) {
    case ScalarType::kI8:
      return Load<int8_t>(p);
    case ScalarType::kU8:
      return Load<uint8_t>(p);
    case ScalarType::kI16:
      return Load<int16_t>(p);
    case ScalarType::kU16:
      return Load<uint16_t>(p);
    case ScalarType::kI32:
      return Load<int32_t>(p);
    case ScalarType::kU32:
      return Load<uint32_t>(p);
    case ScalarType::kI64:
      return static_cast<double>(Load<int64_t>(p));
    case ScalarType::kU64:
      return static_cast<double>(Load<uint64_t>(p));
    case ScalarType::kF32:
      return Load<float>(p);
    case ScalarType::kF64:
      return Load<double>(p);
  }
  return 0.0;
}

float ReadScalarAsFloat(const char* p, ScalarType type) {
  if (type == ScalarType::kF32) return Load<float>(p);
  return static_cast<float>(ReadScalar(p, type));
}

}  // namespace

size_t ScalarSize(ScalarType type) {
  switch (type) {
    case ScalarType::kI8:
    case ScalarType::kU8:
      return 1;
    case ScalarType::kI16:
    case ScalarType::kU16:
      return 2;
    case ScalarType::kI32:
    case ScalarType::kU32:
    case ScalarType::kF32:
      return 4;
    case ScalarType::kI64:
    case ScalarType::kU64:
    case ScalarType::kF64:
      return 8;
  }
  return 0;
}

const char* ScalarTypeName(ScalarType type) {
  switch (type) {
    case ScalarType::kI8:
      return "int8";
    case ScalarType::kU8:
      return "uint8";
    case ScalarType::kI16:
      return "int16";
    case ScalarType::kU16:
      return "uint16";
    case ScalarType::kI32:
      return "int32";
    case ScalarType::kU32:
      return "uint32";
    case ScalarType::kI64:
      return "int64";
    case ScalarType::kU64:
      return "uint64";
    case ScalarType::kF32:
      return "float32";
    case ScalarType::kF64:
      return "float64";
  }
  return "?";
}

const std::vector<std::string>& IntensityNames() {
  static const std::vector<std::string> kNames = {"intensity", "scalar_intensity", "reflectivity",
                                                  "remission", "i"};
  return kNames;
}

int IntensityRank(std::string_view name) {
  const std::vector<std::string>& names = IntensityNames();
  for (size_t rank = 0; rank < names.size(); ++rank) {
    const std::string& candidate = names[rank];
    if (candidate.size() == name.size() &&
        std::equal(name.begin(), name.end(), candidate.begin(),
                   [](char a, char b) { return std::tolower(static_cast<unsigned char>(a)) == b; }))
      return static_cast<int>(rank);
  }
  return -1;
}

int BetterIntensityRank(int best, std::string_view name) {
  const int rank = IntensityRank(name);
  return rank >= 0 && (best < 0 || rank < best) ? rank : best;
}

std::string NoIntensityNote(const std::string& path) {
  std::string names;
  for (const std::string& name : IntensityNames()) names += (names.empty() ? "" : ", ") + name;
  return path + " has no intensity field (" + names + ", in any case): its points read intensity 0";
}

void NoteMissingIntensity(const std::string& path, const RecordLayout& layout, std::string* note) {
  if (note) *note = layout.has_intensity ? std::string() : NoIntensityNote(path);
}

RecordLayout MakeRecordLayout(const std::string& path, std::vector<Column> columns,
                              const char* field_noun) {
  const std::string noun = field_noun;
  int intensity_rank = -1;
  for (const Column& column : columns)
    intensity_rank = BetterIntensityRank(intensity_rank, column.name);
  RecordLayout layout;
  bool seen[static_cast<int>(ColumnRole::kRing) + 1] = {};
  for (Column& column : columns) {
    const std::string& name = column.name;
    column.role = RoleOf(name, intensity_rank);
    if (column.role != ColumnRole::kSkip) {
      bool& was_seen = seen[static_cast<int>(column.role)];
      if (was_seen) throw IoError(path, noun + " " + Quote(name) + " appears twice");
      was_seen = true;
      if (column.count != 1) {
        throw IoError(path, noun + " " + Quote(name) + " has COUNT " +
                                std::to_string(column.count) + "; it must be 1");
      }
    }
    const size_t size = ScalarSize(column.type);
    if (column.count > (SIZE_MAX - layout.record_bytes) / size ||
        column.count > SIZE_MAX - layout.record_values) {
      throw IoError(path, noun + " " + Quote(name) + " COUNT " + std::to_string(column.count) +
                              " makes a point record too large");
    }
    layout.record_bytes += size * column.count;
    layout.record_values += column.count;
  }
  for (ColumnRole axis : {ColumnRole::kX, ColumnRole::kY, ColumnRole::kZ}) {
    if (!seen[static_cast<int>(axis)]) {
      const char* name = axis == ColumnRole::kX ? "x" : axis == ColumnRole::kY ? "y" : "z";
      throw IoError(path, std::string("no ") + Quote(name) + " " + noun);
    }
  }
  layout.has_ring = seen[static_cast<int>(ColumnRole::kRing)];
  layout.has_intensity = seen[static_cast<int>(ColumnRole::kIntensity)];
  layout.columns = std::move(columns);
  return layout;
}

namespace {

// Stores one value of a used column into point i of the cloud.
void StoreValue(const std::string& path, const RecordLayout& layout, ColumnRole role, double value,
                float as_float, size_t i, Cloud* cloud) {
  switch (role) {
    case ColumnRole::kX:
      cloud->xyzi[4 * i + 0] = as_float;
      return;
    case ColumnRole::kY:
      cloud->xyzi[4 * i + 1] = as_float;
      return;
    case ColumnRole::kZ:
      cloud->xyzi[4 * i + 2] = as_float;
      return;
    case ColumnRole::kIntensity:
      cloud->xyzi[4 * i + 3] = as_float;
      return;
    case ColumnRole::kRing:
      if (!RingFromValue(value, &cloud->ring[i])) {
        throw IoError(path, layout.noun + " " + std::to_string(i) + " has ring " +
                                FloatText(value) + ", not a whole number >= 0");
      }
      return;
    case ColumnRole::kSkip:
      return;
  }
}

}  // namespace

Cloud DecodeBinaryRecords(const std::string& path, const char* data, size_t size, size_t points,
                          const RecordLayout& layout, bool reject_extra_bytes) {
  const size_t whole = size / layout.record_bytes;
  if (points > whole) {
    throw IoError(path, "header says " + std::to_string(points) + " " + layout.noun_plural +
                            " but the data holds " + std::to_string(whole) + " (" +
                            std::to_string(size) + " bytes of " +
                            std::to_string(layout.record_bytes) + "-byte " + layout.noun_plural +
                            ")");
  }
  if (reject_extra_bytes && size != points * layout.record_bytes) {
    throw IoError(path, "data holds " + std::to_string(size) + " bytes, more than the " +
                            std::to_string(points) + " " + layout.noun_plural + " of " +
                            std::to_string(layout.record_bytes) + " bytes the header says");
  }
  Cloud cloud;
  cloud.xyzi.assign(4 * points, 0.0f);
  if (layout.has_ring) cloud.ring.assign(points, 0);
  // Byte offset of each column inside a record.
  std::vector<size_t> offsets;
  size_t offset = 0;
  for (const Column& column : layout.columns) {
    offsets.push_back(offset);
    offset += ScalarSize(column.type) * column.count;
  }
  for (size_t i = 0; i < points; ++i) {
    const char* record = data + i * layout.record_bytes;
    for (size_t c = 0; c < layout.columns.size(); ++c) {
      const Column& column = layout.columns[c];
      if (column.role == ColumnRole::kSkip) continue;
      const char* p = record + offsets[c];
      StoreValue(path, layout, column.role, ReadScalar(p, column.type),
                 ReadScalarAsFloat(p, column.type), i, &cloud);
    }
  }
  return cloud;
}

Cloud DecodeAsciiRecords(const std::string& path, LineCursor* cursor, size_t points,
                         const RecordLayout& layout, bool reject_extra_lines) {
  // Each value takes at least two bytes (a character and a separator): reserve no more than the
  // bytes left could hold, whatever the header says.
  const size_t most = cursor->bytes_left() / (2 * std::max<size_t>(layout.record_values, 1)) + 1;
  Cloud cloud;
  cloud.xyzi.reserve(4 * std::min(points, most));
  if (layout.has_ring) cloud.ring.reserve(std::min(points, most));
  std::vector<std::string_view> tokens;
  std::string_view line;
  for (size_t i = 0; i < points; ++i) {
    tokens.clear();
    while (tokens.empty() && cursor->Next(&line)) SplitTokens(line, &tokens);
    if (tokens.empty()) {
      throw IoError(path, "header says " + std::to_string(points) + " " + layout.noun_plural +
                              " but the data holds " + std::to_string(i));
    }
    const size_t line_number = cursor->line_number();
    if (tokens.size() != layout.record_values) {
      throw IoError(path, "line " + std::to_string(line_number) + " has " +
                              std::to_string(tokens.size()) + " values, expected " +
                              std::to_string(layout.record_values));
    }
    cloud.xyzi.insert(cloud.xyzi.end(), 4, 0.0f);
    if (layout.has_ring) cloud.ring.push_back(0);
    size_t t = 0;
    for (const Column& column : layout.columns) {
      for (uint64_t k = 0; k < column.count; ++k, ++t) {
        double value = 0.0;
        if (!ParseScalarToken(tokens[t], column.type, &value)) {
          throw IoError(path, "line " + std::to_string(line_number) + ": " + Quote(tokens[t]) +
                                  " is not a valid " + ScalarTypeName(column.type) + " value for " +
                                  Quote(column.name));
        }
        StoreValue(path, layout, column.role, value, static_cast<float>(value), i, &cloud);
      }
    }
  }
  if (reject_extra_lines) {
    while (cursor->Next(&line)) {
      SplitTokens(line, &tokens);
      if (!tokens.empty()) {
        throw IoError(path, "line " + std::to_string(cursor->line_number()) +
                                ": more data after the " + std::to_string(points) + " " +
                                layout.noun_plural + " the header says");
      }
    }
  }
  return cloud;
}

void CheckWritable(const std::string& path, const Cloud& cloud, const Labels* labels) {
  const size_t n = cloud.size();
  if (!cloud.ring.empty() && cloud.ring.size() != n) {
    throw IoError(path, "cannot write: the cloud has " + std::to_string(n) + " points but " +
                            std::to_string(cloud.ring.size()) + " ring values");
  }
  if (labels && labels->size() != n) {
    throw IoError(path, "cannot write: the cloud has " + std::to_string(n) + " points but " +
                            std::to_string(labels->size()) + " labels");
  }
}

void AppendRecords(std::string* out, const Cloud& cloud, const Labels* labels, bool binary) {
  const size_t n = cloud.size();
  const bool ring = !cloud.ring.empty();
  const size_t record = 4 * sizeof(float) + (ring ? sizeof(int32_t) : 0) + (labels ? 1 : 0);
  out->reserve(out->size() + n * (binary ? record : 64));
  for (size_t i = 0; i < n; ++i) {
    if (binary) {
      out->append(reinterpret_cast<const char*>(&cloud.xyzi[4 * i]), 4 * sizeof(float));
      if (ring) out->append(reinterpret_cast<const char*>(&cloud.ring[i]), sizeof(int32_t));
      if (labels) out->push_back(static_cast<char>((*labels)[i]));
      continue;
    }
    for (int k = 0; k < 4; ++k) {
      if (k > 0) *out += ' ';
      AppendFloat(out, cloud.xyzi[4 * i + k]);
    }
    if (ring) {
      *out += ' ';
      AppendInteger(out, cloud.ring[i]);
    }
    if (labels) {
      *out += ' ';
      AppendInteger(out, (*labels)[i]);
    }
    *out += '\n';
  }
}

bool ParseScalarToken(std::string_view token, ScalarType type, double* value) {
  // from_chars takes no '+' sign; allow one before a digit or a '.'.
  if (token.size() > 1 && token[0] == '+' && token[1] != '+' && token[1] != '-') {
    token.remove_prefix(1);
  }
  if (token.empty()) return false;
  switch (type) {
    case ScalarType::kI8:
      return ParseInteger<int8_t>(token, value);
    case ScalarType::kU8:
      return ParseInteger<uint8_t>(token, value);
    case ScalarType::kI16:
      return ParseInteger<int16_t>(token, value);
    case ScalarType::kU16:
      return ParseInteger<uint16_t>(token, value);
    case ScalarType::kI32:
      return ParseInteger<int32_t>(token, value);
    case ScalarType::kU32:
      return ParseInteger<uint32_t>(token, value);
    case ScalarType::kI64:
      return ParseInteger<int64_t>(token, value);
    case ScalarType::kU64:
      return ParseInteger<uint64_t>(token, value);
    case ScalarType::kF32:
    case ScalarType::kF64:
      return ParseFloat(token, type, value);
  }
  return false;
}

bool ParseCount(std::string_view token, uint64_t* value) {
  uint64_t parsed = 0;
  auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), parsed);
  if (token.empty() || ec != std::errc() || end != token.data() + token.size()) return false;
  *value = parsed;
  return true;
}

bool RingFromValue(double value, int32_t* ring) {
  if (!std::isfinite(value) || value < 0.0 ||
      value > static_cast<double>(std::numeric_limits<int32_t>::max()) ||
      value != std::floor(value)) {
    return false;
  }
  *ring = static_cast<int32_t>(value);
  return true;
}

void SplitTokens(std::string_view line, std::vector<std::string_view>* tokens) {
  tokens->clear();
  size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
    size_t start = i;
    while (i < line.size() && line[i] != ' ' && line[i] != '\t') ++i;
    if (i > start) tokens->push_back(line.substr(start, i - start));
  }
}

std::string Quote(std::string_view text) {
  constexpr size_t kMaxShown = 40;
  std::string out = "'";
  for (size_t i = 0; i < text.size() && i < kMaxShown; ++i) {
    unsigned char c = static_cast<unsigned char>(text[i]);
    if (c >= 0x20 && c < 0x7f) {
      out += static_cast<char>(c);
    } else {
      static const char kHex[] = "0123456789abcdef";
      out += "\\x";
      out += kHex[c >> 4];
      out += kHex[c & 0xf];
    }
  }
  if (text.size() > kMaxShown) out += "...";
  return out + "'";
}

void AppendFloat(std::string* out, float value) {
  char buffer[64];
  auto [end, ec] = std::to_chars(buffer, buffer + sizeof(buffer), value);
  out->append(buffer, ec == std::errc() ? end : buffer);
}

void AppendInteger(std::string* out, int64_t value) {
  char buffer[32];
  auto [end, ec] = std::to_chars(buffer, buffer + sizeof(buffer), value);
  out->append(buffer, ec == std::errc() ? end : buffer);
}

std::string FloatText(double value) {
  char buffer[64];
  auto [end, ec] = std::to_chars(buffer, buffer + sizeof(buffer), value);
  return std::string(buffer, ec == std::errc() ? end : buffer);
}

bool LineCursor::Next(std::string_view* line) {
  if (offset_ >= size_) return false;
  const char* start = data_ + offset_;
  const void* newline = std::memchr(start, '\n', size_ - offset_);
  size_t length;
  if (newline) {
    length = static_cast<size_t>(static_cast<const char*>(newline) - start);
    offset_ += length + 1;
    had_newline_ = true;
  } else {
    length = size_ - offset_;
    offset_ = size_;
    had_newline_ = false;
  }
  if (length > 0 && start[length - 1] == '\r') --length;
  *line = std::string_view(start, length);
  ++line_number_;
  return true;
}

}  // namespace lpir
