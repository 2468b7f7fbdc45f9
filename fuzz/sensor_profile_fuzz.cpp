// Fuzz target of the sensor-profile reader (host/io/sensor_profile.h). It covers the calibration
// files too: `lpir-gseg calibrate` writes its result (k_xz, k_yz, b_x, b_y) as a sensor profile,
// read back by this same reader. Any bytes either throw IoError or give a profile that keeps the
// reader's promises (beams = elevation entries, strictly descending within -90..90, width a
// multiple of 64, max_range > min_range), reads back identically after WriteSensorProfile, and
// gives parameters (ParamsForSensor) or std::invalid_argument, both as documented; then, for
// images and grids of at most 2^16 pixels and cells, the CPU reference labels a small street under
// it (every stage runs, so a profile value that drives one into undefined behaviour is a finding).
// Tables are built only for grids of at most 2^16 rings: a profile may ask for 4e9 rings, which
// ParamsForSensor accepts and MakeTables would try to build (a limit for the parameters, noted in
// the issue-6 report).
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <stdexcept>

#include "fuzz/fuzz_file.h"
#include "host/io/io_error.h"
#include "host/io/sensor_profile.h"
#include "reference_cpu/cloud.h"
#include "reference_cpu/frame.h"
#include "reference_cpu/params.h"
#include "reference_cpu/pipeline.h"

namespace {

// Rings of road at 2-60 m, a wall and a car-sized box, a few invalid points, rings of intensity
// 0-1 (raw: the profile's scale applies).
lpir::Cloud Street() {
  lpir::Cloud c;
  for (int k = 0; k < 720; ++k) {
    const float a = float(k) * 0.0087266f, r = 2.0f + float(k % 30) * 2.0f;
    c.Push(r * std::cos(a), r * std::sin(a), -1.7f + 0.01f * float(k % 7), float(k % 100) / 99);
  }
  for (int k = 0; k < 60; ++k) {
    c.Push(8.0f, -4.0f + 0.15f * float(k), -1.7f + 0.05f * float(k % 40), 0.4f);  // a wall
    c.Push(5.0f + 0.05f * float(k % 30), 1.0f, -1.2f + 0.01f * float(k), 0.6f);   // a car side
  }
  c.Push(0, 0, 0, 0);
  c.Push(std::nanf(""), 1, 1, 1);
  c.Push(1e30f, 1, 1, 1);
  return c;
}

bool SameBits(float a, float b) { return std::memcmp(&a, &b, sizeof(float)) == 0; }

bool SameBits(const std::vector<float>& a, const std::vector<float>& b) {
  return a.size() == b.size() &&
         (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0);
}

bool SameProfile(const lpir::SensorProfile& a, const lpir::SensorProfile& b) {
  if (a.overrides.size() != b.overrides.size()) return false;
  for (size_t i = 0; i < a.overrides.size(); ++i) {
    if (a.overrides[i].first != b.overrides[i].first ||
        !SameBits(a.overrides[i].second, b.overrides[i].second))
      return false;
  }
  if (a.frame_points != b.frame_points) return false;
  return a.name == b.name && a.beams == b.beams && a.width == b.width &&
         a.max_points == b.max_points && SameBits(a.elevation_deg, b.elevation_deg) &&
         SameBits(a.beam_origin_z, b.beam_origin_z) && a.ring_zero_is_top == b.ring_zero_is_top &&
         SameBits(a.sensor_height, b.sensor_height) && SameBits(a.min_range, b.min_range) &&
         SameBits(a.max_range, b.max_range) && SameBits(a.k_xz, b.k_xz) &&
         SameBits(a.k_yz, b.k_yz) && SameBits(a.b_x, b.b_x) && SameBits(a.b_y, b.b_y);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace lpir;
  static fuzz::FuzzFile in, out;
  in.Write(data, size);
  SensorProfile profile;
  try {
    // A path with a '/' is read as a file; no sensors folder is needed.
    profile = LoadSensorProfile(in.path(), "/nonexistent");
  } catch (const IoError&) {
    return 0;
  }
  LPIR_FUZZ_CHECK(profile.beams >= 1 && profile.elevation_deg.size() == profile.beams);
  for (size_t i = 0; i < profile.elevation_deg.size(); ++i) {
    LPIR_FUZZ_CHECK(profile.elevation_deg[i] >= -90 && profile.elevation_deg[i] <= 90);
    LPIR_FUZZ_CHECK(i == 0 || profile.elevation_deg[i] < profile.elevation_deg[i - 1]);
  }
  LPIR_FUZZ_CHECK(profile.beam_origin_z.empty() || profile.beam_origin_z.size() == profile.beams);
  LPIR_FUZZ_CHECK(profile.width > 0 && profile.width % 64 == 0);
  LPIR_FUZZ_CHECK(profile.max_range > profile.min_range);

  WriteSensorProfile(out.path(), profile);
  LPIR_FUZZ_CHECK(SameProfile(profile, LoadSensorProfile(out.path(), "/nonexistent")));

  Params params;
  try {
    params = ParamsForSensor(profile);
  } catch (const std::invalid_argument&) {
    return 0;
  }
  LPIR_FUZZ_CHECK(params.width == profile.width && params.beams == profile.beams);
  if (uint64_t(params.rings_near) + params.rings_far > (1u << 16)) return 0;
  const Tables tables = MakeTables(profile, params);
  LPIR_FUZZ_CHECK(tables.beam_bound.size() == profile.beams - 1);
  LPIR_FUZZ_CHECK(tables.column_dir.size() == 2 * size_t(profile.width));
  LPIR_FUZZ_CHECK(tables.ring_bound2.size() == size_t(params.rings_near) + params.rings_far);
  // The whole method on a small street under the profile (small images and grids only, to keep
  // each input fast): any value the reader lets through must give labels, not undefined behaviour.
  const uint64_t cells = uint64_t(params.rings_near) * params.sectors_near +
                         uint64_t(params.rings_far) * params.sectors_far;
  if (uint64_t(profile.width) * profile.beams > (1u << 16) || cells > (1u << 16)) return 0;
  static const Cloud street = Street();
  Frame frame;
  RunReference(street, params, tables, frame);
  LPIR_FUZZ_CHECK(frame.label.size() == street.size() && frame.why.size() == street.size());
  for (size_t i = 0; i < street.size(); ++i) LPIR_FUZZ_CHECK(frame.label[i] <= 1);
  return 0;
}
