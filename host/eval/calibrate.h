// calibrate (offline, CPU, Eigen; paper III-B.3, eqs. 2-3): the LiDAR's mount tilt from
// scans of flat ground. A pure function: clouds + sensor profile + options in, the fitted lines or
// a refusal with its reason out. It never reads files or prints (apps/cli/cmd_calibrate.cpp does).
//
// SIGN CONVENTION (the simulator's, apps/sim/scene.h, so a simulated tilt reads back as itself).
// In the sensor frame flat ground is the plane
//     z = k_xz * x + k_yz * y - b,   pitch_deg = atan(k_xz), roll_deg = atan(k_yz) in degrees,
// positive pitch: the ground rises ahead (+x), positive roll: it rises to the left (+y). Eq. 2's
// lines are z = k_xz * x - b_x (front and rear) and z = k_yz * y - b_y (left and right): b_x, b_y
// are POSITIVE heights, the distance along the sensor's own z axis from its origin down to the
// ground (= minus the lines' intercepts; for a simulated scene exactly its `sensor_height`; the
// perpendicular height is b / sqrt(1 + k_xz^2 + k_yz^2)). Eq. 3, z_t = z - (k_xz x + k_yz y),
// then puts flat ground at z_t = -b everywhere.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "reference_cpu/cloud.h"
#include "reference_cpu/sensor.h"

namespace lpir {

// Every threshold of the calibration, with its unit. The defaults are measured in
// tests/calibrate_test.cpp (simulated HDL-64E scenes, pitch and roll in [-5, 5] degrees).
struct CalibrateOptions {
  uint32_t band_columns = 3;         // range-image columns either side of each direction (III-B.3:
                                     // "a 3-pixel width on both sides of each fitting line")
  float min_distance = 3.0f;         // m, d_thr: planar distance gate, lower end (and >= min_range)
  float max_distance = 30.0f;        // m, d_thr: upper end (and <= max_range)
  float height_gate = 0.5f;          // m, h_thr: |z + sensor_height| <= height_gate + distance *
                                     // tan(max_tilt_deg), so tilted ground far out still passes
  float max_tilt_deg = 10.0f;        // steepest mount tilt looked for: widens the height gate and
                                     // bounds the RANSAC slopes (a wall is never a ground line)
  float inlier_threshold = 0.05f;    // m, vertical distance of a RANSAC inlier to its line
  uint32_t ransac_iterations = 400;  // fixed count: the same input gives the same output
  uint32_t ransac_seed = 0x0CA11B7Eu;  // std::mt19937 seed (raw outputs, portable across libs)
  uint32_t min_points = 60;            // gated points each line needs (too few: refused)
  float min_inlier_fraction = 0.6f;    // flatness: share of a line's gated points within
                                       // inlier_threshold of it (below: refused, not flat)
  float max_rms = 0.03f;               // m, flatness: RMS vertical residual of a line's inliers
  float max_b_diff = 0.01f;            // m, |b_x - b_y| allowed (III-B.3: "less than 1 cm")
  // Drop reflection noise first (III-B.1: z < h_noise, the profile's value, on the uncorrected
  // z).
  bool noise_filter = true;
};

// The four directions of III-B.3 and their range-image columns (eq. 1: u = W/2 (1 - az/pi)).
enum CalibDirection { kCalibFront = 0, kCalibRear = 1, kCalibLeft = 2, kCalibRight = 3 };
const char* CalibDirectionName(int direction);  // "front", "rear", "left", "right"

// One line of eq. 2, z = k * a - b with a = x (XOZ, front + rear) or a = y (YOZ, left + right).
struct CalibLine {
  double k = 0;                // slope: k_xz or k_yz
  double b = 0;                // m, b_x or b_y (positive: the ground lies below the sensor)
  uint32_t points = 0;         // gated points offered to RANSAC
  uint32_t inliers = 0;        // within inlier_threshold of the final line
  double inlier_fraction = 0;  // inliers / points
  double rms = 0;              // m, RMS vertical residual of the inliers
};

enum class CalibRefusal {
  kNone,             // accepted
  kTooFewPoints,     // fewer than min_points survive the gates on a line
  kNotFlat,          // a line's inlier fraction or residual is out of bounds
  kHeightsDisagree,  // |b_x - b_y| > max_b_diff
};
const char* CalibRefusalName(CalibRefusal refusal);  // "", "too_few_points", "not_flat", ...

struct Calibration {
  CalibRefusal refusal = CalibRefusal::kNone;
  std::string reason;                      // why it was refused and what to do; empty when accepted
  double k_xz = 0, k_yz = 0;               // eq. 2 slopes
  double b_x = 0, b_y = 0;                 // m, eq. 2 heights (see the sign convention above)
  double pitch_deg = 0, roll_deg = 0;      // atan(k_xz), atan(k_yz)
  CalibLine xoz, yoz;                      // the two fits (filled as far as the calibration got)
  uint32_t band_points[4] = {0, 0, 0, 0};  // gated points per CalibDirection, all scans
  uint32_t noise_points = 0;               // points of the bands dropped as reflection noise
  uint32_t scans = 0;
  bool ok() const { return refusal == CalibRefusal::kNone; }
};

// Calibrates from `scans` (sensor frame; several scans pool their gated points). Deterministic.
// std::invalid_argument for inconsistent options (e.g. max_distance <= min_distance).
Calibration Calibrate(const std::vector<Cloud>& scans, const SensorProfile& sensor,
                      const CalibrateOptions& options = {});

// `sensor` with k_xz, k_yz, b_x, b_y taken from an accepted calibration (std::invalid_argument
// for a refused one); with `set_height`, sensor_height becomes (b_x + b_y) / 2 as well.
SensorProfile ApplyCalibration(SensorProfile sensor, const Calibration& calibration,
                               bool set_height = false);

}  // namespace lpir
