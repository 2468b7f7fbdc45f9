// What the PCD and PLY readers share: the scalar types both formats store, the per-point columns
// a header declares, and strict decoding of those columns (binary or ASCII) into a Cloud.
// ASCII numbers are parsed with std::from_chars: independent of the C locale.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "reference_cpu/cloud.h"

namespace lpir {

enum class ScalarType { kI8, kU8, kI16, kU16, kI32, kU32, kI64, kU64, kF32, kF64 };

size_t ScalarSize(ScalarType type);
// "int8", "uint16", "float32", ... for messages.
const char* ScalarTypeName(ScalarType type);

// Which Cloud value a column feeds.
enum class ColumnRole { kSkip, kX, kY, kZ, kIntensity, kRing };

// One field of a point record as a header declares it.
struct Column {
  std::string name;
  ScalarType type = ScalarType::kF32;
  uint64_t count = 1;  // values per point (PCD COUNT); more than 1 only for skipped columns
  ColumnRole role = ColumnRole::kSkip;
};

// The layout of one point record, with the roles assigned.
struct RecordLayout {
  std::vector<Column> columns;
  size_t record_bytes = 0;   // binary: bytes per point
  size_t record_values = 0;  // ASCII: values per point (one line)
  bool has_ring = false;
  bool has_intensity = false;
  // What the format calls a point, for messages ("point"/"points", "vertex"/"vertices").
  std::string noun = "point";
  std::string noun_plural = "points";
};

// The names writers give a point's intensity, best first, compared ignoring case; a record with
// several reads the first (an Ouster cloud holds intensity and reflectivity: intensity).
//   intensity         PCL, ROS drivers, most converters
//   scalar_intensity  CloudCompare's scalar field, written scalar_Intensity
//   reflectivity      Ouster's and Livox's calibrated return strength
//   remission         KITTI's and SemanticKITTI's word for it
//   i                 the short name some ROS drivers publish
const std::vector<std::string>& IntensityNames();
// The place of `name` in IntensityNames(), ignoring ASCII case; -1 when it is none of them.
int IntensityRank(std::string_view name);
// The better of `best` (an IntensityRank, -1: none yet) and IntensityRank(name): fold it over a
// record's field names to find the intensity's rank.
int BetterIntensityRank(int best, std::string_view name);
// The note for a file without an intensity field: "<path> has no intensity field (...): its
// points read intensity 0".
std::string NoIntensityNote(const std::string& path);

// Assigns roles by name (x, y, z, ring, and as the intensity the columns of the best
// IntensityRank present; others are skipped) and computes the record sizes. IoError naming the
// file when x, y or z is missing, a used column appears twice or has a count other than 1, or the
// record size overflows. `field_noun` is what the format calls a column in messages ("field",
// "property").
RecordLayout MakeRecordLayout(const std::string& path, std::vector<Column> columns,
                              const char* field_noun);
// *note (when `note` is given): NoIntensityNote(path) when the layout has no intensity column,
// else empty.
void NoteMissingIntensity(const std::string& path, const RecordLayout& layout, std::string* note);

// Decodes `points` packed little-endian records from the `size` bytes at `data`. IoError naming
// the file when fewer bytes are there than the points need (the message gives both counts), when
// `reject_extra_bytes` and more are there, or for a ring that is not a whole number >= 0.
// Nothing is allocated before the size is checked.
Cloud DecodeBinaryRecords(const std::string& path, const char* data, size_t size, size_t points,
                          const RecordLayout& layout, bool reject_extra_bytes);

// Walks a byte buffer line by line ("\n" or "\r\n" endings; a last line may lack one).
class LineCursor {
 public:
  LineCursor(const char* data, size_t size) : data_(data), size_(size) {}

  // The next line without its ending; false when no bytes are left.
  bool Next(std::string_view* line);
  // 1-based number of the line Next last returned.
  size_t line_number() const { return line_number_; }
  // Offset of the first byte after the line Next last returned and its ending.
  size_t offset() const { return offset_; }
  // Whether that line ended with "\n" (false only for an unterminated last line).
  bool had_newline() const { return had_newline_; }
  size_t bytes_left() const { return size_ - offset_; }

 private:
  const char* data_;
  size_t size_;
  size_t offset_ = 0;
  size_t line_number_ = 0;
  bool had_newline_ = false;
};

// Decodes `points` ASCII records, one per non-blank line, from the cursor on. IoError naming the
// file and line for a wrong number of values, a value that is not a number of its column's type
// (nan and inf are numbers for float columns), a bad ring, fewer lines than `points`, or, when
// `reject_extra_lines`, non-blank lines after the last record.
Cloud DecodeAsciiRecords(const std::string& path, LineCursor* cursor, size_t points,
                         const RecordLayout& layout, bool reject_extra_lines);

// IoError naming the file unless the cloud's ring (when present) and labels (when given) have one
// entry per point.
void CheckWritable(const std::string& path, const Cloud& cloud, const Labels* labels);
// Appends the records the writers use: x y z intensity as float32, then ring as int32 when the
// cloud has one, then label as uint8 when given; packed little-endian when binary, else one line
// per point with floats in their shortest exact text.
void AppendRecords(std::string* out, const Cloud& cloud, const Labels* labels, bool binary);

// Parses the whole token as a value of `type`. Float tokens take decimal and exponent forms and
// nan/inf (float32 tokens are rounded to float directly, so float text round-trips exactly);
// integer tokens must be whole decimal numbers inside the type's range. False for anything else.
bool ParseScalarToken(std::string_view token, ScalarType type, double* value);
// A whole decimal number without sign (a header count); false for anything else or overflow.
bool ParseCount(std::string_view token, uint64_t* value);

// A ring index from a stored value: true when it is a finite whole number in [0, INT32_MAX].
bool RingFromValue(double value, int32_t* ring);

// Splits on spaces and tabs into `tokens` (replacing its contents).
void SplitTokens(std::string_view line, std::vector<std::string_view>* tokens);

// `text` in single quotes for an error message: non-printable bytes as \xNN, long text cut.
std::string Quote(std::string_view text);
// Shortest decimal text that reads back as exactly `value` (nan, inf, -inf when not finite).
void AppendFloat(std::string* out, float value);
void AppendInteger(std::string* out, int64_t value);
std::string FloatText(double value);

}  // namespace lpir
