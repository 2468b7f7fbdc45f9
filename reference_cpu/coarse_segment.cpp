// coarse_segment (paper eqs. 5-7): seeds by the adaptive height threshold, one plane per
// cell from its seeds, ground = within the cell's point-to-plane threshold.
// In: cloud xy, zt, flags, point_cell, cell_zmin/zmax/count; tables.ring_inner.
// Out: cell_seed_mode, cell_plane (8 ints per cell), coarse (per point).
//
// Seeds (eq. 5, read as docs/spec.md, Readings of the paper says): lambda = cell radial size *
// slope_max + seed_margin; h_nmin = lowest z_t of the non-empty 3x3 neighbour cells (own h_min when
// none).
//   mode 0 (no seeds): empty; or h_min - h_nmin > lambda + rise_margin (the cell's lowest point
//     sits above what neighbour and slope allow: a car roof, a wall filling the cell); or h_min >
//     -sensor_height + ground_max_above + slope_max * inner radius (far above any ground the
//     slope limit can reach from under the sensor).
//     With rise_carry 1, also none when h_min - h_in > lambda + rise_margin, h_in the lowest
//     carried ground of the nearer ring's three cells under this one (NeighbourMin's sectors; the
//     prior's base for ring 0). A cell's carried ground: min(h_min, h_in + slope_max * radial size)
//     when it has seeds and h_min lies no more than lambda + rise_margin under h_nmin (not a point
//     under the road: reflection noise), else h_in + slope_max * radial size: the ground's highest
//     reach from the sensor along the sector, so a wall's feet cannot vouch for each other (float
//     ops via Ftz0).
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
// The float results compared with a threshold (lambda, base, prior, rise, spread, the seed test's
// z_t - h) go through exact::Ftz0, so that a device that flushes subnormals agrees.
// CPU layout (same integers, fewer passes): coordinates go to mm four at a time in int32
// (exact::ToFixed32; the contract's int64 path when one exceeds 2^30 mm); the centred moments come
// from raw sums modulo 2^64 (s_ab - m_a s_b - m_b s_a + n m_a m_b is the same integer); sums kept
// over runs of one cell. Threads (reference_cpu/threads.h): pieces of points, each summing into its
// own slots and cells, merged by integer addition; pieces of slots fit the planes.
#include <algorithm>
#include <cstdlib>
#include <limits>
#include <vector>

#include "reference_cpu/exact.h"
#include "reference_cpu/stages.h"

namespace lpir {
namespace {

constexpr float kMm = 1000.0f;            // metres -> mm
constexpr int64_t kQ = 16384;             // Q14 unit normal
constexpr float kDistUnit = 16384000.0f;  // metres -> mm * 2^14
// Seeds whose second eigenvalue is below this fraction of the first (width below ~3 % of their
// length) lie on a line and get the horizontal plane instead.
constexpr float kMinPlanarity = 1e-3f;
// Fewer seeds than this get the horizontal plane through their mean: a plane fitted to a handful
// of points tilts freely (docs/decisions/coarse_segment.md).
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
  return ring < p.rings_near
             ? ring * p.sectors_near + sector
             : p.rings_near * p.sectors_near + (ring - p.rings_near) * p.sectors_far + sector;
}

// The cell of ring `ring` ds sectors (-1, 0 or 1, wrapping) from the one under g's centre: zones
// differ in sector count.
uint32_t CellUnder(const Params& p, const CellGeometry& g, uint32_t ring, int ds) {
  const uint32_t sectors = ring < p.rings_near ? p.sectors_near : p.sectors_far;
  const uint32_t centre = uint32_t(uint64_t(g.sector) * sectors / g.sectors);
  return CellIndex(p, ring, uint32_t((int64_t(centre) + ds + sectors) % sectors));
}

// Lowest h_min key among the non-empty cells of the 3x3 neighbourhood (excluding the cell).
uint32_t NeighbourMin(const Params& p, const Frame& f, uint32_t cell) {
  const CellGeometry g = Geometry(p, cell);
  const uint32_t rings = p.rings_near + p.rings_far;
  uint32_t best = kNone;
  for (int dr = -1; dr <= 1; ++dr) {
    const int64_t ring = int64_t(g.ring) + dr;
    if (ring < 0 || ring >= int64_t(rings)) continue;
    for (int ds = -1; ds <= 1; ++ds) {
      const uint32_t other = CellUnder(p, g, uint32_t(ring), ds);
      if (other == cell || f.cell_count[other] == 0) continue;
      best = std::min(best, f.cell_zmin[other]);
    }
  }
  return best;
}

// exact::Isqrt (floor(sqrt(v)), bit by bit) with conditional moves for its data-dependent branch.
uint64_t Isqrt(uint64_t v) {
  uint64_t result = 0;
  uint64_t bit = uint64_t(1) << 62;
  while (bit > v) bit >>= 2;
  while (bit != 0) {
    const uint64_t trial = result + bit;
    const bool take = v >= trial;
    v = take ? v - trial : v;
    result = take ? (result >> 1) + bit : result >> 1;
    bit >>= 2;
  }
  return result;
}

// Sets n to the Q14 unit normal of the seeds' plane from centred int64 second moments
// (xx, xy, xz, yy, yz, zz); false when degenerate.
bool PlaneNormal(const int64_t m[6], int64_t n[3]) {
  int64_t maxabs = 0;
  for (int k = 0; k < 6; ++k) maxabs = std::max<int64_t>(maxabs, m[k] < 0 ? -m[k] : m[k]);
  int shift = 0;
  while ((maxabs >> shift) >= (int64_t(1) << 24)) ++shift;
  float c[6];
  // exact::DivToZero(m[k], 2^shift), as a shift of the magnitude.
  for (int k = 0; k < 6; ++k) {
    const uint64_t mag = (m[k] < 0 ? uint64_t(0) - uint64_t(m[k]) : uint64_t(m[k])) >> shift;
    c[k] = float(m[k] < 0 ? -int64_t(mag) : int64_t(mag));
  }
  const float c00 = c[0], c01 = c[1], c02 = c[2], c11 = c[3], c12 = c[4], c22 = c[5];
  // Adjugate (symmetric): a_ij, each two products and one difference.
  float t0, t1;
  t0 = c11 * c22;
  t1 = c12 * c12;
  const float a00 = t0 - t1;
  t0 = c02 * c12;
  t1 = c01 * c22;
  const float a01 = t0 - t1;
  t0 = c01 * c12;
  t1 = c02 * c11;
  const float a02 = t0 - t1;
  t0 = c00 * c22;
  t1 = c02 * c02;
  const float a11 = t0 - t1;
  t0 = c01 * c02;
  t1 = c00 * c12;
  const float a12 = t0 - t1;
  t0 = c00 * c11;
  t1 = c01 * c01;
  const float a22 = t0 - t1;
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
  const int64_t len = int64_t(Isqrt(len2));
  if (len == 0) return false;
  for (int k = 0; k < 3; ++k) n[k] = exact::DivToZero(q[k] * kQ, len);
  return true;
}

// Per cell, what a point needs to decide whether it is a seed, as one test: seed iff
// z_t - h <= lambda. Mode 1: h = h_min and the cell's lambda; mode 2 (every point): h = +inf, so
// z_t - h = -inf <= 0; mode 0 (none): h = -inf, so z_t - h = +inf > 0 (z_t is finite: prepare
// keeps only finite points, and its conversion to mm needs it anyway). `slot` is the compact
// index of the cell's seed sums and plane; 0 for mode 0 cells (no seeds, no plane).
struct SeedTest {
  float h;
  float lambda;
  uint32_t slot;
};

// Seed sums of a slot: count, coordinates, and the raw second moments. The sums of products are
// kept modulo 2^64 (uint64): the centred moments derived from them are then exactly the int64
// sums of products of (q - mean), whatever the intermediate magnitudes.
struct SeedSums {
  int64_t n, x, y, z;
  uint64_t xx, xy, xz, yy, yz, zz;
};

// The plane of a slot as the per-point passes read it: distance = |n . q - offset|. All zero
// (distance 0, never compared) for a cell that cannot hold ground.
struct Fit {
  int64_t nx, ny, nz, offset;
};

// Buffers reused from frame to frame (each thread has its own). Per-cell tables are indexed by
// cell + 1 (uint32): a point without a cell (kNone) wraps to entry 0, which says "no seed, no
// ground".
struct Scratch {
  std::vector<SeedTest> test;       // per cell + 1
  std::vector<float> carried;       // per cell: the carried ground (rise_carry only)
  std::vector<int64_t> thr;         // per cell + 1: the threshold, -1 when no ground
  std::vector<uint32_t> cell_of;    // per slot
  std::vector<SeedSums> sums;       // per slot
  std::vector<Fit> fit;             // per cell + 1
  std::vector<int64_t> dist_sum;    // per cell + 1
  std::vector<int32_t> qx, qy, qz;  // per point with a cell: x, y, z_t in mm (else 0)
  std::vector<uint8_t> ground;      // per slot: 1 when the cell may hold ground
  std::vector<uint8_t> seed;        // per point: 1 for a seed
  std::vector<int64_t> dist;        // per point: |n . (q - mean)|, 0 in cells without ground
  // The sums of the pieces of points after the first (which sums into sums and dist_sum): per
  // piece a slot's SeedSums and a cell + 1's distance sum.
  std::vector<SeedSums> piece_sums;
  std::vector<int64_t> piece_dist_sums;
};
thread_local Scratch scratch;

// m = sum (a - ma)(b - mb) from the raw sums: sab - ma sb - mb sa + n ma mb, modulo 2^64.
int64_t Centred(uint64_t sab, int64_t sa, int64_t sb, int64_t ma, int64_t mb, int64_t n) {
  const uint64_t r = sab - uint64_t(ma) * uint64_t(sb) - uint64_t(mb) * uint64_t(sa) +
                     uint64_t(n) * uint64_t(ma) * uint64_t(mb);
  return int64_t(r);
}

// v with its bits cleared where keep is 0 (a select the vectoriser can use).
inline float Keep(float v, uint32_t keep) { return exact::FromBits(exact::Bits(v) & keep); }

// The passes of CoarseSegment, in the contract's order. The scalar ones are kept out of line
// (noinline), so that each loop has the registers to itself; the vector ones (ToMillimetres,
// SumDistances, Label) are inlined into their pieces' AVX2 build (reference_cpu/threads.h).

// The lowest carried ground of the nearer ring's three cells under cell g (NeighbourMin's sectors);
// `base` for ring 0.
float InnerCarried(const Params& p, const CellGeometry& g, const std::vector<float>& carried,
                   float base) {
  if (g.ring == 0) return base;
  float h = std::numeric_limits<float>::infinity();
  for (int ds = -1; ds <= 1; ++ds) h = std::min(h, carried[CellUnder(p, g, g.ring - 1, ds)]);
  return h;
}

// Seed mode per cell (eq. 5), in cell order (ring by ring, so the nearer ring's carried ground is
// known); cells that may have seeds get the next slot (slot 0: none). Writes cell_seed_mode,
// s.test, s.cell_of and, with rise_carry, s.carried.
[[gnu::noinline]] void SeedModes(const Params& p, const Tables& t, Frame& f, Scratch& s) {
  constexpr float kInf = std::numeric_limits<float>::infinity();
  const uint32_t cells = CellCount(p);
  const float lambda_near = exact::Ftz0(exact::Ftz0(p.ring_res_near * p.slope_max) + p.seed_margin);
  const float lambda_far = exact::Ftz0(exact::Ftz0(p.ring_res_far * p.slope_max) + p.seed_margin);
  const uint32_t near_cells = p.rings_near * p.sectors_near;
  const float base = exact::Ftz0(-p.sensor_height + p.ground_max_above);
  const float reach_near = exact::Ftz0(p.ring_res_near * p.slope_max);
  const float reach_far = exact::Ftz0(p.ring_res_far * p.slope_max);
  s.test.assign(size_t(cells) + 1, SeedTest{-kInf, 0.0f, 0u});
  s.cell_of.assign(1, kNone);
  if (p.rise_carry) s.carried.assign(cells, 0.0f);
  for (uint32_t c = 0; c < cells; ++c) {
    const CellGeometry g = Geometry(p, c);
    float carried = 0.0f;  // this cell's carried ground without seeds (rise_carry)
    float inner = 0.0f;
    if (p.rise_carry) {
      inner = InnerCarried(p, g, s.carried, base);
      carried = exact::Ftz0(inner + (c < near_cells ? reach_near : reach_far));
      s.carried[c] = carried;
    }
    if (f.cell_count[c] == 0) continue;
    const float lam = c < near_cells ? lambda_near : lambda_far;
    const float hmin = exact::FromKey(f.cell_zmin[c]), hmax = exact::FromKey(f.cell_zmax[c]);
    const uint32_t nkey = NeighbourMin(p, f, c);
    const float hnmin = nkey == kNone ? hmin : exact::FromKey(nkey);
    const float rise = exact::Ftz0(hmin - hnmin);
    const float prior = exact::Ftz0(base + exact::Ftz0(p.slope_max * t.ring_inner[g.ring]));
    const float rise_lim = exact::Ftz0(lam + p.rise_margin);
    if (rise > rise_lim || hmin > prior) continue;
    if (p.rise_carry && exact::Ftz0(hmin - inner) > rise_lim) continue;
    if (p.rise_carry && !(exact::Ftz0(hnmin - hmin) > rise_lim))
      s.carried[c] = std::min(hmin, carried);
    const float spread = exact::Ftz0(hmax - hnmin);
    const uint32_t mode = spread <= p.h_athr ? 2u : 1u;
    f.cell_seed_mode[c] = mode;
    const uint32_t slot = uint32_t(s.cell_of.size());
    s.test[size_t(c) + 1] = mode == 2 ? SeedTest{kInf, 0.0f, slot} : SeedTest{hmin, lam, slot};
    s.cell_of.push_back(c);
  }
}

// Every point of `points` with a cell in mm (0 without one): x, y and z_t into s.qx, s.qy, s.qz,
// SSE-wide; the scalar path of the contract if any coordinate lies beyond 2^30 mm.
void ToMillimetres(const Cloud& cloud, const Frame& f, Scratch& s, Range points) {
  const float* __restrict xyzi = cloud.xyzi.data();
  const float* __restrict zt = f.zt.data();
  const uint32_t* __restrict point_cell = f.point_cell.data();
  int32_t* __restrict qx = s.qx.data();
  int32_t* __restrict qy = s.qy.data();
  int32_t* __restrict qz = s.qz.data();
  uint32_t bad = 0;
  for (uint32_t i = points.begin; i < points.end; ++i) {
    const uint32_t keep = 0u - uint32_t(point_cell[i] != kNone);
    qx[i] = exact::ToFixed32(Keep(xyzi[4 * size_t(i)], keep), kMm, bad);
    qy[i] = exact::ToFixed32(Keep(xyzi[4 * size_t(i) + 1], keep), kMm, bad);
    qz[i] = exact::ToFixed32(Keep(zt[i], keep), kMm, bad);
  }
  for (uint32_t i = points.begin; bad && i < points.end; ++i) {
    if (point_cell[i] == kNone) continue;
    qx[i] = int32_t(exact::ToFixed(xyzi[4 * size_t(i)], kMm));
    qy[i] = int32_t(exact::ToFixed(xyzi[4 * size_t(i) + 1], kMm));
    qz[i] = int32_t(exact::ToFixed(zt[i], kMm));
  }
}

// The end of the run of points of one cell that starts at i (scan order keeps a cell's points
// together, about ten on a KITTI ring): the first point after i in another cell, or end.
inline uint32_t RunEnd(const uint32_t* __restrict point_cell, uint32_t i, uint32_t end) {
  const uint32_t c = point_cell[i];
  uint32_t j = i + 1;
  while (j < end && point_cell[j] == c) ++j;
  return j;
}

// The seed test of every point of `points` (s.seed), and the seeds' sums per slot into `sums`
// (int64, order-independent), one run of one cell at a time: the cell's test and the run's sums
// stay in registers, and go to the cell's sums when the run ends. A run without a slot (mode 0, or
// no cell) has no seeds; in a mode 2 run every point is one (its test says so for any finite z_t).
[[gnu::noinline]] void SumSeeds(const Frame& f, Scratch& s, Range points,
                                SeedSums* __restrict sums) {
  const float* __restrict zt = f.zt.data();
  const uint32_t* __restrict point_cell = f.point_cell.data();
  const int32_t* __restrict qx = s.qx.data();
  const int32_t* __restrict qy = s.qy.data();
  const int32_t* __restrict qz = s.qz.data();
  const SeedTest* __restrict test = s.test.data();
  uint8_t* __restrict seed = s.seed.data();
  for (uint32_t i = points.begin; i < points.end;) {
    const uint32_t end = RunEnd(point_cell, i, points.end);
    const SeedTest st = test[point_cell[i] + 1u];
    if (st.slot == 0) {
      std::fill(seed + i, seed + end, uint8_t(0));
      i = end;
      continue;
    }
    const bool all = st.h == std::numeric_limits<float>::infinity();
    int64_t rn = 0, rx = 0, ry = 0, rz = 0;
    uint64_t rxx = 0, rxy = 0, rxz = 0, ryy = 0, ryz = 0, rzz = 0;
    for (; i < end; ++i) {
      const bool is_seed = all || exact::Ftz0(zt[i] - st.h) <= st.lambda;
      seed[i] = is_seed;
      if (!is_seed) continue;
      const int64_t x = qx[i], y = qy[i], z = qz[i];
      rn += 1, rx += x, ry += y, rz += z;
      rxx += uint64_t(x * x), rxy += uint64_t(x * y), rxz += uint64_t(x * z);
      ryy += uint64_t(y * y), ryz += uint64_t(y * z), rzz += uint64_t(z * z);
    }
    SeedSums& a = sums[st.slot];
    a.n += rn, a.x += rx, a.y += ry, a.z += rz;
    a.xx += rxx, a.xy += rxy, a.xz += rxz, a.yy += ryy, a.yz += ryz, a.zz += rzz;
  }
}

// b's sums added to a's (int64 and modulo 2^64: the same in any order).
inline void AddSums(SeedSums& a, const SeedSums& b) {
  a.n += b.n, a.x += b.x, a.y += b.y, a.z += b.z;
  a.xx += b.xx, a.xy += b.xy, a.xz += b.xz, a.yy += b.yy, a.yz += b.yz, a.zz += b.zz;
}

// Mean, centred moments and normal per slot of `slots` with seeds (eqs. 6-7) into cell_plane (all
// but the threshold); the slots whose normal is flat enough get their s.fit and s.ground, the
// others threshold -1 (no ground). Slot 0 (no cell) is passed over.
[[gnu::noinline]] void FitPlanes(const Params& p, Frame& f, Scratch& s, Range slots) {
  const int64_t min_z2 = exact::ToFixed(p.normal_min_z2, float(kQ * kQ));
  for (uint32_t k = std::max(slots.begin, 1u); k < slots.end; ++k) {
    const SeedSums& a = s.sums[k];
    if (a.n == 0) continue;
    int32_t* plane = &f.cell_plane[size_t(s.cell_of[k]) * 8];
    const int64_t mx = exact::DivToZero(a.x, a.n), my = exact::DivToZero(a.y, a.n),
                  mz = exact::DivToZero(a.z, a.n);
    plane[3] = int32_t(mx), plane[4] = int32_t(my), plane[5] = int32_t(mz);
    plane[7] = int32_t(a.n);
    const int64_t mom[6] = {
        Centred(a.xx, a.x, a.x, mx, mx, a.n), Centred(a.xy, a.x, a.y, mx, my, a.n),
        Centred(a.xz, a.x, a.z, mx, mz, a.n), Centred(a.yy, a.y, a.y, my, my, a.n),
        Centred(a.yz, a.y, a.z, my, mz, a.n), Centred(a.zz, a.z, a.z, mz, mz, a.n)};
    int64_t nq[3] = {0, 0, kQ};
    if (plane[7] < kMinPlaneSeeds || !PlaneNormal(mom, nq)) nq[0] = 0, nq[1] = 0, nq[2] = kQ;
    plane[0] = int32_t(nq[0]), plane[1] = int32_t(nq[1]), plane[2] = int32_t(nq[2]);
    // A normal steeper than allowed: no ground in the cell.
    if (int64_t(plane[2]) * plane[2] < min_z2) {
      plane[6] = -1;
      continue;
    }
    // n . (q - mean) = n . q - n . mean exactly (int64, far from overflow).
    s.fit[size_t(s.cell_of[k]) + 1] = Fit{
        plane[0], plane[1], plane[2],
        plane[0] * int64_t(plane[3]) + plane[1] * int64_t(plane[4]) + plane[2] * int64_t(plane[5])};
    s.ground[k] = 1;
  }
}

// Distance in mm * 2^14 of every point of `points` to its cell's plane (s.dist; 0 in cells without
// ground), and the seeds' sum per cell + 1 into `dist_sum`, again kept in a register over a run of
// one cell.
void SumDistances(const Frame& f, Scratch& s, Range points, int64_t* __restrict dist_sum) {
  const int32_t* __restrict qx = s.qx.data();
  const int32_t* __restrict qy = s.qy.data();
  const int32_t* __restrict qz = s.qz.data();
  const uint32_t* __restrict point_cell = f.point_cell.data();
  const uint8_t* __restrict seed = s.seed.data();
  const Fit* __restrict fit = s.fit.data();
  int64_t* __restrict dist = s.dist.data();
  uint32_t run_cell = kNone;
  Fit g = fit[0];
  int64_t run_sum = 0;
  for (uint32_t i = points.begin; i < points.end; ++i) {
    const uint32_t c = point_cell[i];
    if (c != run_cell) {
      dist_sum[run_cell + 1u] += run_sum;
      run_sum = 0;
      run_cell = c;
      g = fit[c + 1u];
    }
    int64_t d = g.nx * qx[i] + g.ny * qy[i] + g.nz * qz[i] - g.offset;
    d = d < 0 ? -d : d;
    dist[i] = d;
    run_sum += d & -int64_t(seed[i]);
  }
  dist_sum[run_cell + 1u] += run_sum;
}

// Threshold per slot with ground: max(plane_dist_floor, plane_dist_scale * mean seed |distance|)
// into cell_plane and s.thr (-1 for every other cell).
[[gnu::noinline]] void Thresholds(const Params& p, Frame& f, Scratch& s) {
  const uint32_t slots = uint32_t(s.cell_of.size());
  const int64_t floor_q = exact::ToFixed(p.plane_dist_floor, kDistUnit);
  const int64_t scale_q = exact::ToFixed(p.plane_dist_scale, 256.0f);
  s.thr.assign(size_t(CellCount(p)) + 1, -1);
  for (uint32_t k = 1; k < slots; ++k) {
    if (!s.ground[k]) continue;
    int32_t* plane = &f.cell_plane[size_t(s.cell_of[k]) * 8];
    const int64_t mean_scaled =
        exact::DivToZero(scale_q * s.dist_sum[size_t(s.cell_of[k]) + 1], 256 * int64_t(plane[7]));
    plane[6] = int32_t(std::min<int64_t>(std::max(floor_q, mean_scaled), 0x7FFFFFFF));
    s.thr[size_t(s.cell_of[k]) + 1] = plane[6];
  }
}

// Coarse label per point of `points`: distances are >= 0, so a threshold of -1 (no seeds, no
// ground) or any negative one says 0.
void Label(Frame& f, const Scratch& s, Range points) {
  const uint32_t* __restrict point_cell = f.point_cell.data();
  const int64_t* __restrict dist = s.dist.data();
  const int64_t* __restrict thr = s.thr.data();
  uint32_t* __restrict coarse = f.coarse.data();
  for (uint32_t i = points.begin; i < points.end; ++i)
    coarse[i] = dist[i] <= thr[point_cell[i] + 1u];
}

}  // namespace

// Pieces of points for the per-point passes, each summing into its own slots and cells (the first
// into s.sums and s.dist_sum), merged by integer addition (the same in any order); pieces of slots
// for the planes.
void CoarseSegment(const Cloud& cloud, const Params& p, const Tables& t, Frame& f,
                   Threads threads) {
  const uint32_t n = f.n, cells = CellCount(p);
  f.cell_seed_mode.assign(cells, 0u);
  f.cell_plane.assign(size_t(cells) * 8, 0);
  f.coarse.resize(n);
  Scratch& s = scratch;
  SeedModes(p, t, f, s);
  const uint32_t slots = uint32_t(s.cell_of.size());
  s.qx.resize(n), s.qy.resize(n), s.qz.resize(n);
  s.seed.resize(n);
  s.dist.resize(n);
  s.sums.assign(slots, SeedSums{});
  s.dist_sum.assign(size_t(cells) + 1, 0);
  const uint32_t pieces = PiecesFor(threads, n, 4096);
  s.piece_sums.resize(size_t(pieces - 1) * slots);
  s.piece_dist_sums.resize(size_t(pieces - 1) * (cells + 1));
  auto piece_sums = [&](uint32_t k) {
    return k ? s.piece_sums.data() + size_t(k - 1) * slots : s.sums.data();
  };
  auto piece_dist_sums = [&](uint32_t k) {
    return k ? s.piece_dist_sums.data() + size_t(k - 1) * (cells + 1) : s.dist_sum.data();
  };
  ForPieces(threads, pieces, n, [&](uint32_t k, Range points) {
    ToMillimetres(cloud, f, s, points);
    SeedSums* sums = piece_sums(k);
    if (k) std::fill(sums, sums + slots, SeedSums{});
    SumSeeds(f, s, points, sums);
  });
  for (uint32_t k = 1; k < pieces; ++k)
    for (uint32_t slot = 0; slot < slots; ++slot) AddSums(s.sums[slot], piece_sums(k)[slot]);
  s.fit.assign(size_t(cells) + 1, Fit{0, 0, 0, 0});
  s.ground.assign(slots, 0);
  ForPieces(threads, PiecesFor(threads, slots, 64), slots,
            [&](uint32_t, Range r) { FitPlanes(p, f, s, r); });
  ForPieces(threads, pieces, n, [&](uint32_t k, Range points) {
    int64_t* dist_sum = piece_dist_sums(k);
    if (k) std::fill(dist_sum, dist_sum + cells + 1, 0);
    SumDistances(f, s, points, dist_sum);
  });
  for (uint32_t k = 1; k < pieces; ++k)
    for (uint32_t c = 0; c <= cells; ++c) s.dist_sum[c] += piece_dist_sums(k)[c];
  Thresholds(p, f, s);
  ForPieces(threads, pieces, n, [&](uint32_t, Range points) { Label(f, s, points); });
}

}  // namespace lpir
