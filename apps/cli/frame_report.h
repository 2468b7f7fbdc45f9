// segment --report FILE.csv|.json: a row (CSV) or an object (JSON) per input frame, written as
// the frames finish, in input order. Columns / keys, in this order:
//   input           the file, or the drive the message came from
//   sequence, stamp_ns, topic   the message's place in the drive (empty / null for a file)
//   points, ground, ground_fraction
//   invalid         points labelled invalid (non-ground), and by reason: invalid_not_finite,
//                   invalid_at_origin, invalid_out_of_range, invalid_bad_ring (apps/cli/
//                   invalid_reasons.h; they sum to invalid)
//   ms              the frame's total time (FrameTimes::total_ms)
//   sensor_height, k_xz, k_yz   the mount the frame was segmented with (Segmenter::mount())
//   mount_estimated 1 when that mount is the frame's own estimate (profile key mount per_frame),
//                   0 when it is the profile's (mount fixed, or too little ground to estimate)
//   backend, device "vulkan" and the device's name, or "cpu" and "CPU reference"
//   error           why the frame failed ("" / null when it was segmented; its figures are 0)
// CSV: a header line, then a line per frame; a field holding a comma, quote or line break is
// quoted ("" for a quote). JSON: {"frames": [...], "summary": {"frames", "failed", "seconds",
// "backend", "device"}}, its strings UTF-8 (a name's bytes that are not UTF-8 as U+FFFD).
#pragma once
#include <cstdint>
#include <cstdio>
#include <string>

#include "apps/cli/invalid_reasons.h"
#include "reference_cpu/params.h"

namespace lpir {

struct FrameRecord {
  std::string input;
  bool from_drive = false;  // sequence, stamp_ns and topic hold
  uint64_t sequence = 0;
  int64_t stamp_ns = 0;
  std::string topic;
  size_t points = 0, ground = 0, invalid = 0;
  InvalidReasons reasons;
  double ms = 0;
  Mount mount{0.0f, 0.0f, 0.0f};
  bool mount_estimated = false;
  std::string error;  // "" when segmented
};

class FrameReport {
 public:
  // True for the report names accepted: ending in .csv or .json.
  static bool IsReportName(const std::string& path);
  // Creates `path` (.csv or .json). IoError naming it when it cannot be created.
  FrameReport(const std::string& path, std::string backend, std::string device);
  ~FrameReport();  // closes the file (without the JSON summary when Close was not called)
  FrameReport(const FrameReport&) = delete;
  FrameReport& operator=(const FrameReport&) = delete;

  void Add(const FrameRecord& r);
  // Ends the report (JSON: the summary and closing brackets) and closes it. IoError naming the
  // file when a write failed.
  void Close(size_t frames, size_t failed, double seconds);

 private:
  std::string path_, backend_, device_;
  bool json_;
  std::FILE* file_ = nullptr;
  size_t rows_ = 0;
};

}  // namespace lpir
