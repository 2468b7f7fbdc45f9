#include "host/api/mount_estimate.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <random>
#include <vector>

namespace lpir {
namespace {

constexpr int kSide = int(2 * kMountReach / kMountCell);  // cells along x and along y

struct Lowest {
  double x, y, z;
};

// Least squares of z = a x + b y + c over the points of `pts` with keep[i]; false when fewer
// than three or the normal equations are singular.
bool FitPlane(const std::vector<Lowest>& pts, const std::vector<char>& keep, double out[3]) {
  double m[3][4] = {};  // [x y 1]^T [x y 1] | [x y 1]^T z
  size_t count = 0;
  for (size_t i = 0; i < pts.size(); ++i) {
    if (!keep[i]) continue;
    const double row[3] = {pts[i].x, pts[i].y, 1.0};
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) m[r][c] += row[r] * row[c];
      m[r][3] += row[r] * pts[i].z;
    }
    ++count;
  }
  if (count < 3) return false;
  for (int c = 0; c < 3; ++c) {  // Gauss-Jordan with partial pivoting
    int pivot = c;
    for (int r = c + 1; r < 3; ++r)
      if (std::fabs(m[r][c]) > std::fabs(m[pivot][c])) pivot = r;
    if (!(std::fabs(m[pivot][c]) > 1e-9)) return false;
    if (pivot != c)
      for (int k = 0; k < 4; ++k) std::swap(m[c][k], m[pivot][k]);
    for (int r = 0; r < 3; ++r) {
      if (r == c) continue;
      const double f = m[r][c] / m[c][c];
      for (int k = c; k < 4; ++k) m[r][k] -= f * m[c][k];
    }
  }
  for (int r = 0; r < 3; ++r) out[r] = m[r][3] / m[r][r];
  return true;
}

// Cells whose lowest point lies within kMountInlier of `plane` (z = p0 x + p1 y + p2), marked in
// `keep` when given.
size_t Within(const std::vector<Lowest>& pts, const double plane[3], std::vector<char>* keep) {
  size_t count = 0;
  for (size_t i = 0; i < pts.size(); ++i) {
    const double residual = pts[i].z - (plane[0] * pts[i].x + plane[1] * pts[i].y + plane[2]);
    const bool in = std::fabs(residual) < kMountInlier;
    if (keep) (*keep)[i] = in;
    count += in;
  }
  return count;
}

float NoSubnormal(double v) { return std::fabs(v) < double(FLT_MIN) ? 0.0f : float(v); }

}  // namespace

MountEstimate EstimateMount(const Cloud& cloud, const SensorProfile& sensor,
                            const Mount& fallback) {
  MountEstimate out;
  out.mount = fallback;
  thread_local std::vector<Lowest> cells;  // scratch reused from frame to frame
  thread_local std::vector<Lowest> pts;
  thread_local std::vector<char> keep;
  cells.assign(size_t(kSide) * kSide, Lowest{0, 0, INFINITY});
  const double min_r = sensor.min_range, max_r = std::min<double>(sensor.max_range, kMountReach);
  for (size_t i = 0; i < cloud.size(); ++i) {  // step 1
    const double x = cloud.x(i), y = cloud.y(i), z = cloud.z(i);
    if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(z)) continue;
    if (x == 0 && y == 0 && z == 0) continue;
    const double r = std::hypot(x, y);
    if (r < min_r || r > max_r) continue;
    const int cx = std::clamp(int(std::floor(x / kMountCell)) + kSide / 2, 0, kSide - 1);
    const int cy = std::clamp(int(std::floor(y / kMountCell)) + kSide / 2, 0, kSide - 1);
    Lowest& cell = cells[size_t(cy) * kSide + cx];
    if (z < cell.z) cell = Lowest{x, y, z};
  }
  pts.clear();
  for (const Lowest& c : cells)
    if (c.z != INFINITY) pts.push_back(c);
  out.cells = pts.size();
  if (pts.size() < kMountMinCells) return out;
  // Step 2: the plane through three cells that the most cells lie within kMountInlier of.
  std::mt19937 rng(kMountSeed);  // raw outputs: the same on every standard library
  const uint32_t n = uint32_t(pts.size());
  size_t best_count = 0;
  double plane[3] = {0, 0, 0};
  keep.assign(pts.size(), 0);
  for (uint32_t iteration = 0; iteration < kMountTries; ++iteration) {
    const uint32_t a = rng() % n, b = rng() % n, c = rng() % n;
    if (a == b || b == c || a == c) continue;
    double candidate[3];
    keep[a] = keep[b] = keep[c] = 1;
    const bool solved = FitPlane(pts, keep, candidate);
    keep[a] = keep[b] = keep[c] = 0;
    if (!solved || !(std::fabs(candidate[0]) <= kMountMaxTilt) ||
        !(std::fabs(candidate[1]) <= kMountMaxTilt))
      continue;
    const size_t count = Within(pts, candidate, nullptr);
    if (count > best_count) best_count = count, std::copy(candidate, candidate + 3, plane);
  }
  if (best_count == 0) return out;
  for (int refine = 0; refine < 3; ++refine) {  // step 3
    Within(pts, plane, &keep);
    if (!FitPlane(pts, keep, plane)) return out;
  }
  out.kept = Within(pts, plane, &keep);
  const double height = -plane[2];  // step 4
  if (out.kept < kMountMinCells || !(std::fabs(plane[0]) <= kMountMaxTilt) ||
      !(std::fabs(plane[1]) <= kMountMaxTilt) || !(height >= kMountMinHeight) ||
      !(height <= kMountMaxHeight))
    return out;
  out.mount = Mount{NoSubnormal(plane[0]), NoSubnormal(plane[1]), float(height)};
  out.estimated = true;
  return out;
}

MountEstimate FrameMount(const Cloud& cloud, const SensorProfile& sensor, const Params& params) {
  if (sensor.mount == MountSource::kPerFrame) return EstimateMount(cloud, sensor, MountOf(params));
  MountEstimate fixed;
  fixed.mount = MountOf(params);
  return fixed;
}

}  // namespace lpir
