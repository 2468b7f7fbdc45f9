// Properties every cloud a reader returns must have, checked by the cloud fuzz targets: a ring
// field empty or one entry per point, every ring >= 0; a note about a missing intensity only
// with every intensity +0; and a write/read round trip through the project's own writer that
// gives the same cloud back (bit for bit in binary; in ASCII, NaN comes back as a NaN, its
// payload not kept by its text form). FuzzCloudFormat is the whole target of a format with an
// ASCII and a binary form (PCD, PLY).
#pragma once
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <functional>
#include <string>

#include "fuzz/fuzz_file.h"
#include "host/io/io_error.h"
#include "reference_cpu/cloud.h"

namespace lpir::fuzz {

inline void CheckCloudShape(const Cloud& cloud) {
  LPIR_FUZZ_CHECK(cloud.xyzi.size() % 4 == 0);
  LPIR_FUZZ_CHECK(cloud.ring.empty() || cloud.ring.size() == cloud.size());
  for (int32_t ring : cloud.ring) LPIR_FUZZ_CHECK(ring >= 0);
}

// A reader that notes a missing intensity has set every intensity to +0.
inline void CheckIntensityNote(const Cloud& cloud, const std::string& note) {
  if (note.empty()) return;
  for (size_t i = 0; i < cloud.size(); ++i) {
    const float intensity = cloud.intensity(i);
    LPIR_FUZZ_CHECK(intensity == 0.0f && !std::signbit(intensity));
  }
}

inline bool SameFloat(float a, float b, bool nan_matches_nan) {
  if (nan_matches_nan && std::isnan(a) && std::isnan(b)) return true;
  return std::memcmp(&a, &b, sizeof(float)) == 0;
}

inline void CheckSameCloud(const Cloud& a, const Cloud& b, bool nan_matches_nan) {
  LPIR_FUZZ_CHECK(a.xyzi.size() == b.xyzi.size());
  for (size_t i = 0; i < a.xyzi.size(); ++i)
    LPIR_FUZZ_CHECK(SameFloat(a.xyzi[i], b.xyzi[i], nan_matches_nan));
  LPIR_FUZZ_CHECK(a.ring == b.ring);
}

// A reader: the path, and where to put its note (may be null).
using CloudReader = std::function<Cloud(const std::string&, std::string*)>;

// Writes `cloud` with write(path, cloud, labels, binary) into `out`, reads it back with
// read(path), both binary and ASCII, and checks the cloud is unchanged.
inline void CheckRoundTrip(
    const Cloud& cloud, FuzzFile* out,
    const std::function<void(const std::string&, const Cloud&, const Labels*, bool)>& write,
    const CloudReader& read) {
  for (bool binary : {true, false}) {
    write(out->path(), cloud, nullptr, binary);
    CheckSameCloud(cloud, read(out->path(), nullptr), /*nan_matches_nan=*/!binary);
  }
}

// Any bytes either read with `read` as a well-formed cloud (its note true) that survives the round
// trip through `write` (binary and ASCII), or throw IoError; anything else is a finding.
inline int FuzzCloudFormat(
    const uint8_t* data, size_t size, const CloudReader& read,
    const std::function<void(const std::string&, const Cloud&, const Labels*, bool)>& write) {
  static FuzzFile in, out;
  in.Write(data, size);
  Cloud cloud;
  std::string note;
  try {
    cloud = read(in.path(), &note);
  } catch (const IoError&) {
    return 0;
  }
  CheckCloudShape(cloud);
  CheckIntensityNote(cloud, note);
  CheckRoundTrip(cloud, &out, write, read);
  return 0;
}

}  // namespace lpir::fuzz
