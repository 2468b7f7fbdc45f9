// segment --report (see frame_report.h).
#include "apps/cli/frame_report.h"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <utility>

#include "host/io/io_error.h"

namespace lpir {
namespace {

std::string Extension(const std::string& path) {
  return std::filesystem::path(path).extension().string();
}

// A CSV field: as it is, or quoted with its quotes doubled when it holds , " or a line break.
std::string CsvField(const std::string& s) {
  if (s.find_first_of(",\"\r\n") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

// The length of the UTF-8 sequence starting at s[i] (2 to 4), or 0 when it is not a valid one
// (a stray continuation byte, a truncated or overlong sequence, a surrogate, beyond U+10FFFF).
size_t Utf8Length(const std::string& s, size_t i) {
  const auto byte = [&](size_t k) { return static_cast<unsigned char>(s[k]); };
  const unsigned char c = byte(i);
  const size_t n = c >= 0xF0 && c <= 0xF4 ? 4 : c >= 0xE0 ? 3 : c >= 0xC2 && c < 0xE0 ? 2 : 0;
  if (n == 0 || c >= 0xF5 || i + n > s.size()) return 0;
  for (size_t k = 1; k < n; ++k)
    if ((byte(i + k) & 0xC0) != 0x80) return 0;
  const unsigned char d = byte(i + 1);
  if ((c == 0xE0 && d < 0xA0) || (c == 0xED && d >= 0xA0) || (c == 0xF0 && d < 0x90) ||
      (c == 0xF4 && d >= 0x90))
    return 0;
  return n;
}

// A JSON string literal: " and \ escaped, control characters as \u00XX, UTF-8 kept and any byte
// that is not part of valid UTF-8 (a file name is bytes) as U+FFFD, so that the file parses.
std::string JsonString(const std::string& s) {
  std::string q = "\"";
  for (size_t i = 0; i < s.size(); ++i) {
    const unsigned char c = static_cast<unsigned char>(s[i]);
    if (c == '"' || c == '\\') {
      q += '\\';
      q += char(c);
    } else if (c < 0x20) {
      char buf[8];
      std::snprintf(buf, sizeof(buf), "\\u%04x", c);
      q += buf;
    } else if (c < 0x80) {
      q += char(c);
    } else if (const size_t n = Utf8Length(s, i)) {
      q.append(s, i, n);
      i += n - 1;
    } else {
      q += "\\ufffd";
    }
  }
  return q + "\"";
}

std::string Number(const char* format, double v) {
  char buf[48];
  std::snprintf(buf, sizeof(buf), format, v);
  return buf;
}

}  // namespace

bool FrameReport::IsReportName(const std::string& path) {
  const std::string ext = Extension(path);
  return ext == ".csv" || ext == ".json";
}

FrameReport::FrameReport(const std::string& path, std::string backend, std::string device)
    : path_(path),
      backend_(std::move(backend)),
      device_(std::move(device)),
      json_(Extension(path) == ".json") {
  if (!IsReportName(path)) throw IoError(path, "a report must be named .csv or .json");
  file_ = std::fopen(path.c_str(), "wb");
  if (!file_) throw IoError(path, std::string("cannot create the report: ") + std::strerror(errno));
  std::fputs(json_ ? "{\"frames\": [\n"
                   : "input,sequence,stamp_ns,topic,points,ground,ground_fraction,invalid,"
                     "invalid_not_finite,invalid_at_origin,invalid_out_of_range,invalid_bad_ring,"
                     "ms,sensor_height,k_xz,k_yz,mount_estimated,backend,device,error\n",
             file_);
}

FrameReport::~FrameReport() {
  if (file_) std::fclose(file_);
}

void FrameReport::Add(const FrameRecord& r) {
  const double fraction = r.points ? double(r.ground) / double(r.points) : 0.0;
  const std::string n[] = {std::to_string(r.points),
                           std::to_string(r.ground),
                           Number("%.6f", fraction),
                           std::to_string(r.invalid),
                           std::to_string(r.reasons.not_finite),
                           std::to_string(r.reasons.at_origin),
                           std::to_string(r.reasons.out_of_range),
                           std::to_string(r.reasons.bad_ring),
                           Number("%.3f", r.ms),
                           Number("%.4f", r.mount.sensor_height),
                           Number("%.6f", r.mount.k_xz),
                           Number("%.6f", r.mount.k_yz),
                           r.mount_estimated ? "1" : "0"};
  std::string line;
  if (json_) {
    const char* keys[] = {"points",
                          "ground",
                          "ground_fraction",
                          "invalid",
                          "invalid_not_finite",
                          "invalid_at_origin",
                          "invalid_out_of_range",
                          "invalid_bad_ring",
                          "ms",
                          "sensor_height",
                          "k_xz",
                          "k_yz",
                          "mount_estimated"};
    line = std::string(rows_ ? ",\n" : "") + "  {\"input\": " + JsonString(r.input);
    if (r.from_drive)
      line += ", \"sequence\": " + std::to_string(r.sequence) +
              ", \"stamp_ns\": " + std::to_string(r.stamp_ns) +
              ", \"topic\": " + JsonString(r.topic);
    else
      line += ", \"sequence\": null, \"stamp_ns\": null, \"topic\": null";
    for (size_t k = 0; k < sizeof(keys) / sizeof(keys[0]); ++k)
      line += std::string(", \"") + keys[k] + "\": " + n[k];
    line += ", \"backend\": " + JsonString(backend_) + ", \"device\": " + JsonString(device_) +
            ", \"error\": " + (r.error.empty() ? "null" : JsonString(r.error)) + "}";
  } else {
    line = CsvField(r.input) + ",";
    if (r.from_drive)
      line +=
          std::to_string(r.sequence) + "," + std::to_string(r.stamp_ns) + "," + CsvField(r.topic);
    else
      line += ",,";
    for (const std::string& v : n) line += "," + v;
    line += "," + CsvField(backend_) + "," + CsvField(device_) + "," + CsvField(r.error) + "\n";
  }
  std::fputs(line.c_str(), file_);
  ++rows_;
}

void FrameReport::Close(size_t frames, size_t failed, double seconds) {
  if (json_)
    std::fprintf(file_,
                 "%s],\n \"summary\": {\"frames\": %zu, \"failed\": %zu, \"seconds\": %.3f, "
                 "\"backend\": %s, \"device\": %s}}\n",
                 rows_ ? "\n" : "", frames, failed, seconds, JsonString(backend_).c_str(),
                 JsonString(device_).c_str());
  const bool failed_write = std::ferror(file_) != 0;
  const bool failed_close = std::fclose(file_) != 0;
  file_ = nullptr;
  if (failed_write || failed_close) throw IoError(path_, "writing the report failed");
}

}  // namespace lpir
