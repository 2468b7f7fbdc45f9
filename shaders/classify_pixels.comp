// Stage 6, classify pixels (paper eqs. 8-12): the GPU twin of reference_cpu/classify_pixels.cpp,
// same bytes. One invocation per pixel < pixels (push constant).
// In: binding 0 Params (uniform: t_edge, t_slope_*, t_stdz_*, t_stdi_*), 1 pixel_filled (uint),
//     2 f_edge_l, 3 f_edge_r, 4 f_slope, 5 f_varz, 6 f_vari (floats per pixel).
// Out: 7 pixel_class (kPixNonGround 0, kPixGround 1, kPixUnknown 2, kPixEmpty 3).
// edge = edge_l >= t_edge || edge_r >= t_edge (eq. 8); votes -1 when value <= low, else 1 when
// value >= high, else 0 (eqs. 9-11; a slope < 0, undefined, votes 0); s = sum of the three votes;
// s > 0 non-ground, s < 0 without edge ground, else unknown (eq. 12); pixel_filled == 0: empty.
// Comparisons only, each done as IEEE does it but on the bits (ordered keys with -0 = +0, false
// when a NaN is involved), so a device that flushes subnormals or folds NaN tests agrees with the
// CPU.
#version 450
#extension GL_GOOGLE_include_directive : require

#include "common/params.h"
#include "common/exact.glsl"

layout(local_size_x_id = 0) in;

layout(std140, set = 0, binding = 0) uniform ParamsBlock { Params p; };
layout(std430, set = 0, binding = 1) readonly buffer Filled { uint pixel_filled[]; };
layout(std430, set = 0, binding = 2) readonly buffer EdgeL { float f_edge_l[]; };
layout(std430, set = 0, binding = 3) readonly buffer EdgeR { float f_edge_r[]; };
layout(std430, set = 0, binding = 4) readonly buffer Slope { float f_slope[]; };
layout(std430, set = 0, binding = 5) readonly buffer VarZ { float f_varz[]; };
layout(std430, set = 0, binding = 6) readonly buffer VarI { float f_vari[]; };
layout(std430, set = 0, binding = 7) writeonly buffer PixelClass { uint pixel_class[]; };

layout(push_constant) uniform Push { uint pixels; } pc;

const uint kPixNonGround = 0u;  // reference_cpu/frame.h
const uint kPixGround = 1u;
const uint kPixUnknown = 2u;
const uint kPixEmpty = 3u;

bool IsNan(float f) { return (floatBitsToUint(f) & 0x7FFFFFFFu) > 0x7F800000u; }
uint OrderKey(float f) {
  uint u = floatBitsToUint(f);
  return exact_Key(uintBitsToFloat((u & 0x7FFFFFFFu) == 0u ? 0u : u));
}
bool Less(float a, float b) { return !IsNan(a) && !IsNan(b) && OrderKey(a) < OrderKey(b); }
bool LessEq(float a, float b) { return !IsNan(a) && !IsNan(b) && OrderKey(a) <= OrderKey(b); }

int Vote(float value, float low, float high) {
  if (LessEq(value, low)) return -1;
  if (LessEq(high, value)) return 1;
  return 0;
}

void main() {
  uint pix = gl_GlobalInvocationID.x;
  if (pix >= pc.pixels) return;
  bool edge = LessEq(p.t_edge, f_edge_l[pix]) || LessEq(p.t_edge, f_edge_r[pix]);  // eq. 8
  float slope = f_slope[pix];
  int s = (Less(slope, 0.0) ? 0 : Vote(slope, p.t_slope_low, p.t_slope_high)) +  // eq. 9
          Vote(f_varz[pix], p.t_stdz_low, p.t_stdz_high) +                        // eq. 10
          Vote(f_vari[pix], p.t_stdi_low, p.t_stdi_high);                         // eq. 11
  uint c;  // eq. 12
  if (s > 0) c = kPixNonGround;
  else if (!edge && s < 0) c = kPixGround;
  else c = kPixUnknown;
  pixel_class[pix] = pixel_filled[pix] != 0u ? c : kPixEmpty;
}
