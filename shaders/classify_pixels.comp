// classify_pixels (paper eqs. 8-12): the GPU twin of reference_cpu/classify_pixels.cpp,
// same bytes. Two passes (specialization constant kPass): 0, one invocation per quad of pixels
// 4q .. 4q + 3 < pixels (push constant), read and written as vec4 / uvec4
// (docs/decisions/classify_pixels.md); 1, one invocation per pixel of the last pixels % 4.
// In: binding 0 Params (uniform: t_edge, t_slope_*, t_stdz_*), 1 pixel_filled (uint),
//     2 f_edge_l, 3 f_edge_r, 4 f_slope, 5 f_varz (floats per pixel).
// Out: 6 pixel_class (kPixNonGround 0, kPixGround 1, kPixUnknown 2, kPixEmpty 3, kPixBank 5).
// edge = edge_l >= t_edge || edge_r >= t_edge (eq. 8); votes -1 when value <= low, else 1 when
// value >= high, else 0 (eqs. 9-10; a slope < 0, undefined, votes 0); eq. 11's intensity vote is
// -1 (uniform intensity, as the reference takes it); s = the sum of the three votes; s > 0
// non-ground, s < 0 without edge ground, else unknown (eq. 12); a non-ground pixel with slope <
// bank_slope and varz < bank_rough is a bank; pixel_filled == 0: empty.
// Comparisons only, each done as IEEE does it but on the bits (ordered keys with -0 = +0, false
// when a NaN is involved), so a device that flushes subnormals or folds NaN tests agrees with the
// CPU.
#version 450
#extension GL_GOOGLE_include_directive : require

#include "common/params.h"
#include "common/frame_codes.h"
#include "common/exact.glsl"
#include "common/compare.glsl"

layout(local_size_x_id = 0) in;

layout(std140, set = 0, binding = 0) uniform ParamsBlock { Params p; };
layout(std430, set = 0, binding = 1) readonly buffer Filled { uint pixel_filled[]; };
layout(std430, set = 0, binding = 2) readonly buffer EdgeL { float f_edge_l[]; };
layout(std430, set = 0, binding = 3) readonly buffer EdgeR { float f_edge_r[]; };
layout(std430, set = 0, binding = 4) readonly buffer Slope { float f_slope[]; };
layout(std430, set = 0, binding = 5) readonly buffer VarZ { float f_varz[]; };
layout(std430, set = 0, binding = 6) writeonly buffer PixelClass { uint pixel_class[]; };
// The same buffers four pixels at a time (pass 0).
layout(std430, set = 0, binding = 1) readonly buffer Filled4 { uvec4 pixel_filled4[]; };
layout(std430, set = 0, binding = 2) readonly buffer EdgeL4 { vec4 f_edge_l4[]; };
layout(std430, set = 0, binding = 3) readonly buffer EdgeR4 { vec4 f_edge_r4[]; };
layout(std430, set = 0, binding = 4) readonly buffer Slope4 { vec4 f_slope4[]; };
layout(std430, set = 0, binding = 5) readonly buffer VarZ4 { vec4 f_varz4[]; };
layout(std430, set = 0, binding = 6) writeonly buffer PixelClass4 { uvec4 pixel_class4[]; };

layout(constant_id = 1) const uint kPass = 0u;  // a pipeline per pass (host/vk/kernel.h)

layout(push_constant) uniform Push { uint pixels; } pc;

const int kIntensityVote = -1;  // reference_cpu/classify_pixels.cpp

int Vote(float value, float low, float high) {
  if (LessEq(value, low)) return -1;
  if (LessEq(high, value)) return 1;
  return 0;
}

uint Classify(uint filled, float edge_l, float edge_r, float slope, float varz) {
  bool edge = LessEq(p.t_edge, edge_l) || LessEq(p.t_edge, edge_r);  // eq. 8
  int s = (Less(slope, 0.0) ? 0 : Vote(slope, p.t_slope_low, p.t_slope_high)) +  // eq. 9
          Vote(varz, p.t_stdz_low, p.t_stdz_high) +                              // eq. 10
          kIntensityVote;                                                        // eq. 11
  uint c;  // eq. 12
  if (s > 0) c = Less(slope, p.bank_slope) && Less(varz, p.bank_rough) ? kPixBank : kPixNonGround;
  else if (!edge && s < 0) c = kPixGround;
  else c = kPixUnknown;
  return filled != 0u ? c : kPixEmpty;
}

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (kPass == 0u) {
    if (i >= pc.pixels / 4u) return;
    uvec4 filled = pixel_filled4[i];
    vec4 el = f_edge_l4[i], er = f_edge_r4[i], sl = f_slope4[i], vz = f_varz4[i];
    uvec4 c;
    for (int k = 0; k < 4; ++k) c[k] = Classify(filled[k], el[k], er[k], sl[k], vz[k]);
    pixel_class4[i] = c;
    return;
  }
  uint pix = pc.pixels / 4u * 4u + i;
  if (pix >= pc.pixels) return;
  pixel_class[pix] =
      Classify(pixel_filled[pix], f_edge_l[pix], f_edge_r[pix], f_slope[pix], f_varz[pix]);
}
