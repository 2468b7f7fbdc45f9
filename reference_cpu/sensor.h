// What the pipeline needs to know about a LiDAR. Parsed from sensors/<name>.txt by
// host/io/sensor_profile.h; the core never reads files.
#pragma once
#include <string>
#include <utility>
#include <vector>

namespace lpir {

// Bounds on a profile that keep every valid point inside the fixed-point ranges of coarse_segment
// and feature_maps (mm in int32, 0.1 mm moments in int64); ParamsForSensor and the profile reader
// enforce them.
constexpr float kMaxProfileRange = 1000.0f;   // m, the largest max_range
constexpr float kMaxProfileTiltSlope = 1.0f;  // |k_xz|, |k_yz|: a mount tilt of at most 45 degrees

// How the sensor covers its field of view, and so what a range-image row is.
enum class ScanPattern {
  kSpinning,  // beams on a spinning head: a row per beam, a ring field read as the row
  // Non-repetitive (Livox): no beams, a row per elevation bin of the table, a ring field ignored.
  kRosette,  // Risley prisms: a rosette filling a circle (Mid-40, Mid-70, Avia)
  kBand,     // a full turn of azimuth over the table's elevations (Mid-360)
};

// Where the mount (k_xz, k_yz, sensor_height) comes from.
enum class MountSource {
  kFixed,     // the profile's values, for every frame
  kPerFrame,  // estimated from each cloud's lowest surface (host/api/mount_estimate.h); the
              // profile's values where a cloud shows too little of it
};

struct SensorProfile {
  std::string name;  // e.g. "hdl64e"
  ScanPattern pattern = ScanPattern::kSpinning;
  MountSource mount = MountSource::kFixed;
  unsigned beams = 64;    // image rows: beams, or elevation bins of a non-repetitive pattern
  unsigned width = 2048;  // image columns (one per azimuth step, 360 degrees)
  // Largest cloud a segmenter takes unless told (0: beams x width x 2, a point a pixel and as
  // many second returns); for a sensor that fires more often a turn than the image has columns.
  unsigned max_points = 0;
  // Returns of one 100 ms frame of a non-repetitive pattern (the datasheet's point rate over its
  // 10 Hz): the rays `simulate` casts a frame (apps/sim/scan_pattern.h). 0: not given; a
  // spinning sensor's simulated frame is its beams x width rays.
  unsigned frame_points = 0;
  // Beam elevations (the centres of the elevation bins of a non-repetitive pattern), degrees,
  // row 0 (top) first, descending.
  std::vector<float> elevation_deg;
  // Height of each beam's laser origin above the sensor frame's origin, m, row 0 first (empty:
  // all 0). The HDL-64E fires from 0.1-0.2 m above its centre, which bends near elevations.
  std::vector<float> beam_origin_z;
  bool ring_zero_is_top = false;   // when the file has a ring field: true if ring 0 is the top beam
  float sensor_height = 1.73f;     // m, sensor above the ground it stands on
  float min_range = 2.5f;          // m, planar range below which points are invalid (the car)
  float max_range = 120.0f;        // m, planar range above which points are invalid
  float k_xz = 0.0f, k_yz = 0.0f;  // mount tilt, eq. 2-3 (from `calibrate`)
  float b_x = 0.0f, b_y = 0.0f;    // m, fitted sensor height at the origin, eq. 2 (informative)
  // Parameter overrides, "name value" pairs applied over the defaults (see ApplyOverride).
  std::vector<std::pair<std::string, float>> overrides;
};

}  // namespace lpir
