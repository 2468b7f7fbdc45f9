// calibrate (paper III-B.3, eqs. 2-3; contract and sign convention in calibrate.h).
// Offline and on the CPU, so outside the bit-exact contract: atan2 and doubles are used freely.
//
// How the paper's steps are read (each choice is measured in tests/calibrate_test.cpp):
//  1. Reflection noise first (III-B.1, Fig. 1: noise is removed before the tilt is estimated): a
//     point is dropped when z < h_noise, the profile's parameter (ParamsForSensor, so a
//     `param h_noise` override applies), as prepare drops it. z is not corrected yet: the tilt
//     is what is being measured, and the profile's own k_xz, k_yz are ignored so that a
//     recalibration never compounds an old one.
//  2. "Generate a LiDAR depth image ... extract the point cloud from four main directions" and
//     "sample point clouds within a 3-pixel width on both sides of each fitting line": a point's
//     range-image column is eq. 1's u = floor(W/2 (1 - atan2(y, x)/pi)) mod W (W = the profile's
//     width), so the directions are the column boundaries front u = W/2 (azimuth 0, +x),
//     left W/4 (+y), right 3W/4 (-y), rear 0 (-x); a band is the band_columns columns on each
//     side of its boundary (2 x 3 = 6 columns by default). Every point of those columns is taken,
//     not only each pixel's nearest: a spinning LiDAR gives one return per beam and column.
//  3. "Valid fitting points are selected by setting ground height thresholds h_thr and distance
//     thresholds d_thr": planar distance r = sqrt(x^2 + y^2) within [max(min_distance,
//     min_range), min(max_distance, max_range)], and |z + sensor_height| <= height_gate +
//     r * tan(max_tilt_deg) (the gate widens with r so that ground tilted by up to max_tilt_deg
//     still passes 30 m out).
//  4. Eq. 2 by RANSAC: the front and rear bands give the XOZ line z = k_xz x - b_x, the left and
//     right bands the YOZ line z = k_yz y - b_y. RANSAC draws pairs of points from a
//     std::mt19937 seeded with ransac_seed (+ 1 for YOZ), a fixed number of iterations, using its
//     raw 32-bit outputs modulo n (portable: std::uniform_int_distribution is not); a pair closer
//     than 1 m in a, or whose slope exceeds tan(max_tilt_deg), is skipped (a wall or a car's back
//     is never taken for the ground). The best line has the most inliers (vertical residual <=
//     inlier_threshold; ties: the first found), then a least-squares refit on its inliers
//     (Eigen, QR), the inliers taken again from the refit line, and a second refit.
//  5. Our addition: the bands are 6 columns wide, so a front point lies up to 0.9 % of its
//     distance off the x axis and the roll leaks into the XOZ line (and the pitch into YOZ). The
//     two fits therefore run twice: the second time each line fits z - k_other * other, with the
//     other line's slope from the first pass. Eq. 2's lines are then the plane's exact cuts.
//  6. Refusals, in this order: fewer than min_points gated points on a line (too few); a line
//     with inlier fraction < min_inlier_fraction or inlier RMS > max_rms, or the ground found
//     above the sensor (not flat); |b_x - b_y| > max_b_diff ("the error between them should be
//     less than 1 cm. If the error is too large, recalibration is required on a flatter
//     surface"). Every refusal's reason says what was measured and what to do.
#include "host/eval/calibrate.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <stdexcept>

#include "reference_cpu/params.h"

namespace lpir {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kMinPairSpan = 1.0;  // m, the two points of a RANSAC sample lie this far apart

// One gated point as one line sees it: a along the line's axis, `other` across it.
struct LinePoint {
  double a, other, z;
};

std::string Format(const char* format, double v) {
  char buf[64];
  std::snprintf(buf, sizeof(buf), format, v);
  return buf;
}

// Range-image column of (x, y), eq. 1.
uint32_t Column(double x, double y, uint32_t width) {
  const double u = 0.5 * (1.0 - std::atan2(y, x) / kPi) * double(width);
  const int64_t col = int64_t(std::floor(u));
  return uint32_t(((col % int64_t(width)) + int64_t(width)) % int64_t(width));
}

// The direction whose band holds column `col`, or -1.
int BandOf(uint32_t col, uint32_t width, uint32_t band) {
  const uint32_t boundary[4] = {width / 2, 0, width / 4, 3 * width / 4};
  for (int d = 0; d < 4; ++d) {
    const uint32_t off = (col + width - boundary[d]) % width;  // columns past the boundary
    if (off < band || off >= width - band) return d;
  }
  return -1;
}

struct Line {
  double k = 0, c = 0;  // z = k a + c
};

// Points within `threshold` of `line` (vertical residual of z - k_other * other).
std::vector<uint32_t> Inliers(const std::vector<LinePoint>& pts, double k_other, const Line& line,
                              double threshold) {
  std::vector<uint32_t> in;
  for (uint32_t i = 0; i < pts.size(); ++i) {
    const double z = pts[i].z - k_other * pts[i].other;
    if (std::abs(z - (line.k * pts[i].a + line.c)) <= threshold) in.push_back(i);
  }
  return in;
}

// Least squares z - k_other * other = k a + c over `idx` (Eigen, column-pivoting QR).
Line Refit(const std::vector<LinePoint>& pts, double k_other, const std::vector<uint32_t>& idx) {
  Eigen::MatrixXd a(idx.size(), 2);
  Eigen::VectorXd z(idx.size());
  for (size_t r = 0; r < idx.size(); ++r) {
    const LinePoint& p = pts[idx[r]];
    a(r, 0) = p.a, a(r, 1) = 1.0;
    z(r) = p.z - k_other * p.other;
  }
  const Eigen::Vector2d sol = a.colPivHouseholderQr().solve(z);
  return {sol(0), sol(1)};
}

// Eq. 2 by RANSAC + two least-squares refits (step 4 above). Returns the fit; `points` and
// `inliers` say how it went (inliers 0: no admissible sample at all).
CalibLine FitLine(const std::vector<LinePoint>& pts, double k_other, const CalibrateOptions& o,
                  uint32_t seed) {
  CalibLine out;
  out.points = uint32_t(pts.size());
  const uint32_t n = uint32_t(pts.size());
  if (n < 2) return out;
  const double max_slope = std::tan(double(o.max_tilt_deg) * kPi / 180.0);
  const double thr = o.inlier_threshold;
  std::mt19937 rng(seed);
  Line best;
  uint32_t best_count = 0;
  for (uint32_t it = 0; it < o.ransac_iterations; ++it) {
    const uint32_t i = rng() % n, j = rng() % n;
    const double da = pts[j].a - pts[i].a;
    if (std::abs(da) < kMinPairSpan) continue;
    const double zi = pts[i].z - k_other * pts[i].other, zj = pts[j].z - k_other * pts[j].other;
    const double k = (zj - zi) / da;
    if (std::abs(k) > max_slope) continue;
    const Line cand{k, zi - k * pts[i].a};
    uint32_t count = 0;
    for (const LinePoint& p : pts)
      count += std::abs(p.z - k_other * p.other - (cand.k * p.a + cand.c)) <= thr ? 1u : 0u;
    if (count > best_count) best_count = count, best = cand;
  }
  if (best_count < 2) return out;
  std::vector<uint32_t> in = Inliers(pts, k_other, best, thr);
  for (int pass = 0; pass < 2 && in.size() >= 2; ++pass) {
    const Line refit = Refit(pts, k_other, in);
    std::vector<uint32_t> again = Inliers(pts, k_other, refit, thr);
    if (again.size() < 2) break;
    best = refit;
    in.swap(again);
  }
  double sq = 0;
  for (uint32_t i : in) {
    const double r = pts[i].z - k_other * pts[i].other - (best.k * pts[i].a + best.c);
    sq += r * r;
  }
  out.k = best.k;
  out.b = -best.c;
  out.inliers = uint32_t(in.size());
  out.inlier_fraction = double(in.size()) / double(n);
  out.rms = in.empty() ? 0.0 : std::sqrt(sq / double(in.size()));
  return out;
}

std::string GateText(double d_min, double d_max, const CalibrateOptions& o, float height) {
  return "planar distance " + Format("%g", d_min) + "-" + Format("%g", d_max) +
         " m, height within " + Format("%g", o.height_gate) + " m + tan(" +
         Format("%g", o.max_tilt_deg) + " deg) x distance of z = -" + Format("%g", height) +
         " m (the profile's sensor_height), " + std::to_string(o.band_columns) +
         " columns either side of each direction";
}

// The flatness check of one line (step 6); "" when it passes.
std::string FlatnessProblem(const char* name, const CalibLine& l, const CalibrateOptions& o) {
  if (l.inliers < 2 || l.inlier_fraction < o.min_inlier_fraction || l.rms > o.max_rms)
    return std::string(name) + ": only " + Format("%.1f", 100.0 * l.inlier_fraction) + " % of " +
           std::to_string(l.points) + " gated points lie within " +
           Format("%g", 100.0 * o.inlier_threshold) + " cm of the best line (need " +
           Format("%g", 100.0 * o.min_inlier_fraction) + " %), inlier RMS residual " +
           Format("%.2f", 100.0 * l.rms) + " cm (limit " + Format("%g", 100.0 * o.max_rms) + " cm)";
  if (l.b <= 0)
    return std::string(name) + ": the fitted ground crosses the sensor's z axis " +
           Format("%.3f", -l.b) + " m above it";
  return "";
}

}  // namespace

const char* CalibDirectionName(int direction) {
  static const char* const kNames[4] = {"front", "rear", "left", "right"};
  return direction >= 0 && direction < 4 ? kNames[direction] : "?";
}

const char* CalibRefusalName(CalibRefusal refusal) {
  switch (refusal) {
    case CalibRefusal::kNone:
      return "";
    case CalibRefusal::kTooFewPoints:
      return "too_few_points";
    case CalibRefusal::kNotFlat:
      return "not_flat";
    case CalibRefusal::kHeightsDisagree:
      return "heights_disagree";
  }
  return "?";
}

Calibration Calibrate(const std::vector<Cloud>& scans, const SensorProfile& sensor,
                      const CalibrateOptions& o) {
  const double d_min = std::max(double(o.min_distance), double(sensor.min_range));
  const double d_max = std::min(double(o.max_distance), double(sensor.max_range));
  if (!(d_max > d_min))
    throw std::invalid_argument("calibrate: the distance gate " + Format("%g", d_min) + "-" +
                                Format("%g", d_max) + " m is empty");
  if (o.band_columns == 0 || 2 * o.band_columns > sensor.width / 4)
    throw std::invalid_argument("calibrate: band_columns must lie in 1.." +
                                std::to_string(sensor.width / 8));
  if (!(o.max_tilt_deg > 0 && o.max_tilt_deg < 45) || !(o.inlier_threshold > 0) ||
      !(o.height_gate > 0) || o.ransac_iterations == 0)
    throw std::invalid_argument(
        "calibrate: max_tilt_deg must lie in (0, 45), inlier_threshold and height_gate must be "
        "positive, ransac_iterations at least 1");
  const Params params = ParamsForSensor(sensor);
  const double tilt_gate = std::tan(double(o.max_tilt_deg) * kPi / 180.0);

  Calibration out;
  out.scans = uint32_t(scans.size());
  // Steps 1-3: noise filter, bands, gates; the gated points of every scan pooled.
  std::vector<LinePoint> xoz, yoz;
  for (const Cloud& cloud : scans) {
    for (size_t i = 0; i < cloud.size(); ++i) {
      const double x = cloud.x(i), y = cloud.y(i), z = cloud.z(i);
      if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(z)) continue;
      const double r = std::sqrt(x * x + y * y);
      if (r < d_min || r > d_max) continue;  // d_thr
      const int dir = BandOf(Column(x, y, sensor.width), sensor.width, o.band_columns);
      if (dir < 0) continue;
      if (o.noise_filter && float(z) < params.h_noise) {  // III-B.1
        ++out.noise_points;
        continue;
      }
      if (std::abs(z + double(sensor.sensor_height)) > double(o.height_gate) + r * tilt_gate)
        continue;  // h_thr
      ++out.band_points[dir];
      if (dir == kCalibFront || dir == kCalibRear) {
        xoz.push_back({x, y, z});
      } else {
        yoz.push_back({y, x, z});
      }
    }
  }
  out.xoz.points = uint32_t(xoz.size());
  out.yoz.points = uint32_t(yoz.size());
  const std::string gates = GateText(d_min, d_max, o, sensor.sensor_height);
  if (xoz.size() < o.min_points || yoz.size() < o.min_points) {
    const bool x_short = xoz.size() < o.min_points;
    out.refusal = CalibRefusal::kTooFewPoints;
    out.reason = "too few points survive the gates: " +
                 std::string(x_short ? "front + rear (XOZ line): " : "left + right (YOZ line): ") +
                 std::to_string(x_short ? xoz.size() : yoz.size()) + " (front " +
                 std::to_string(out.band_points[0]) + ", rear " +
                 std::to_string(out.band_points[1]) + ", left " +
                 std::to_string(out.band_points[2]) + ", right " +
                 std::to_string(out.band_points[3]) + "), need at least " +
                 std::to_string(o.min_points) + " per line (gates: " + gates +
                 "). Record flat open ground all around the vehicle (an empty parking lot or "
                 "plaza), check that the sensor profile (width, sensor_height, range limits) "
                 "matches the scans, or pass more scans";
    return out;
  }

  // Steps 4-5: eq. 2 twice, the second pass with the other line's slope removed.
  double k_xz = 0, k_yz = 0;
  for (int pass = 0; pass < 2; ++pass) {
    out.xoz = FitLine(xoz, k_yz, o, o.ransac_seed);
    out.yoz = FitLine(yoz, k_xz, o, o.ransac_seed + 1u);
    k_xz = out.xoz.k, k_yz = out.yoz.k;
  }
  out.k_xz = out.xoz.k, out.k_yz = out.yoz.k;
  out.b_x = out.xoz.b, out.b_y = out.yoz.b;
  out.pitch_deg = std::atan(out.k_xz) * 180.0 / kPi;
  out.roll_deg = std::atan(out.k_yz) * 180.0 / kPi;

  // Step 6: flatness, then the paper's |b_x - b_y| check.
  std::string problem = FlatnessProblem("front + rear (XOZ line)", out.xoz, o);
  const std::string y_problem = FlatnessProblem("left + right (YOZ line)", out.yoz, o);
  if (!y_problem.empty()) problem += (problem.empty() ? "" : "; ") + y_problem;
  if (!problem.empty()) {
    out.refusal = CalibRefusal::kNotFlat;
    out.reason = "the ground is not flat enough: " + problem +
                 ". Calibrate on a flat, open surface (an empty parking lot or plaza) with no "
                 "objects, ramps or curbs within " +
                 Format("%g", d_max) + " m ahead, behind or to the sides";
    return out;
  }
  const double diff = std::abs(out.b_x - out.b_y);
  if (diff > double(o.max_b_diff)) {
    out.refusal = CalibRefusal::kHeightsDisagree;
    out.reason = "b_x = " + Format("%.4f", out.b_x) +
                 " m (front + rear) and b_y = " + Format("%.4f", out.b_y) +
                 " m (left + right) differ by " + Format("%.2f", 100.0 * diff) +
                 " cm, more than the " + Format("%g", 100.0 * o.max_b_diff) +
                 " cm allowed (paper III-B.3): the ground ahead and behind is not one plane "
                 "with the ground to the sides (a crowned road, curbs, sidewalks?). Recalibrate "
                 "on a flatter surface";
    return out;
  }
  return out;
}

SensorProfile ApplyCalibration(SensorProfile sensor, const Calibration& c, bool set_height) {
  if (!c.ok())
    throw std::invalid_argument("a refused calibration cannot go into a sensor profile: " +
                                c.reason);
  sensor.k_xz = float(c.k_xz);
  sensor.k_yz = float(c.k_yz);
  sensor.b_x = float(c.b_x);
  sensor.b_y = float(c.b_y);
  if (set_height) sensor.sensor_height = float(0.5 * (c.b_x + c.b_y));
  return sensor;
}

}  // namespace lpir
