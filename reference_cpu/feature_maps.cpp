// feature_maps (paper III-D.1, Fig. 6 and 10).
// In: pixel_point, r2, zt. Out per pixel: pixel_filled, f_range, f_height, f_slope, f_edge_l,
// f_edge_r, f_varz.
// Measured pixel (its winning point): range = Sqrt(r2) (planar, d_i of eq. 1), height z_t.
// Hole filling (the morphology of Fig. 10): an empty pixel whose left and right neighbours are
// measured and whose ranges differ by at most hole_gap takes their average (x 0.5, exact); only
// measured pixels feed the filling, so the result does not depend on the order.
// Then on measured and filled pixels, columns wrapping around (360 degrees), rows not:
//   slope  = |z(v+1) - z| / |r(v+1) - r| toward the next row down (ground slope shows between
//            rings), Div; -1 when that neighbour is empty or the ranges are equal (no evidence).
//            v+1, not the paper's u+1 (docs/decisions/feature_maps.md).
//   edge_l = |z - z(u-1)|, edge_r = |z(u+1) - z| (0 when the neighbour is empty);
//   var_z  = variance of height over the filled pixels of the 3x3 window about its line in
//            range: the variance of z - b r, b the least-squares slope of z on r clamped to
//            [-1, 1], so that a smooth slope (a road's camber, a bank) reads as smooth as flat
//            ground and a wall (r constant, or b beyond 45 degrees) as rough as before
//            (docs/decisions/feature_maps.md, Variance about the line). From exact integer
//            moments: heights and ranges quantised to 0.1 mm (ToFixed); n, sum z, sum z^2, sum r,
//            sum r^2, sum r z in int64 (associative, so window sums are shared: three-column row
//            sums, then three rows); Vz = n sum z^2 - (sum z)^2, Vr = n sum r^2 - (sum r)^2,
//            C = n sum r z - sum r sum z (int64, exact: |q| <= 1e7 at the profile's 1000 m bound);
//            then in float, each op rounded: vz, vr, c = I64ToFloat of them; b = Div(c, vr) when
//            vr > 0, else 0, clamped to [-1, 1]; bc = b * c; res = (vz - (bc + bc)) + (b * b) * vr,
//            at least 0; var = Div(res, n^2) * quantum^2. Order-independent by construction; no
//            result can be subnormal (every non-zero operand is an integer of at least 1, or b of
//            at least 2^-53).
// Results that can be subnormal go through exact::Ftz0 (subnormals and -0 to +0), so that a device
// that flushes agrees: the filled height (sum and product), the edges.
// Float operations, each rounded on its own, in this order: fill (l + r) * 0.5; slope
// dz = |z(v+1) - z|, dr = |r(v+1) - r|, Div(dz, dr); edges as above; variance as above.
// CPU implementation (the bits do not depend on it): row by row, each row measured and filled
// just before the row above it needs it; columns wrap without %; slope and edges without branches
// (every quotient computed on a non-zero divisor, then the defined value selected) so that those
// loops vectorise. The moments are summed in doubles, one array per moment, so that those loops
// vectorise too: where every quantised value of a window is at most 2^22 in magnitude (heights and
// ranges under 419 m), each sum and product is an integer under 2^53, so the doubles hold the int64
// values exactly and convert to the same floats; a row with a larger value takes the int64 sums
// pixel by pixel. Threads (reference_cpu/threads.h): pieces of rows, each measuring the rows just
// outside it once more for itself.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

#include "reference_cpu/exact.h"
#include "reference_cpu/stages.h"

namespace lpir {

namespace {

constexpr float kHeightScale = 10000.0f;  // m -> 0.1 mm
constexpr float kHeightQuantum2 = 1e-8f;  // (0.1 mm)^2 in m^2

// Quantised values up to this magnitude keep every window sum and product exact in a double:
// n * sum z^2 <= 81 * 2^44 < 2^53.
constexpr int32_t kNarrow = 1 << 22;

// The three-column sums of each pixel of one image row (columns wrap), one array per moment of the
// quantised height and range, exact as doubles; `wide` when a value of the row is beyond kNarrow
// (the arrays are then not filled). The six arrays lie in one block, each 64 bytes after the end of
// the one before: VarianceRow reads 18 of them side by side, and arrays 2^k doubles apart would
// fall in the same sets of the L1 cache (measured: the stage 6 % slower).
struct RowMoments {
  std::vector<double> block;
  double *n = nullptr, *z = nullptr, *zz = nullptr, *r = nullptr, *rr = nullptr, *rz = nullptr;
  bool wide = false;
  RowMoments() = default;
  RowMoments(const RowMoments&) = delete;  // the pointers point into its own block
  RowMoments& operator=(const RowMoments&) = delete;
  void Resize(uint32_t w) {
    const size_t stride = size_t(w) + 8;
    block.resize(6 * stride);
    double** arrays[6] = {&n, &z, &zz, &r, &rr, &rz};
    for (size_t k = 0; k < 6; ++k) *arrays[k] = block.data() + k * stride;
  }
  void Zero() {
    std::fill(block.begin(), block.end(), 0.0);
    wide = false;
  }
};

// Scratch reused from frame to frame (each thread has its own): the sums of three image rows and
// the quantised values of the row being summed (int32, then as doubles with the wrap's two
// columns), an empty row that stands for the ones above the first and below the last, and the two
// rows just outside a band of rows, measured for it (filled, range, height of each).
struct Scratch {
  RowMoments sums[3];
  std::vector<int32_t> qz, qr;
  std::vector<double> dz, dr, dn;
  std::vector<uint32_t> empty_filled;
  std::vector<float> empty_value;
  std::vector<uint32_t> outside_filled[2];
  std::vector<float> outside_range[2], outside_height[2];
};
thread_local Scratch scratch;

// c ? a : b, by bit masks (selects of this form vectorise where the branch would not).
inline float Select(bool c, float a, float b) {
  const uint32_t mask = 0u - uint32_t(c);
  return exact::FromBits((exact::Bits(a) & mask) | (exact::Bits(b) & ~mask));
}

// One image row of the maps.
struct Row {
  uint32_t* filled;
  float* range;
  float* height;
};

// The measured pixels of one row, then its one-pixel holes.
void MeasureRow(const uint32_t* __restrict point, const float* __restrict r2,
                const float* __restrict zt, float hole_gap, uint32_t w, const Row& row) {
  uint32_t* __restrict filled = row.filled;
  float* __restrict range = row.range;
  float* __restrict height = row.height;
  // Without branches: point 0 stands in for none (its values are read, then not taken), and the
  // square roots are taken in a second loop, which becomes vector code.
  uint32_t holes = 0;
  for (uint32_t u = 0; u < w; ++u) {
    const uint32_t i = point[u], has = uint32_t(i != kNone);
    const uint32_t at = i & (0u - has);
    filled[u] = has;
    range[u] = r2[at];
    height[u] = Select(has != 0u, zt[at], 0.0f);
    holes |= has ^ 1u;
  }
  for (uint32_t u = 0; u < w; ++u) range[u] = Select(filled[u] != 0u, exact::Sqrt(range[u]), 0.0f);
  if (!holes) return;
  // Only measured pixels (filled 1) feed the filling: a filled pixel (2) has none as neighbour.
  auto fill = [&](uint32_t u, uint32_t l, uint32_t r) {
    if (filled[u] != 0u || filled[l] != 1u || filled[r] != 1u) return;
    const float gap = std::fabs(range[l] - range[r]);
    if (!(gap <= hole_gap)) return;
    filled[u] = 2u;
    range[u] = (range[l] + range[r]) * 0.5f;
    height[u] = exact::Ftz0(exact::Ftz0(height[l] + height[r]) * 0.5f);
  };
  fill(0, w - 1, w > 1 ? 1 : 0);
  for (uint32_t u = 1; u + 1 < w; ++u) fill(u, u - 1, u + 1);
  if (w > 1) fill(w - 1, w - 2, 0);
}

// The three-column sums of pixels 0 .. w - 1 from the row's quantised heights z, ranges r and
// counts n (as doubles), each readable at -1 and w (the row's last and first pixel: columns wrap).
void SumThreeColumns(const double* __restrict z, const double* __restrict r,
                     const double* __restrict n, uint32_t w, double* __restrict on,
                     double* __restrict oz, double* __restrict ozz, double* __restrict or_,
                     double* __restrict orr, double* __restrict orz) {
  for (int64_t u = 0; u < int64_t(w); ++u) {
    const double z0 = z[u - 1], z1 = z[u], z2 = z[u + 1];
    const double r0 = r[u - 1], r1 = r[u], r2 = r[u + 1];
    on[u] = n[u - 1] + n[u] + n[u + 1];
    oz[u] = z0 + z1 + z2;
    ozz[u] = z0 * z0 + z1 * z1 + z2 * z2;
    or_[u] = r0 + r1 + r2;
    orr[u] = r0 * r0 + r1 * r1 + r2 * r2;
    orz[u] = r0 * z0 + r1 * z1 + r2 * z2;
  }
}

// Three-column sums of one finished row: each pixel's count and moments of its quantised height
// and range summed with its two neighbours' (columns wrap). Empty pixels hold height and range 0,
// which quantise to 0, so only the count needs their flag. The quantisation runs four pixels at a
// time in int32 (exact::ToFixed32, in `qz` and `qr`); a row with a value beyond kNarrow (or beyond
// ToFixed32) is only marked wide. `dz`, `dr` and `dn` hold w + 2 doubles: the row's values with
// its last pixel before them and its first after them.
void RowSums(const uint32_t* __restrict filled, const float* __restrict height,
             const float* __restrict range, uint32_t w, int32_t* __restrict qz,
             int32_t* __restrict qr, double* __restrict dz, double* __restrict dr,
             double* __restrict dn, RowMoments& out) {
  uint32_t bad = 0, wide = 0;
  for (uint32_t u = 0; u < w; ++u) {
    qz[u] = exact::ToFixed32(height[u], kHeightScale, bad);
    qr[u] = exact::ToFixed32(range[u], kHeightScale, bad);
    // |q| > kNarrow, as one unsigned comparison
    wide |= uint32_t(uint32_t(qz[u]) + uint32_t(kNarrow) > 2u * uint32_t(kNarrow)) |
            uint32_t(uint32_t(qr[u]) + uint32_t(kNarrow) > 2u * uint32_t(kNarrow));
  }
  out.wide = (bad | wide) != 0;
  if (out.wide) return;
  for (uint32_t u = 0; u < w; ++u) {  // as doubles, so that the sums run two to a vector
    dz[u + 1] = double(qz[u]), dr[u + 1] = double(qr[u]);
    dn[u + 1] = double(int32_t(filled[u] != 0u));
  }
  for (double* d : {dz, dr, dn}) d[0] = d[w], d[w + 1] = d[1];
  SumThreeColumns(dz + 1, dr + 1, dn + 1, w, out.n, out.z, out.zz, out.r, out.rr, out.rz);
}

// The contract's float steps from the window's terms vz, vr and c (the exact integers as floats)
// and den = n^2 (> 0): b = Div(c, vr) when vr > 0, else 0, clamped to [-1, 1]; res = (vz - (bc +
// bc)) + (b * b) * vr, at least 0; Div(res, den) * quantum^2. Without branches, so that a loop over
// it becomes vector code.
inline float VarianceFromTerms(float vz, float vr, float c, float den) {
  const bool positive = vr > 0.0f;
  const float fitted = Select(positive, exact::Div(c, Select(positive, vr, 1.0f)), 0.0f);
  const float b = std::min(std::max(fitted, -1.0f), 1.0f);
  const float bc = b * c;
  const float res = (vz - (bc + bc)) + (b * b) * vr;
  return exact::Div(std::max(res, 0.0f), den) * kHeightQuantum2;
}

// The variance of z about the window's line in range (the contract above) from its moments.
inline float VarianceAboutLine(int64_t n, int64_t sz, int64_t szz, int64_t sr, int64_t srr,
                               int64_t srz) {
  return VarianceFromTerms(exact::I64ToFloat(n * szz - sz * sz),
                           exact::I64ToFloat(n * srr - sr * sr),
                           exact::I64ToFloat(n * srz - sr * sz), float(n * n));  // n^2 <= 81: exact
}

// varz of one row from the three-column sums of the rows above, here and below (none wide):
// VarianceAboutLine with the int64 values held exactly in doubles (kNarrow), so that the loop
// vectorises; 0 where the pixel is not filled.
void VarianceRow(const RowMoments& above, const RowMoments& here, const RowMoments& below,
                 const uint32_t* __restrict filled, uint32_t w, float* __restrict varz) {
  const double* __restrict an = above.n, * __restrict bn = here.n, * __restrict cn = below.n;
  const double* __restrict az = above.z, * __restrict bz = here.z, * __restrict cz = below.z;
  const double* __restrict azz = above.zz, * __restrict bzz = here.zz, * __restrict czz = below.zz;
  const double* __restrict ar = above.r, * __restrict br = here.r, * __restrict cr = below.r;
  const double* __restrict arr = above.rr, * __restrict brr = here.rr, * __restrict crr = below.rr;
  const double* __restrict arz = above.rz, * __restrict brz = here.rz, * __restrict crz = below.rz;
  for (uint32_t u = 0; u < w; ++u) {
    const double n = an[u] + bn[u] + cn[u];
    const double sz = az[u] + bz[u] + cz[u], szz = azz[u] + bzz[u] + czz[u];
    const double sr = ar[u] + br[u] + cr[u], srr = arr[u] + brr[u] + crr[u];
    const double srz = arz[u] + brz[u] + crz[u];
    const bool f = filled[u] != 0u;  // then n >= 1
    const float nf = float(n);
    const float var = VarianceFromTerms(float(n * szz - sz * sz), float(n * srr - sr * sr),
                                        float(n * srz - sr * sz), Select(f, nf * nf, 1.0f));
    varz[u] = Select(f, var, 0.0f);
  }
}

// varz of row `here` pixel by pixel in int64 (VarianceAboutLine), for a window with a wide row:
// each filled pixel's 3 x 3 window of the rows above, here and below, columns wrapping.
void VarianceRowWide(const Row& above, const Row& here, const Row& below, uint32_t w,
                     float* __restrict varz) {
  for (uint32_t u = 0; u < w; ++u) {
    varz[u] = 0.0f;
    if (!here.filled[u]) continue;
    int64_t n = 0, sz = 0, szz = 0, sr = 0, srr = 0, srz = 0;
    const uint32_t columns[3] = {u == 0 ? w - 1 : u - 1, u, u + 1 == w ? 0 : u + 1};
    for (const Row* row : {&above, &here, &below}) {
      for (uint32_t k : columns) {
        const int64_t z = exact::ToFixed(row->height[k], kHeightScale);
        const int64_t r = exact::ToFixed(row->range[k], kHeightScale);
        n += int64_t(row->filled[k] != 0u);
        sz += z, szz += z * z, sr += r, srr += r * r, srz += r * z;
      }
    }
    varz[u] = VarianceAboutLine(n, sz, szz, sr, srr, srz);
  }
}

// Slope and edges of one row, given the row below (empty below the last row). Branch-free, so
// that the loops vectorise: every quotient is computed (on a divisor made non-zero) and the
// contract's value selected.
void SlopeEdges(const Row& row, const Row& below, uint32_t w, float* __restrict slope,
                float* __restrict edge_l, float* __restrict edge_r) {
  const uint32_t* __restrict filled = row.filled;
  const float* __restrict height = row.height;
  const float* __restrict range = row.range;
  const uint32_t* __restrict filled_b = below.filled;
  const float* __restrict height_b = below.height;
  const float* __restrict range_b = below.range;
  for (size_t u = 0; u < w; ++u) {
    const float dz = std::fabs(height_b[u] - height[u]);
    const float dr = std::fabs(range_b[u] - range[u]);
    const bool positive = dr > 0.0f;
    const float quotient = exact::Div(dz, Select(positive, dr, 1.0f));
    const float s = Select((filled_b[u] != 0u) & positive, quotient, -1.0f);
    slope[u] = Select(filled[u] != 0u, s, 0.0f);
  }
  auto edges = [&](size_t u, size_t ul, size_t ur) {
    const bool f = filled[u] != 0u;
    const float z = height[u];
    const float el = exact::Ftz0(std::fabs(z - height[ul]));
    const float er = exact::Ftz0(std::fabs(height[ur] - z));
    edge_l[u] = Select(f & (filled[ul] != 0u), el, 0.0f);
    edge_r[u] = Select(f & (filled[ur] != 0u), er, 0.0f);
  };
  edges(0, w - 1, w > 1 ? 1 : 0);  // columns wrap
  for (size_t u = 1; u + 1 < w; ++u) edges(u, u - 1, u + 1);
  if (w > 1) edges(w - 1, w - 2, 0);
}

}  // namespace

namespace {

// Rows v0 .. v1 - 1 of the maps, row by row, each row measured and filled just before the row above
// it needs it. A row just outside the band (v0 - 1, v1) is measured into s's own rows, never the
// frame's, so that bands of rows run side by side and write only their own rows.
void FeatureRows(const Params& p, Frame& f, uint32_t v0, uint32_t v1, Scratch& s) {
  const uint32_t w = p.width, h = p.beams;
  for (RowMoments& row : s.sums) row.Resize(w);
  s.qz.resize(w), s.qr.resize(w), s.dz.resize(w + 2), s.dr.resize(w + 2), s.dn.resize(w + 2);
  s.empty_filled.assign(w, 0u);
  s.empty_value.assign(w, 0.0f);
  for (int k = 0; k < 2; ++k) {
    s.outside_filled[k].resize(w);
    s.outside_range[k].resize(w);
    s.outside_height[k].resize(w);
  }
  // Row v: the frame's inside the band, s's just outside it, empty outside the image.
  auto row_of = [&](uint32_t v) {
    if (v >= h) return Row{s.empty_filled.data(), s.empty_value.data(), s.empty_value.data()};
    if (v + 1 == v0 || v == v1) {
      const int k = v == v1;
      return Row{s.outside_filled[k].data(), s.outside_range[k].data(), s.outside_height[k].data()};
    }
    const size_t o = size_t(v) * w;
    return Row{f.pixel_filled.data() + o, f.f_range.data() + o, f.f_height.data() + o};
  };
  auto measure = [&](uint32_t v) {
    if (v >= h) return;
    static const float kNoPoint[1] = {0.0f};  // read in place of point 0 when there are none
    const float* r2 = f.n ? f.r2.data() : kNoPoint;
    const float* zt = f.n ? f.zt.data() : kNoPoint;
    MeasureRow(f.pixel_point.data() + size_t(v) * w, r2, zt, p.hole_gap, w, row_of(v));
  };

  // The rows' three-column sums: above (zero above the first row), here and below.
  RowMoments* above = &s.sums[0];
  RowMoments* here = &s.sums[1];
  RowMoments* below = &s.sums[2];
  if (v0 == 0) {
    above->Zero();
  } else {
    measure(v0 - 1);
    const Row r = row_of(v0 - 1);
    RowSums(r.filled, r.height, r.range, w, s.qz.data(), s.qr.data(), s.dz.data(), s.dr.data(),
            s.dn.data(), *above);
  }
  measure(v0);
  {
    const Row r = row_of(v0);
    RowSums(r.filled, r.height, r.range, w, s.qz.data(), s.qr.data(), s.dz.data(), s.dr.data(),
            s.dn.data(), *here);
  }
  measure(v0 + 1);
  for (uint32_t v = v0; v < v1; ++v) {
    const Row row = row_of(v), next = row_of(v + 1);
    RowSums(next.filled, next.height, next.range, w, s.qz.data(), s.qr.data(), s.dz.data(),
            s.dr.data(), s.dn.data(), *below);
    const size_t o = size_t(v) * w;
    SlopeEdges(row, next, w, f.f_slope.data() + o, f.f_edge_l.data() + o, f.f_edge_r.data() + o);
    // The 3x3 windows: this row's sums and those of the rows above and below.
    float* varz = f.f_varz.data() + o;
    if (above->wide || here->wide || below->wide)
      VarianceRowWide(row_of(v - 1), row, next, w, varz);
    else
      VarianceRow(*above, *here, *below, row.filled, w, varz);
    RowMoments* spare = above;
    above = here, here = below, below = spare;
    if (v + 2 <= v1) measure(v + 2);
  }
}

}  // namespace

// Pieces of rows (FeatureRows), each measuring the row above and below it once more for itself.
void FeatureMaps(const Params& p, Frame& f, Threads threads) {
  const uint32_t w = p.width, h = p.beams, pixels = w * h;
  f.pixel_filled.resize(pixels);
  f.f_range.resize(pixels);
  f.f_height.resize(pixels);
  f.f_slope.resize(pixels);
  f.f_edge_l.resize(pixels);
  f.f_edge_r.resize(pixels);
  f.f_varz.resize(pixels);
  if (pixels == 0) return;
  ForPieces(threads, PiecesFor(threads, h, 8), h,
            [&](uint32_t, Range rows) { FeatureRows(p, f, rows.begin, rows.end, scratch); });
}

}  // namespace lpir
