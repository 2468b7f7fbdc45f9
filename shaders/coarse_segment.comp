// coarse_segment (paper eqs. 5-7): the GPU twin of reference_cpu/coarse_segment.cpp,
// same bytes (cell_seed_mode, cell_plane, coarse). Six passes of this one shader, chosen by the
// specialization constant kPass (one pipeline each), with a compute -> compute barrier between
// each two (CoarseSegmentStage::Record records them all):
//   pass 0, one invocation per cell: seed mode (eq. 5: lambda, the 3x3 neighbour minimum, the
//     rise and slope-prior rules, the whole-cell rule), cell_seed_mode, cell_plane zeroed, the
//     cell's scratch: sums zeroed and the seed test (h, lambda) as the CPU's SeedTest (mode 2:
//     h = +inf, lambda 0; mode 1: h = h_min and the zone's lambda; mode 0: no seeds). lambda,
//     base, prior, rise and spread, each result through exact_Ftz0 as in the reference (a device
//     may flush a subnormal one), as is pass 1's z_t - h. With rise_carry the rise rule also
//     reads the nearer ring's carried ground, so the rings go in order: the first workgroup
//     alone runs ring after ring, a barrier between two, each cell's carried ground in its
//     scratch word kCarried (the distance sum's high word, zeroed again at the end); the other
//     workgroups return.
//   pass 1, one invocation per kItems consecutive points: seed iff z_t - h <= lambda (one rounded
//     float op, the CPU's test; mode 2 decided on z_t's bits with the same outcome, no infinity
//     arithmetic); a seed adds n, x, y, z and the six products to its cell's sums. The chunk's
//     seeds are summed in registers while their cell stays the same (scans come ring by ring,
//     so consecutive points mostly share a cell) and each run is added with one set of atomics.
//   pass 2, one invocation per cell: mean (DivToZero), centred moments, PlaneNormal, the plane
//     (cell_plane[0..5, 7]), cell_plane[6] = -1 when the normal is too steep.
//   pass 3, one invocation per kItems consecutive points: |n . q - n . mean| of the seeds of
//     ground cells, summed per cell (runs of one cell summed in registers first, as in pass 1).
//   pass 4, one invocation per cell: threshold max(floor, scale * mean seed distance) into
//     cell_plane[6] of the ground cells.
//   pass 5, one invocation per kItems consecutive points: coarse = the point's cell is a ground
//     cell and its |distance| <= threshold (the cell's plane read once per run of one cell).
//   kItems is the device's shape (specialization constant 2: host/vk/shape.h). A chunk starts
//   with no run and no cell read, so every point's test, sums and label are the same for every
//   kItems (with kItems = 1 each point reads its cell and adds its own sums), and the sums are
//   order-independent integers (below).
// In: binding 0 Params (uniform), 1 xyzi (4 floats per point), 2 zt, 3 point_cell (per point),
//     4 cell_zmin, 5 cell_zmax (ordered keys), 6 cell_count (per cell), 7 ring_inner (per ring).
// Out: 8 cell_seed_mode, 9 cell_plane (8 ints per cell), 10 coarse (per point).
// Scratch: 11 coarse_scratch, kScratch uints per cell (written by pass 0 before any read).
//
// Exactness. Coordinates: int(exact_ToFixed(v, 1000)) (the CPU's int32 of ToFixed). Sums: every
// per-cell sum is an integer modulo 2^64 (the CPU keeps the products' sums in uint64, the others
// in int64 far from overflow), so addition order cannot matter. Without 64-bit atomics each sum is
// two uint words (lo, hi): atomicAdd of the low 32 bits returns the old low word, the carry out of
// that addition is (old + lo < old), and hi + carry goes to the high word by a second atomicAdd.
// Every carry is counted exactly once, so (hi, lo) is the sum modulo 2^64 whatever the order.
// Centred moments from the raw sums as the CPU computes them (s_ab - m_a s_b - m_b s_a +
// n m_a m_b modulo 2^64), which is the exact int64 sum of (a - m_a)(b - m_b). The normal: the
// CPU's PlaneNormal op for op, every float `precise` (no contraction), int64 -> float only for
// magnitudes below 2^24 (exact), power-of-two rescaling by exponent bits, exact_Isqrt.
// Nothing here divides floats or takes a float square root.
#version 450
#extension GL_GOOGLE_include_directive : require

#include "common/params.h"
#include "common/frame_codes.h"
#include "common/exact.glsl"

layout(local_size_x_id = 0) in;

layout(std140, set = 0, binding = 0) uniform ParamsBlock { Params p; };
layout(std430, set = 0, binding = 1) readonly buffer Xyzi { vec4 xyzi[]; };
layout(std430, set = 0, binding = 2) readonly buffer Zt { float zt[]; };
layout(std430, set = 0, binding = 3) readonly buffer PointCell { uint point_cell[]; };
layout(std430, set = 0, binding = 4) readonly buffer CellZmin { uint cell_zmin[]; };
layout(std430, set = 0, binding = 5) readonly buffer CellZmax { uint cell_zmax[]; };
layout(std430, set = 0, binding = 6) readonly buffer CellCount { uint cell_count[]; };
layout(std430, set = 0, binding = 7) readonly buffer RingInner { float ring_inner[]; };
layout(std430, set = 0, binding = 8) buffer CellSeedMode { uint cell_seed_mode[]; };
layout(std430, set = 0, binding = 9) buffer CellPlane { int cell_plane[]; };
layout(std430, set = 0, binding = 10) writeonly buffer Coarse { uint coarse[]; };
layout(std430, set = 0, binding = 11) buffer CoarseScratch { uint coarse_scratch[]; };
// Cell c's plane as two vectors, a = cell_plane[8c .. 8c + 3] (normal, mean x) and b =
// cell_plane[8c + 4 .. 8c + 7] (mean y, mean z, threshold, seeds): two loads instead of eight (on a
// CPU driver each buffer access is a loop over the SIMD lanes, and every branch runs).
layout(std430, set = 0, binding = 9) readonly buffer CellPlane4 { ivec4 cell_plane4[]; };
// The seed test (h, lambda): words kTestH, kTestLambda = components z, w of the cell's sixth uvec4.
layout(std430, set = 0, binding = 11) readonly buffer CoarseScratch4 { uvec4 coarse_scratch4[]; };

layout(constant_id = 1) const uint kPass = 0u;  // a pipeline per pass (host/vk/kernel.h)
layout(constant_id = 2) const uint kItems = 1u;  // points per invocation, passes 1, 3, 5 (shape)

layout(push_constant) uniform Push {
  uint count;  // cells (passes 0, 2, 4) or points (passes 1, 3, 5)
} pc;

const int64_t kQ = int64_t(16384);  // Q14 unit normal
const int kMinPlaneSeeds = 16;
const float kMm = 1000.0;
const float kMinPlanarity = 1e-3;

// Scratch layout per cell (uints): 10 sums of two words (lo, hi): n, x, y, z, xx, xy, xz, yy,
// yz, zz; then the seed distance sum (two words); then the seed test h and lambda (float bits).
const uint kScratch = 24u;
const uint kSumDist = 10u;
const uint kTestH = 22u;
const uint kTestLambda = 23u;
const uint kCarried = 21u;  // pass 0 with rise_carry only: the carried ground (float bits)
// The same words, coherent: pass 0's invocations read one another's carried ground (pass 0
// accesses word kCarried through this alias only).
layout(std430, set = 0, binding = 11) coherent buffer CoarseScratchC { uint coarse_scratch_c[]; };

uint Base(uint cell) { return cell * kScratch; }

void AtomicAdd64(uint word, uint64_t v) {
  if (v == uint64_t(0)) return;
  uint lo = uint(v), hi = uint(v >> 32);
  uint old = atomicAdd(coarse_scratch[word], lo);
  uint carry = (old + lo < old) ? 1u : 0u;
  hi += carry;
  if (hi != 0u) atomicAdd(coarse_scratch[word + 1u], hi);
}
uint64_t Sum(uint cell, uint k) {
  uint w = Base(cell) + 2u * k;
  return (uint64_t(coarse_scratch[w + 1u]) << 32) | uint64_t(coarse_scratch[w]);
}

// ---- pass 0: seed mode -----------------------------------------------------------------------

uint CellIndex(uint ring, uint sector) {
  return ring < p.rings_near ? ring * p.sectors_near + sector
                             : p.rings_near * p.sectors_near +
                                   (ring - p.rings_near) * p.sectors_far + sector;
}

// The cell of ring `ring` ds sectors (-1, 0 or 1, wrapping) from the one under the centre of
// sector `sector` of `sectors` (the reference's CellUnder): zones differ in sector count.
uint CellUnder(uint sector, uint sectors, uint ring, int ds) {
  uint rs = ring < p.rings_near ? p.sectors_near : p.sectors_far;
  uint centre = uint(uint64_t(sector) * uint64_t(rs) / uint64_t(sectors));
  return CellIndex(ring, uint((int64_t(centre) + int64_t(ds) + int64_t(rs)) % int64_t(rs)));
}

void SeedMode(uint c) {
  for (uint k = 0u; k < 8u; ++k) cell_plane[8u * c + k] = 0;
  for (uint k = 0u; k < kCarried; ++k) coarse_scratch[Base(c) + k] = 0u;  // word 21: below
  float inf = uintBitsToFloat(0x7F800000u);
  uint mode = 0u;
  float h = -inf, lam_out = 0.0;
  uint near_cells = p.rings_near * p.sectors_near;
  uint ring, sector, sectors;
  if (c < near_cells) {
    ring = c / p.sectors_near;
    sector = c % p.sectors_near;
    sectors = p.sectors_near;
  } else {
    uint d = c - near_cells;
    ring = p.rings_near + d / p.sectors_far;
    sector = d % p.sectors_far;
    sectors = p.sectors_far;
  }
  // rise_carry: the lowest carried ground of the nearer ring's three cells under this one
  // (NeighbourMin's sectors; the prior's base for ring 0), and this cell's without seeds.
  precise float reach =
      exact_Ftz0((c < near_cells ? p.ring_res_near : p.ring_res_far) * p.slope_max);
  float inner = 0.0, carried = 0.0;
  if (p.rise_carry != 0u) {
    precise float base0 = exact_Ftz0(-p.sensor_height + p.ground_max_above);
    inner = base0;
    if (ring > 0u) {
      inner = inf;
      for (int ds = -1; ds <= 1; ++ds) {
        uint other = CellUnder(sector, sectors, ring - 1u, ds);
        float o = uintBitsToFloat(coarse_scratch_c[Base(other) + kCarried]);
        inner = o < inner ? o : inner;
      }
    }
    precise float up = exact_Ftz0(inner + reach);
    carried = up;
  }
  if (cell_count[c] != 0u) {
    // NeighbourMin: the lowest h_min key of the non-empty 3x3 neighbours (not the cell itself).
    uint rings = p.rings_near + p.rings_far;
    uint best = kNone;
    for (int dr = -1; dr <= 1; ++dr) {
      int r = int(ring) + dr;
      if (r < 0 || r >= int(rings)) continue;
      for (int ds = -1; ds <= 1; ++ds) {
        uint other = CellUnder(sector, sectors, uint(r), ds);
        if (other == c || cell_count[other] == 0u) continue;
        best = min(best, cell_zmin[other]);
      }
    }
    precise float lam = exact_Ftz0(reach + p.seed_margin);
    float hmin = exact_FromKey(cell_zmin[c]), hmax = exact_FromKey(cell_zmax[c]);
    float hnmin = best == kNone ? hmin : exact_FromKey(best);
    precise float rise = exact_Ftz0(hmin - hnmin);
    precise float base = exact_Ftz0(-p.sensor_height + p.ground_max_above);
    precise float slope_r = exact_Ftz0(p.slope_max * ring_inner[ring]);
    precise float prior = exact_Ftz0(base + slope_r);
    precise float rise_lim = exact_Ftz0(lam + p.rise_margin);
    precise float above = exact_Ftz0(hmin - inner);
    precise float below = exact_Ftz0(hnmin - hmin);
    bool carry_rejects = p.rise_carry != 0u && above > rise_lim;
    if (!(rise > rise_lim || hmin > prior || carry_rejects)) {
      // The cell seeds: its lowest point carries the ground on, unless it lies further under
      // its neighbours' than the rise allows above them (reflection noise under the road).
      if (p.rise_carry != 0u && !(below > rise_lim)) carried = hmin < carried ? hmin : carried;
      precise float spread = exact_Ftz0(hmax - hnmin);
      mode = spread <= p.h_athr ? 2u : 1u;
      if (mode == 2u) {
        h = inf;
        lam_out = 0.0;
      } else {
        h = hmin;
        lam_out = lam;
      }
    }
  }
  // The carried ground; 0 (the distance sum's zero high word) without rise_carry.
  coarse_scratch_c[Base(c) + kCarried] = floatBitsToUint(carried);
  cell_seed_mode[c] = mode;
  coarse_scratch[Base(c) + kTestH] = floatBitsToUint(h);
  coarse_scratch[Base(c) + kTestLambda] = floatBitsToUint(lam_out);
}

// ---- per-point helpers -----------------------------------------------------------------------

// A cell's seed test, as pass 0 left it: the mode and (h, lambda). The point passes read it once
// per run of points in one cell (on a CPU driver every buffer access is a loop over the SIMD
// lanes: loads are most of a pass's cost).
struct SeedTest {
  uint mode;
  float h, lam;
};
SeedTest SeedTestOf(uint c) {
  uvec2 test = coarse_scratch4[(Base(c) + kTestH) / 4u].zw;  // kTestH = 22, kTestLambda = 23
  return SeedTest(cell_seed_mode[c], uintBitsToFloat(test.x), uintBitsToFloat(test.y));
}

// The CPU's seed test for a point with z_t = z of a cell with test t (mode 0: never).
// Mode 2 (CPU: z_t - +inf <= 0) by bits, so nothing depends on the device's infinities: a seed
// unless z_t is +inf or NaN.
bool IsSeed(float z, SeedTest t) {
  uint u = floatBitsToUint(z);
  precise float dz = exact_Ftz0(z - t.h);
  return t.mode == 2u ? u != 0x7F800000u && (u & 0x7FFFFFFFu) <= 0x7F800000u
                      : t.mode != 0u && dz <= t.lam;
}

// Point i's coordinates in mm (z: its z_t).
ivec3 Mm(uint i, float z) {
  vec2 xy = xyzi[i].xy;  // one load, not two
  return ivec3(int(exact_ToFixed(xy.x, kMm)), int(exact_ToFixed(xy.y, kMm)),
               int(exact_ToFixed(z, kMm)));
}

// ---- pass 2: the plane -----------------------------------------------------------------------

int64_t Centred(uint64_t sab, int64_t sa, int64_t sb, int64_t ma, int64_t mb, int64_t n) {
  uint64_t r = sab - uint64_t(ma) * uint64_t(sb) - uint64_t(mb) * uint64_t(sa) +
               uint64_t(n) * uint64_t(ma) * uint64_t(mb);
  return int64_t(r);
}

// reference_cpu PlaneNormal, op for op.
bool PlaneNormal(int64_t m[6], out int64_t n[3]) {
  n[0] = int64_t(0);
  n[1] = int64_t(0);
  n[2] = kQ;
  int64_t maxabs = int64_t(0);
  for (int k = 0; k < 6; ++k) maxabs = max(maxabs, m[k] < int64_t(0) ? -m[k] : m[k]);
  int shift = 0;
  while ((maxabs >> shift) >= (int64_t(1) << 24)) ++shift;
  float c[6];
  for (int k = 0; k < 6; ++k) {
    uint64_t mag =
        (m[k] < int64_t(0) ? uint64_t(0) - uint64_t(m[k]) : uint64_t(m[k])) >> uint64_t(shift);
    c[k] = exact_I64ToFloat(m[k] < int64_t(0) ? -int64_t(mag) : int64_t(mag));
  }
  float c00 = c[0], c01 = c[1], c02 = c[2], c11 = c[3], c12 = c[4], c22 = c[5];
  precise float t0, t1;
  t0 = c11 * c22; t1 = c12 * c12; precise float a00 = t0 - t1;
  t0 = c02 * c12; t1 = c01 * c22; precise float a01 = t0 - t1;
  t0 = c01 * c12; t1 = c02 * c11; precise float a02 = t0 - t1;
  t0 = c00 * c22; t1 = c02 * c02; precise float a11 = t0 - t1;
  t0 = c01 * c02; t1 = c00 * c12; precise float a12 = t0 - t1;
  t0 = c00 * c11; t1 = c01 * c01; precise float a22 = t0 - t1;
  float a[3][3] = float[3][3](float[3](a00, a01, a02), float[3](a01, a11, a12),
                              float[3](a02, a12, a22));
  precise float trace = c00 + c11;
  trace = trace + c22;
  precise float trace2 = trace * trace;
  precise float adj_trace = a00 + a11;
  adj_trace = adj_trace + a22;
  precise float min_adj = trace2 * kMinPlanarity;
  if (!(adj_trace >= min_adj)) return false;
  int col = 0;
  if (a11 > a[col][col]) col = 1;
  if (a22 > a[col][col]) col = 2;
  precise float v[3] = float[3](a[0][col], a[1][col], a[2][col]);
  for (int step = 0; step < 3; ++step) {
    float ax = abs(v[0]), ay = abs(v[1]), az = abs(v[2]);
    float mxy = ax < ay ? ay : ax;  // std::max(a, b): a < b ? b : a
    float mx = mxy < az ? az : mxy;
    if (!(mx > 0.0)) return false;
    float scale = exact_Pow2(-exact_Exponent(mx));
    for (int k = 0; k < 3; ++k) v[k] = v[k] * scale;
    if (step == 2) break;
    precise float w[3];
    for (int r = 0; r < 3; ++r) {
      precise float s = a[r][0] * v[0];
      s = s + a[r][1] * v[1];
      s = s + a[r][2] * v[2];
      w[r] = s;
    }
    v[0] = w[0];
    v[1] = w[1];
    v[2] = w[2];
  }
  if (v[2] < 0.0) {
    v[0] = -v[0];
    v[1] = -v[1];
    v[2] = -v[2];
  }
  int64_t q[3];
  uint64_t len2 = uint64_t(0);
  for (int k = 0; k < 3; ++k) {
    q[k] = exact_ToFixed(v[k], 1048576.0);  // 2^20
    len2 += uint64_t(q[k] * q[k]);
  }
  int64_t len = int64_t(exact_Isqrt(len2));
  if (len == int64_t(0)) return false;
  for (int k = 0; k < 3; ++k) n[k] = exact_DivToZero(q[k] * kQ, len);
  return true;
}

int64_t MinZ2() { return exact_ToFixed(p.normal_min_z2, 268435456.0); }  // kQ * kQ

void FitPlane(uint c) {
  if (cell_seed_mode[c] == 0u) return;
  int64_t n = int64_t(Sum(c, 0u));
  if (n == int64_t(0)) return;
  int64_t sx = int64_t(Sum(c, 1u)), sy = int64_t(Sum(c, 2u)), sz = int64_t(Sum(c, 3u));
  int64_t mx = exact_DivToZero(sx, n), my = exact_DivToZero(sy, n), mz = exact_DivToZero(sz, n);
  int64_t mom[6] = int64_t[6](
      Centred(Sum(c, 4u), sx, sx, mx, mx, n), Centred(Sum(c, 5u), sx, sy, mx, my, n),
      Centred(Sum(c, 6u), sx, sz, mx, mz, n), Centred(Sum(c, 7u), sy, sy, my, my, n),
      Centred(Sum(c, 8u), sy, sz, my, mz, n), Centred(Sum(c, 9u), sz, sz, mz, mz, n));
  int count = int(n);
  int64_t nq[3];
  if (count < kMinPlaneSeeds || !PlaneNormal(mom, nq)) {
    nq[0] = int64_t(0);
    nq[1] = int64_t(0);
    nq[2] = kQ;
  }
  uint b = 8u * c;
  cell_plane[b + 0u] = int(nq[0]);
  cell_plane[b + 1u] = int(nq[1]);
  cell_plane[b + 2u] = int(nq[2]);
  cell_plane[b + 3u] = int(mx);
  cell_plane[b + 4u] = int(my);
  cell_plane[b + 5u] = int(mz);
  cell_plane[b + 7u] = count;
  int64_t z = int64_t(int(nq[2]));
  if (z * z < MinZ2()) cell_plane[b + 6u] = -1;
}

// A cell whose plane may hold ground (after pass 2): seeds, and a normal not too steep; on the
// plane vectors a, b of a cell with seeds.
bool GroundPlane(ivec4 a, ivec4 b) {
  int64_t z = int64_t(a.z);
  return b.w != 0 && z * z >= MinZ2();
}

bool Ground(uint c) {
  return cell_seed_mode[c] != 0u && GroundPlane(cell_plane4[2u * c], cell_plane4[2u * c + 1u]);
}

// |n . q - n . mean| in mm * 2^14 (int64) of point i (z_t = z) to the plane a, b.
int64_t Distance(uint i, float z, ivec4 a, ivec4 b) {
  int64_t nx = int64_t(a.x), ny = int64_t(a.y), nz = int64_t(a.z);
  int64_t offset = nx * int64_t(a.w) + ny * int64_t(b.x) + nz * int64_t(b.y);
  ivec3 q = Mm(i, z);
  int64_t d = nx * int64_t(q.x) + ny * int64_t(q.y) + nz * int64_t(q.z) - offset;
  return d < int64_t(0) ? -d : d;
}

// ---- passes 1 and 3: per-cell sums over a chunk of points ----------------------------------

// Adds one run's sums (s[0] = seeds, then x, y, z, xx, xy, xz, yy, yz, zz) to cell c.
void FlushSeedSums(uint c, uint64_t s[10]) {
  uint b = Base(c);
  atomicAdd(coarse_scratch[b], uint(s[0]));  // n < 2^32: its high word stays 0
  for (uint k = 1u; k < 10u; ++k) AtomicAdd64(b + 2u * k, s[k]);
}

// Pass 1 over points first .. first + kItems - 1.
void SeedSums(uint first) {
  uint end = min(first + kItems, pc.count);
  uint cur = kNone, seen = kNone;  // the cell of the sums s, the cell of the test t
  SeedTest t = SeedTest(0u, 0.0, 0.0);
  uint64_t s[10];
  for (uint i = first; i < end; ++i) {
    uint c = point_cell[i];
    if (c == kNone) continue;
    if (c != seen) {
      seen = c;
      t = SeedTestOf(c);
    }
    float zf = zt[i];
    if (!IsSeed(zf, t)) continue;
    if (c != cur) {
      if (cur != kNone) FlushSeedSums(cur, s);
      cur = c;
      for (uint k = 0u; k < 10u; ++k) s[k] = uint64_t(0);
    }
    ivec3 q = Mm(i, zf);
    int64_t x = int64_t(q.x), y = int64_t(q.y), z = int64_t(q.z);
    s[0] += uint64_t(1);
    s[1] += uint64_t(x);
    s[2] += uint64_t(y);
    s[3] += uint64_t(z);
    s[4] += uint64_t(x * x);
    s[5] += uint64_t(x * y);
    s[6] += uint64_t(x * z);
    s[7] += uint64_t(y * y);
    s[8] += uint64_t(y * z);
    s[9] += uint64_t(z * z);
  }
  if (cur != kNone) FlushSeedSums(cur, s);
}

// Pass 3 over points first .. first + kItems - 1.
void DistanceSums(uint first) {
  uint end = min(first + kItems, pc.count);
  uint cur = kNone, seen = kNone;  // the cell of sum, the cell of t, a, b and ground
  SeedTest t = SeedTest(0u, 0.0, 0.0);
  ivec4 a = ivec4(0), b = ivec4(0);
  bool ground = false;
  uint64_t sum = uint64_t(0);
  for (uint i = first; i < end; ++i) {
    uint c = point_cell[i];
    if (c == kNone) continue;
    if (c != seen) {
      seen = c;
      t = SeedTestOf(c);
      a = cell_plane4[2u * c];
      b = cell_plane4[2u * c + 1u];
      ground = t.mode != 0u && GroundPlane(a, b);
    }
    float z = zt[i];
    if (!ground || !IsSeed(z, t)) continue;
    if (c != cur) {
      if (cur != kNone) AtomicAdd64(Base(cur) + 2u * kSumDist, sum);
      cur = c;
      sum = uint64_t(0);
    }
    sum += uint64_t(Distance(i, z, a, b));
  }
  if (cur != kNone) AtomicAdd64(Base(cur) + 2u * kSumDist, sum);
}

// Pass 5 over points first .. first + kItems - 1: coarse = the point's cell is a ground cell and
// its |distance| (Distance's arithmetic) <= the threshold; the cell's plane is read once per run.
void Classify(uint first) {
  uint end = min(first + kItems, pc.count);
  uint cur = kNone;
  bool ground = false;
  int64_t nx = int64_t(0), ny = int64_t(0), nz = int64_t(0), offset = int64_t(0);
  int64_t threshold = int64_t(0);
  for (uint i = first; i < end; ++i) {
    uint c = point_cell[i];
    if (c != cur) {
      cur = c;
      ground = false;
      if (c != kNone && cell_seed_mode[c] != 0u) {
        ivec4 a = cell_plane4[2u * c], b = cell_plane4[2u * c + 1u];
        ground = GroundPlane(a, b);
        nx = int64_t(a.x), ny = int64_t(a.y), nz = int64_t(a.z);
        offset = nx * int64_t(a.w) + ny * int64_t(b.x) + nz * int64_t(b.y);
        threshold = int64_t(b.z);
      }
    }
    uint label = 0u;
    if (ground) {
      ivec3 q = Mm(i, zt[i]);
      int64_t d = nx * int64_t(q.x) + ny * int64_t(q.y) + nz * int64_t(q.z) - offset;
      label = (d < int64_t(0) ? -d : d) <= threshold ? 1u : 0u;
    }
    coarse[i] = label;
  }
}

// Pass 0 with rise_carry: the first workgroup, ring after ring (each ring's cells strided over its
// invocations, a barrier between two rings), then the carried words zeroed.
void SeedModesCarried() {
  uint rings = p.rings_near + p.rings_far;
  for (uint ring = 0u; ring < rings; ++ring) {
    uint sectors = ring < p.rings_near ? p.sectors_near : p.sectors_far;
    for (uint s = gl_LocalInvocationID.x; s < sectors; s += gl_WorkGroupSize.x)
      SeedMode(CellIndex(ring, s));
    memoryBarrierBuffer();
    barrier();
  }
  for (uint c = gl_LocalInvocationID.x; c < pc.count; c += gl_WorkGroupSize.x)
    coarse_scratch_c[Base(c) + kCarried] = 0u;
}

void main() {
  if (kPass == 0u && p.rise_carry != 0u) {
    if (gl_WorkGroupID.x == 0u) SeedModesCarried();
    return;
  }
  uint i = gl_GlobalInvocationID.x;
  if (i >= pc.count) return;
  if (kPass == 0u) {
    SeedMode(i);
  } else if (kPass == 1u) {
    SeedSums(i * kItems);
  } else if (kPass == 2u) {
    FitPlane(i);
  } else if (kPass == 3u) {
    DistanceSums(i * kItems);
  } else if (kPass == 4u) {
    if (!Ground(i)) return;
    int64_t floor_q = exact_ToFixed(p.plane_dist_floor, 16384000.0);  // metres -> mm * 2^14
    int64_t scale_q = exact_ToFixed(p.plane_dist_scale, 256.0);
    int64_t mean_scaled = exact_DivToZero(scale_q * int64_t(Sum(i, kSumDist)),
                                          int64_t(256) * int64_t(cell_plane[8u * i + 7u]));
    cell_plane[8u * i + 6u] = int(min(max(floor_q, mean_scaled), int64_t(0x7FFFFFFF)));
  } else {
    Classify(i * kItems);
  }
}
