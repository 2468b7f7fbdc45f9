// feature_maps (paper III-D.1, Fig. 6 and 10): the GPU twin of
// reference_cpu/feature_maps.cpp, same bytes. Two dispatches of this one shader, the pass chosen
// by the specialization constant kPass (one pipeline each), with a compute -> compute barrier
// between them. First, measure and fill: pass 0 one invocation per pixel < pixels (push
// constant), pixel = v * width + u, or instead, when the width is a multiple of 4, pass 1 one per
// quad of pixels (pixels / 4 of them). Then pass 2, one invocation per run of kItems pixels of a
// row (the device's shape, specialization constant 2: host/vk/shape.h; its 3x3 window's columns
// sliding along the run, each column's three pixels loaded once; a run's first pixel loads its
// three columns, so with kItems = 1 every pixel loads its own, and the integers summed are the
// same for every kItems).
// In: binding 0 Params (uniform: width, beams, hole_gap), 1 pixel_point (uint, kNone empty),
//     2 r2, 3 zt (floats per point).
// Out: 4 pixel_filled (0 empty, 1 measured, 2 filled), 5 f_range, 6 f_height (pass 0 or 1),
//     7 f_slope, 8 f_edge_l, 9 f_edge_r, 10 f_varz (pass 2).
// Scratch: 11 feature_pack, per pixel (filled, range and height bits, 0), written by pass 0 or 1
//     beside the three maps, so that pass 2 reads a pixel with one vector load
//     (docs/decisions/feature_maps.md).
// Pass 0 (or 1), measure and fill: a measured pixel takes range = Sqrt(r2) and height z_t of its
//   winning point; an empty pixel whose left and right neighbours (columns wrap) are
//   measured and whose ranges differ by at most hole_gap takes (l + r) * 0.5 of each. The
//   neighbours' values are recomputed from pixel_point and the per-point buffers (read-only), so
//   no invocation reads what another one writes in this pass.
// Pass 2, on measured and filled pixels (0 everywhere else): slope = Div(|z(v+1) - z|,
//   |r(v+1) - r|), -1 when the pixel below is empty (or absent) or the ranges are equal; edge_l =
//   |z - z(u-1)|, edge_r = |z(u+1) - z| (0 when that neighbour is empty); var_z, the variance of
//   height about the window's line in range, over the 3x3 window (rows clipped, columns
//   wrapping) from the int64 moments n, sum z, sum z^2, sum r, sum r^2, sum r z of the quantised
//   heights and ranges ToFixed(value, 1e4) (the nine neighbours' integers summed directly: the
//   CPU's shared row sums give the same integers), then the reference's VarianceAboutLine op for
//   op: Vz, Vr, C in int64, vz, vr, c = I64ToFloat, b = vr > 0 ? Div(c, vr) : 0 clamped to
//   [-1, 1], bc = b * c, res = max((vz - (bc + bc)) + (b * b) * vr, 0), var = Div(res,
//   float(n * n)) * 1e-8.
// Results that can be subnormal go through exact_Ftz0 as in the reference: the filled height (sum
// and product), the edges.
// Comparisons on the bits (as IEEE does them: -0 == +0, false with a NaN), every float operation
// precise (no contraction), division, square root and int64 -> float by exact.glsl.
#version 450
#extension GL_GOOGLE_include_directive : require

#include "common/params.h"
#include "common/frame_codes.h"
#include "common/exact.glsl"
#include "common/compare.glsl"

layout(local_size_x_id = 0) in;

layout(std140, set = 0, binding = 0) uniform ParamsBlock { Params p; };
layout(std430, set = 0, binding = 1) readonly buffer PixelPoint { uint pixel_point[]; };
layout(std430, set = 0, binding = 2) readonly buffer R2 { float r2[]; };
layout(std430, set = 0, binding = 3) readonly buffer Zt { float zt[]; };
layout(std430, set = 0, binding = 4) writeonly buffer Filled { uint pixel_filled[]; };
layout(std430, set = 0, binding = 5) writeonly buffer Range { float f_range[]; };
layout(std430, set = 0, binding = 6) writeonly buffer Height { float f_height[]; };
layout(std430, set = 0, binding = 7) writeonly buffer Slope { float f_slope[]; };
layout(std430, set = 0, binding = 8) writeonly buffer EdgeL { float f_edge_l[]; };
layout(std430, set = 0, binding = 9) writeonly buffer EdgeR { float f_edge_r[]; };
layout(std430, set = 0, binding = 10) writeonly buffer VarZ { float f_varz[]; };
layout(std430, set = 0, binding = 11) buffer FeaturePack { uvec4 feature_pack[]; };
// Pass 1's views, four pixels at a time.
layout(std430, set = 0, binding = 1) readonly buffer PixelPoint4 { uvec4 pixel_point4[]; };
layout(std430, set = 0, binding = 4) writeonly buffer Filled4 { uvec4 pixel_filled4[]; };
layout(std430, set = 0, binding = 5) writeonly buffer Range4 { vec4 f_range4[]; };
layout(std430, set = 0, binding = 6) writeonly buffer Height4 { vec4 f_height4[]; };

layout(constant_id = 1) const uint kPass = 0u;  // a pipeline per pass (host/vk/kernel.h)
layout(constant_id = 2) const uint kItems = 1u;  // pass 2: pixels of one row per invocation

layout(push_constant) uniform Push {
  uint pixels;
} pc;


// reference_cpu/feature_maps.cpp: kHeightScale (10000), kHeightQuantum2 (1e-8f), by their bits so
// that no literal parsing can differ.
#define kScale uintBitsToFloat(0x461C4000u)     // 10000.0f
#define kQuantum2 uintBitsToFloat(0x322BCC77u)  // 1e-8f

// |x| > 0 as IEEE compares it: non-zero magnitude (subnormals included) and not NaN.
bool AbsPositive(float x) {
  uint m = floatBitsToUint(x) & 0x7FFFFFFFu;
  return m != 0u && m <= 0x7F800000u;
}

// A pixel's maps from its winning point i, or when it has none from the winning points `left`
// and `right` of its neighbours (kNone: none).
// Two square roots in the code, not three, and one load of each value: the measured pixel's
// values are read where the empty pixel's left neighbour's are (docs/decisions/feature_maps.md).
struct Maps {
  uint filled;
  float range, height;
};
Maps Fill(uint i, uint left, uint right) {
  uint il = i != kNone ? i : left;
  uint ir = i != kNone ? kNone : right;
  float rl = 0.0, il_z = 0.0;  // the measured point's, or the left neighbour's
  if (il != kNone) {
    rl = exact_Sqrt(r2[il]);
    il_z = zt[il];
  }
  uint filled = 0u;
  precise float range = 0.0, height = 0.0;
  if (i != kNone) {
    filled = 1u;
    range = rl;
    height = il_z;
  } else if (il != kNone && ir != kNone) {
    float rr = exact_Sqrt(r2[ir]);
    precise float gap = abs(rl - rr);
    if (LessEq(gap, p.hole_gap)) {
      filled = 2u;
      range = (rl + rr) * 0.5;
      precise float z_sum = exact_Ftz0(il_z + zt[ir]);
      height = exact_Ftz0(z_sum * 0.5);
    }
  }
  return Maps(filled, range, height);
}

uvec4 Packed(Maps m) {
  return uvec4(m.filled, floatBitsToUint(m.range), floatBitsToUint(m.height), 0u);
}

// Pass 0, any width: pixel pix.
void MeasureAndFill(uint pix) {
  uint w = p.width;
  uint v = pix / w, u = pix - v * w, row = v * w;
  uint i = pixel_point[pix];
  uint left = i != kNone ? kNone : pixel_point[row + (u == 0u ? w - 1u : u - 1u)];
  uint right = i != kNone ? kNone : pixel_point[row + (u + 1u == w ? 0u : u + 1u)];
  Maps m = Fill(i, left, right);
  // One write of each output (as in pass 2).
  pixel_filled[pix] = m.filled;
  f_range[pix] = m.range;
  f_height[pix] = m.height;
  feature_pack[pix] = Packed(m);
}

// Pass 1, a width that is a multiple of 4: pixels 4e .. 4e + 3 (one row), their winning points
// one vector load, the maps four vector stores (docs/decisions/feature_maps.md).
void MeasureAndFillQuad(uint e) {
  uint w = p.width, first = 4u * e;
  uint v = first / w, u0 = first - v * w, row = v * w;
  uvec4 i = pixel_point4[e];
  uint left = pixel_point[row + (u0 == 0u ? w - 1u : u0 - 1u)];
  uint right = pixel_point[row + (u0 + 4u == w ? 0u : u0 + 4u)];
  Maps a = Fill(i.x, left, i.y), b = Fill(i.y, i.x, i.z), c = Fill(i.z, i.y, i.w),
       d = Fill(i.w, i.z, right);
  pixel_filled4[e] = uvec4(a.filled, b.filled, c.filled, d.filled);
  f_range4[e] = vec4(a.range, b.range, c.range, d.range);
  f_height4[e] = vec4(a.height, b.height, c.height, d.height);
  feature_pack[first] = Packed(a);
  feature_pack[first + 1u] = Packed(b);
  feature_pack[first + 2u] = Packed(c);
  feature_pack[first + 3u] = Packed(d);
}

// A pixel as pass 0 or 1 packed it.
bool IsFilled(uvec4 e) { return e.x != 0u; }
float RangeOf(uvec4 e) { return uintBitsToFloat(e.y); }
float HeightOf(uvec4 e) { return uintBitsToFloat(e.z); }

// One column's pixels in rows v - 1 .. v + 1 (clipped): the int64 moments of the window (filled
// count, sums of the quantised heights, ranges, their squares and products; empty pixels hold 0),
// and the pixels of rows v and v + 1 (zero when v + 1 is past the last row), which are all the
// features of row v need of this column besides the moments.
struct Moments {
  int64_t n, sz, szz, sr, srr, srz;
};
struct Column {
  Moments m;
  uvec4 mid, below;
};
Column ColumnAt(uint col, uint v) {
  uint w = p.width, h = p.beams;
  Column c;
  c.m = Moments(int64_t(0), int64_t(0), int64_t(0), int64_t(0), int64_t(0), int64_t(0));
  c.mid = uvec4(0u);
  c.below = uvec4(0u);
  for (int dv = -1; dv <= 1; ++dv) {
    int vv = int(v) + dv;
    if (vv < 0 || vv >= int(h)) continue;
    uvec4 e = feature_pack[uint(vv) * w + col];
    if (dv == 0) c.mid = e;
    if (dv == 1) c.below = e;
    if (IsFilled(e)) c.m.n += int64_t(1);
    int64_t qz = exact_ToFixed(HeightOf(e), kScale);
    int64_t qr = exact_ToFixed(RangeOf(e), kScale);
    c.m.sz += qz;
    c.m.szz += qz * qz;
    c.m.sr += qr;
    c.m.srr += qr * qr;
    c.m.srz += qr * qz;
  }
  return c;
}

// Pass 2 for pixel pix = v * w + u of columns l, c, r (u - 1, u, u + 1, wrapping), the 3x3
// moments being the sum of the three columns'.
// An empty pixel gets 0 everywhere: computed like the others and replaced at the one write of
// each output, no early return (docs/decisions/feature_maps.md).
void Features(uint pix, uint v, Column l, Column c, Column r) {
  uint h = p.beams;
  bool filled = IsFilled(c.mid);
  float z = HeightOf(c.mid), r_ = RangeOf(c.mid);

  // Slope toward the next row down.
  float slope = -1.0;
  if (v + 1u < h && IsFilled(c.below)) {
    precise float dz = abs(HeightOf(c.below) - z);
    precise float dr = abs(RangeOf(c.below) - r_);
    if (AbsPositive(dr)) slope = exact_Div(dz, dr);
  }
  f_slope[pix] = filled ? slope : 0.0;

  // Edges, columns wrapping.
  precise float el = 0.0, er = 0.0;
  if (IsFilled(l.mid)) el = exact_Ftz0(abs(z - HeightOf(l.mid)));
  if (IsFilled(r.mid)) er = exact_Ftz0(abs(HeightOf(r.mid) - z));
  f_edge_l[pix] = filled ? el : 0.0;
  f_edge_r[pix] = filled ? er : 0.0;

  // 3x3 moments of the quantised values: integers, so any summation order gives the same.
  int64_t n = l.m.n + c.m.n + r.m.n, sz = l.m.sz + c.m.sz + r.m.sz;
  int64_t szz = l.m.szz + c.m.szz + r.m.szz, sr = l.m.sr + c.m.sr + r.m.sr;
  int64_t srr = l.m.srr + c.m.srr + r.m.srr, srz = l.m.srz + c.m.srz + r.m.srz;
  float vz = exact_I64ToFloat(n * szz - sz * sz);
  float vr = exact_I64ToFloat(n * srr - sr * sr);
  float cv = exact_I64ToFloat(n * srz - sr * sz);
  float fitted = vr > 0.0 ? exact_Div(cv, vr) : 0.0;
  float b = min(max(fitted, -1.0), 1.0);
  precise float bc = b * cv;
  precise float res = (vz - (bc + bc)) + (b * b) * vr;
  float den = float(int(n * n));  // <= 81: exact
  precise float varz = exact_Div(max(res, 0.0), den) * kQuantum2;
  f_varz[pix] = filled ? varz : 0.0;
}

// Pass 2 over run `run` (kItems consecutive pixels of one row): the window's column moments slide
// along the row, each column's computed once instead of three times.
void FeaturesRun(uint run) {
  uint w = p.width;
  uint runs_per_row = (w + kItems - 1u) / kItems;
  uint v = run / runs_per_row, u0 = (run % runs_per_row) * kItems;
  uint u1 = min(u0 + kItems, w);
  Column l = ColumnAt(u0 == 0u ? w - 1u : u0 - 1u, v);  // columns wrap
  Column c = ColumnAt(u0, v);
  for (uint u = u0; u < u1; ++u) {
    Column r = ColumnAt(u + 1u == w ? 0u : u + 1u, v);
    Features(v * w + u, v, l, c, r);
    l = c;
    c = r;
  }
}

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= pc.pixels) return;  // pass 2: i is a run, pass 1 a quad, and pc.pixels their count
  if (kPass == 0u) MeasureAndFill(i);
  else if (kPass == 1u) MeasureAndFillQuad(i);
  else FeaturesRun(i);
}
