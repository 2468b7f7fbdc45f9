// back_project (paper III-D.2): the GPU twin of reference_cpu/back_project.cpp, same
// values. One invocation per four points 4j .. 4j + 3 (n, the points, a push constant), read as
// vectors (docs/decisions/back_project.md), the last n % 4 one by one, and written as one word.
// In: binding 0 Params (uniform), 1 flags, 2 point_pixel, 3 pixel_point, 4 pixel_label (per
//     pixel), 5 f_range, 6 f_height (per pixel, floats), 7 r2, 8 zt (per point, floats), 9 coarse
//     (per point).
// Out: binding 10 label_why, one byte per point, label | why << 1 (label 1 ground, 0
// non-ground; why kWhy*), four points to a uint32 word, point 4j + k in bits 8k .. 8k + 7 (the
// reference's Frame::label_why bytes on a little-endian host; host/vk/device enables no 8-bit
// storage, so the word is assembled in registers); the bytes of the last word past n are 0.
// Invalid (no kPointValid): label 0, why kWhyInvalid; noise (valid and kPointNoise): label 0, why
// kWhyNoise; no pixel is read for either (point_pixel is kNone for an invalid point).
// Else pix = point_pixel[i], ground = pixel_label[pix] == kPixGround; a lost point
// (pixel_point[pix] != i) with coarse[i] == 0 on a ground pixel stays ground only within the
// gates: dr = |exact_Sqrt(r2) - f_range[pix]| <= bp_range_gate and
// dz = |zt - f_height[pix]| <= bp_height_gate (each a rounded float op, `precise`). The reference
// evaluates the cheap conditions first; the boolean is the same in any order (no side effects).
// No ties: every invocation writes its own output word, once.
#version 450
#extension GL_GOOGLE_include_directive : require

#include "common/params.h"
#include "common/frame_codes.h"
#include "common/exact.glsl"

layout(local_size_x_id = 0) in;

layout(std140, set = 0, binding = 0) uniform ParamsBlock { Params p; };
layout(std430, set = 0, binding = 1) readonly buffer Flags { uint flags[]; };
layout(std430, set = 0, binding = 2) readonly buffer PointPixel { uint point_pixel[]; };
layout(std430, set = 0, binding = 3) readonly buffer PixelPoint { uint pixel_point[]; };
layout(std430, set = 0, binding = 4) readonly buffer PixelLabel { uint pixel_label[]; };
layout(std430, set = 0, binding = 5) readonly buffer Range { float f_range[]; };
layout(std430, set = 0, binding = 6) readonly buffer Height { float f_height[]; };
layout(std430, set = 0, binding = 7) readonly buffer R2 { float r2[]; };
layout(std430, set = 0, binding = 8) readonly buffer Zt { float zt[]; };
layout(std430, set = 0, binding = 9) readonly buffer Coarse { uint coarse[]; };
layout(std430, set = 0, binding = 10) writeonly buffer LabelWhy { uint label_why[]; };
layout(std430, set = 0, binding = 1) readonly buffer Flags4 { uvec4 flags4[]; };
layout(std430, set = 0, binding = 2) readonly buffer PointPixel4 { uvec4 point_pixel4[]; };
layout(std430, set = 0, binding = 7) readonly buffer R2x4 { vec4 r2_4[]; };
layout(std430, set = 0, binding = 8) readonly buffer Zt4 { vec4 zt4[]; };
layout(std430, set = 0, binding = 9) readonly buffer Coarse4 { uvec4 coarse4[]; };

layout(push_constant) uniform Push { uint n; } pc;


// Point i's byte, label | why << 1, from its flag, pixel, coarse label, r2 and zt. The output is
// written once, after the branches, no early return (docs/decisions/back_project.md).
uint Classify(uint i, uint flag, uint pix, uint coarse_i, float r2_i, float zt_i) {
  bool counted = (flag & (kPointValid | kPointNoise)) == kPointValid;  // valid, not noise
  bool ground = false;
  if (counted) {
    ground = pixel_label[pix] == kPixGround;
    if (ground && pixel_point[pix] != i && coarse_i == 0u) {
      precise float range = exact_Sqrt(r2_i);
      precise float dr = abs(range - f_range[pix]);
      precise float dz = exact_Ftz0(abs(zt_i - f_height[pix]));  // as the reference: may flush
      ground = dr <= p.bp_range_gate && dz <= p.bp_height_gate;
    }
  }
  uint reason = ground                       ? kWhyGround
                : counted                    ? kWhyNonGround
                : (flag & kPointValid) != 0u ? kWhyNoise
                                             : kWhyInvalid;
  return (ground ? 1u : 0u) | (reason << 1);
}

void main() {
  uint j = gl_GlobalInvocationID.x, first = 4u * j;
  if (first >= pc.n) return;
  bool whole = first + 4u <= pc.n;
  uvec4 flag = uvec4(0u), pix = uvec4(0u), c = uvec4(0u);  // past n: invalid, never read
  vec4 r = vec4(0.0), z = vec4(0.0);
  if (whole) {
    flag = flags4[j];
    pix = point_pixel4[j];
    c = coarse4[j];
    r = r2_4[j];
    z = zt4[j];
  } else {
    for (uint k = 0u; first + k < pc.n; ++k) {
      uint i = first + k;
      flag[k] = flags[i];
      pix[k] = point_pixel[i];
      c[k] = coarse[i];
      r[k] = r2[i];
      z[k] = zt[i];
    }
  }
  uint word = Classify(first, flag.x, pix.x, c.x, r.x, z.x) |
              Classify(first + 1u, flag.y, pix.y, c.y, r.y, z.y) << 8 |
              Classify(first + 2u, flag.z, pix.z, c.z, r.z, z.z) << 16 |
              Classify(first + 3u, flag.w, pix.w, c.w, r.w, z.w) << 24;
  // Past n the points read as invalid (byte 4): those bytes are cleared.
  uint left = pc.n - first;
  label_why[j] = left >= 4u ? word : word & ((1u << (8u * left)) - 1u);
}
