// Stage 4, coarse segment (paper eqs. 5-7): seeds by the adaptive height threshold, one plane per
// cell from its seeds, ground = within the cell's point-to-plane threshold.
// In: cloud xy, zt, flags, point_cell, cell_zmin/zmax/count; tables.ring_inner.
// Out: cell_seed_mode, cell_plane (8 ints per cell), coarse (per point).
//
// Seeds (eq. 5, read as SPEC section 2 says): lambda = cell radial size * slope_max + seed_margin;
// h_nmin = lowest z_t of the non-empty 3x3 neighbour cells (own h_min when none).
//   mode 0 (no seeds): empty; or h_min - h_nmin > lambda + rise_margin (the cell's lowest point
//     sits above what neighbour and slope allow: a car roof, a wall filling the cell); or h_min >
//     -sensor_height + ground_max_above + slope_max * inner radius (far above any ground the
//     slope limit can reach from under the sensor).
//   mode 2 (whole cell): h_max - h_nmin <= h_athr.
//   mode 1: the points with z_t - h_min <= lambda.
// Plane (eqs. 6-7): in integers first. Coordinates in mm (ToFixed); mean = sum / n (the mean of
// the seeds: eq. 7 says of non-ground points, we read it as of the seeds); centred second moments
// summed in int64 (order-independent); shifted down to 24 bits so they become floats exactly. The
// normal, the eigenvector of the smallest eigenvalue, is the dominant eigenvector of the adjugate
// (eigenvalues l1 l2 >= l1 l3 >= l2 l3): start from the adjugate's column with the largest
// diagonal, two power steps, each rescaled by an exact power of two. Then the normal becomes a Q14
// integer unit vector with an integer square root, oriented up. Fewer than kMinPlaneSeeds seeds,
// or seeds on a line (second eigenvalue below kMinPlanarity of the first): the horizontal plane
// through the seed mean.
// Threshold: distances n . (p - mean) in mm * 2^14 (int64); thr = max(plane_dist_floor,
// plane_dist_scale * mean seed |distance|) with integer arithmetic. A normal steeper than allowed
// (n_z^2 < normal_min_z2) means no ground in the cell (thr = -1).
// Coarse label: 1 when the point's cell has seeds and |distance| <= thr, else 0.
#include <algorithm>
#include <cstdlib>

#include "reference_cpu/exact.h"
#include "reference_cpu/stages.h"

namespace lpir {
namespace {

constexpr float kMm = 1000.0f;        // metres -> mm
constexpr int64_t kQ = 16384;         // Q14 unit normal
constexpr float kDistUnit = 16384000.0f;  // metres -> mm * 2^14
// Seeds whose second eigenvalue is below this fraction of the first (width below ~3 % of their
// length) lie on a line and get the horizontal plane instead.
constexpr float kMinPlanarity = 1e-3f;
// Fewer seeds than this get the horizontal plane through their mean: a plane fitted to a handful
// of points tilts freely (a car parked beside the sensor: 10 seeds under its body gave a 25-degree
// plane its roof lay within 0.3 m of). Measured (DG F1 07/000964 | 000056; car points labelled
// ground in the demo street, seed 13): 3 seeds 95.56 | 95.17, 1932; 10: 95.56 | 95.15, 1932;
// 16: 95.56 | 95.15, 1; 24: 95.57 | 95.15, 1.
constexpr int32_t kMinPlaneSeeds = 16;

struct CellGeometry {
  uint32_t ring;
  uint32_t sector;
  uint32_t sectors;  // sectors of the ring's zone
};

CellGeometry Geometry(const Params& p, uint32_t cell) {
  const uint32_t near_cells = p.rings_near * p.sectors_near;
  if (cell < near_cells) return {cell / p.sectors_near, cell % p.sectors_near, p.sectors_near};
  const uint32_t c = cell - near_cells;
  return {p.rings_near + c / p.sectors_far, c % p.sectors_far, p.sectors_far};
}

uint32_t CellIndex(const Params& p, uint32_t ring, uint32_t sector) {
  return ring < p.rings_near ? ring * p.sectors_near + sector
                             : p.rings_near * p.sectors_near +
                                   (ring - p.rings_near) * p.sectors_far + sector;
}

// Lowest h_min key among the non-empty cells of the 3x3 neighbourhood (excluding the cell).
uint32_t NeighbourMin(const Params& p, const Frame& f, uint32_t cell) {
  const CellGeometry g = Geometry(p, cell);
  const uint32_t rings = p.rings_near + p.rings_far;
  uint32_t best = kNone;
  for (int dr = -1; dr <= 1; ++dr) {
    const int64_t ring = int64_t(g.ring) + dr;
    if (ring < 0 || ring >= int64_t(rings)) continue;
    const uint32_t sectors = uint32_t(ring) < p.rings_near ? p.sectors_near : p.sectors_far;
    // The neighbour ring's sector under this cell's centre (zones differ in sector count).
    const uint32_t centre = uint32_t(uint64_t(g.sector) * sectors / g.sectors);
    for (int ds = -1; ds <= 1; ++ds) {
      const uint32_t sector = uint32_t((int64_t(centre) + ds + sectors) % sectors);
      const uint32_t other = CellIndex(p, uint32_t(ring), sector);
      if (other == cell || f.cell_count[other] == 0) continue;
      best = std::min(best, f.cell_zmin[other]);
    }
  }
  return best;
}

// Sets n to the Q14 unit normal of the seeds' plane from centred int64 second moments
// (xx, xy, xz, yy, yz, zz); false when degenerate.
bool PlaneNormal(const int64_t m[6], int64_t n[3]) {
  int64_t maxabs = 0;
  for (int k = 0; k < 6; ++k) maxabs = std::max<int64_t>(maxabs, m[k] < 0 ? -m[k] : m[k]);
  int shift = 0;
  while ((maxabs >> shift) >= (int64_t(1) << 24)) ++shift;
  float c[6];
  for (int k = 0; k < 6; ++k) c[k] = float(exact::DivToZero(m[k], int64_t(1) << shift));
  const float c00 = c[0], c01 = c[1], c02 = c[2], c11 = c[3], c12 = c[4], c22 = c[5];
  // Adjugate (symmetric): a_ij, each two products and one difference.
  float t0, t1;
  t0 = c11 * c22; t1 = c12 * c12; const float a00 = t0 - t1;
  t0 = c02 * c12; t1 = c01 * c22; const float a01 = t0 - t1;
  t0 = c01 * c12; t1 = c02 * c11; const float a02 = t0 - t1;
  t0 = c00 * c22; t1 = c02 * c02; const float a11 = t0 - t1;
  t0 = c01 * c02; t1 = c00 * c12; const float a12 = t0 - t1;
  t0 = c00 * c11; t1 = c01 * c01; const float a22 = t0 - t1;
  const float a[3][3] = {{a00, a01, a02}, {a01, a11, a12}, {a02, a12, a22}};
  // Seeds on a line do not span a plane (their normal could point anywhere across the line):
  // the adjugate's trace is l1 l2 + l1 l3 + l2 l3 ~ l1 l2 and the trace squared ~ l1^2, so their
  // ratio ~ l2 / l1, the squared width-to-length ratio of the seed set.
  float trace = c00 + c11;
  trace = trace + c22;
  const float trace2 = trace * trace;
  float adj_trace = a00 + a11;
  adj_trace = adj_trace + a22;
  const float min_adj = trace2 * kMinPlanarity;
  if (!(adj_trace >= min_adj)) return false;
  int col = 0;
  if (a11 > a[col][col]) col = 1;
  if (a22 > a[col][col]) col = 2;
  float v[3] = {a[0][col], a[1][col], a[2][col]};
  for (int step = 0; step < 3; ++step) {
    float mx = std::max(std::max(std::fabs(v[0]), std::fabs(v[1])), std::fabs(v[2]));
    if (!(mx > 0.0f)) return false;
    const float scale = exact::Pow2(-exact::Exponent(mx));  // max |v| into [1, 2)
    for (float& x : v) x = x * scale;
    if (step == 2) break;
    float w[3];
    for (int r = 0; r < 3; ++r) {
      float s = a[r][0] * v[0];
      s = s + a[r][1] * v[1];
      s = s + a[r][2] * v[2];
      w[r] = s;
    }
    v[0] = w[0], v[1] = w[1], v[2] = w[2];
  }
  if (v[2] < 0.0f) v[0] = -v[0], v[1] = -v[1], v[2] = -v[2];
  int64_t q[3];
  uint64_t len2 = 0;
  for (int k = 0; k < 3; ++k) {
    q[k] = exact::ToFixed(v[k], 1048576.0f);  // 2^20
    len2 += uint64_t(q[k] * q[k]);
  }
  const int64_t len = int64_t(exact::Isqrt(len2));
  if (len == 0) return false;
  for (int k = 0; k < 3; ++k) n[k] = exact::DivToZero(q[k] * kQ, len);
  return true;
}


// Buffers reused from frame to frame (the reference is single-threaded).
struct Scratch {
  std::vector<int64_t> sum, mom, dist_sum;
  std::vector<int32_t> fixed;  // per point with a cell: x, y, z_t in mm
  std::vector<uint8_t> seed;
};
thread_local Scratch scratch;

}  // namespace

void CoarseSegment(const Cloud& cloud, const Params& p, const Tables& t, Frame& f) {
  const uint32_t n = f.n, cells = CellCount(p);
  f.cell_seed_mode.assign(cells, 0u);
  f.cell_plane.assign(size_t(cells) * 8, 0);
  f.coarse.resize(n);
  Scratch& s = scratch;

  // Seed mode per cell (eq. 5).
  const float lambda_near = p.ring_res_near * p.slope_max + p.seed_margin;
  const float lambda_far = p.ring_res_far * p.slope_max + p.seed_margin;
  const uint32_t near_cells = p.rings_near * p.sectors_near;
  const float base = -p.sensor_height + p.ground_max_above;
  for (uint32_t c = 0; c < cells; ++c) {
    if (f.cell_count[c] == 0) continue;
    const CellGeometry g = Geometry(p, c);
    const float lam = c < near_cells ? lambda_near : lambda_far;
    const float hmin = exact::FromKey(f.cell_zmin[c]), hmax = exact::FromKey(f.cell_zmax[c]);
    const uint32_t nkey = NeighbourMin(p, f, c);
    const float hnmin = nkey == kNone ? hmin : exact::FromKey(nkey);
    const float rise = hmin - hnmin;
    const float prior = base + p.slope_max * t.ring_inner[g.ring];
    if (rise > lam + p.rise_margin || hmin > prior) continue;
    const float spread = hmax - hnmin;
    f.cell_seed_mode[c] = spread <= p.h_athr ? 2u : 1u;
  }

  // Seeds, and every celled point in mm once: sums for the mean, then centred second moments
  // (int64, order-independent).
  s.sum.assign(size_t(cells) * 4, 0);
  s.mom.assign(size_t(cells) * 6, 0);
  s.dist_sum.assign(cells, 0);
  s.fixed.resize(size_t(n) * 3);
  s.seed.resize(n);
  for (uint32_t i = 0; i < n; ++i) {
    s.seed[i] = 0;
    const uint32_t c = f.point_cell[i];
    if (c == kNone) continue;
    int32_t* q = &s.fixed[size_t(i) * 3];
    q[0] = int32_t(exact::ToFixed(cloud.xyzi[4 * i], kMm));
    q[1] = int32_t(exact::ToFixed(cloud.xyzi[4 * i + 1], kMm));
    q[2] = int32_t(exact::ToFixed(f.zt[i], kMm));
    const uint32_t mode = f.cell_seed_mode[c];
    if (mode == 0) continue;
    const float dz = f.zt[i] - exact::FromKey(f.cell_zmin[c]);
    const float lam = c < near_cells ? lambda_near : lambda_far;
    if (mode == 1 && !(dz <= lam)) continue;
    s.seed[i] = 1;
    int64_t* sc = &s.sum[size_t(c) * 4];
    sc[0] += 1, sc[1] += q[0], sc[2] += q[1], sc[3] += q[2];
  }
  for (uint32_t c = 0; c < cells; ++c) {
    const int64_t* sc = &s.sum[size_t(c) * 4];
    int32_t* plane = &f.cell_plane[size_t(c) * 8];
    if (sc[0] == 0) continue;
    plane[3] = int32_t(exact::DivToZero(sc[1], sc[0]));
    plane[4] = int32_t(exact::DivToZero(sc[2], sc[0]));
    plane[5] = int32_t(exact::DivToZero(sc[3], sc[0]));
    plane[7] = int32_t(sc[0]);
  }
  for (uint32_t i = 0; i < n; ++i) {
    if (!s.seed[i]) continue;
    const uint32_t c = f.point_cell[i];
    const int32_t* plane = &f.cell_plane[size_t(c) * 8];
    const int32_t* q = &s.fixed[size_t(i) * 3];
    const int64_t dx = q[0] - plane[3], dy = q[1] - plane[4], dz = q[2] - plane[5];
    int64_t* m = &s.mom[size_t(c) * 6];
    m[0] += dx * dx, m[1] += dx * dy, m[2] += dx * dz, m[3] += dy * dy, m[4] += dy * dz,
        m[5] += dz * dz;
  }

  // Normal per cell (eq. 6-7).
  const int64_t min_z2 = exact::ToFixed(p.normal_min_z2, float(kQ * kQ));
  for (uint32_t c = 0; c < cells; ++c) {
    int32_t* plane = &f.cell_plane[size_t(c) * 8];
    if (plane[7] == 0) continue;
    int64_t nq[3] = {0, 0, kQ};
    if (plane[7] < kMinPlaneSeeds || !PlaneNormal(&s.mom[size_t(c) * 6], nq))
      nq[0] = 0, nq[1] = 0, nq[2] = kQ;
    plane[0] = int32_t(nq[0]), plane[1] = int32_t(nq[1]), plane[2] = int32_t(nq[2]);
  }

  // Threshold: mean |distance| of the seeds.
  auto distance = [&](uint32_t i, const int32_t* plane) {
    const int32_t* q = &s.fixed[size_t(i) * 3];
    const int64_t dx = q[0] - plane[3], dy = q[1] - plane[4], dz = q[2] - plane[5];
    const int64_t d = plane[0] * dx + plane[1] * dy + plane[2] * dz;
    return d < 0 ? -d : d;
  };
  for (uint32_t i = 0; i < n; ++i) {
    if (!s.seed[i]) continue;
    const uint32_t c = f.point_cell[i];
    s.dist_sum[c] += distance(i, &f.cell_plane[size_t(c) * 8]);
  }
  const int64_t floor_q = exact::ToFixed(p.plane_dist_floor, kDistUnit);
  const int64_t scale_q = exact::ToFixed(p.plane_dist_scale, 256.0f);
  for (uint32_t c = 0; c < cells; ++c) {
    int32_t* plane = &f.cell_plane[size_t(c) * 8];
    if (plane[7] == 0) continue;
    if (int64_t(plane[2]) * plane[2] < min_z2) {
      plane[6] = -1;
      continue;
    }
    const int64_t mean_scaled =
        exact::DivToZero(scale_q * s.dist_sum[c], 256 * int64_t(plane[7]));
    plane[6] = int32_t(std::min<int64_t>(std::max(floor_q, mean_scaled), 0x7FFFFFFF));
  }

  // Coarse label per point.
  for (uint32_t i = 0; i < n; ++i) {
    const uint32_t c = f.point_cell[i];
    uint32_t ground = 0;
    if (c != kNone) {
      const int32_t* plane = &f.cell_plane[size_t(c) * 8];
      ground = plane[7] != 0 && plane[6] >= 0 && distance(i, plane) <= plane[6];
    }
    f.coarse[i] = ground;
  }
}

}  // namespace lpir
