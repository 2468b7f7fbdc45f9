// Stage 9, back-project (paper III-D.2): the GPU twin of reference_cpu/back_project.cpp, same
// values. One invocation per point i < n (push constant).
// In: binding 0 Params (uniform), 1 flags, 2 point_pixel, 3 pixel_point, 4 pixel_label (per
//     pixel), 5 f_range, 6 f_height (per pixel, floats), 7 r2, 8 zt (per point, floats), 9 coarse
//     (per point).
// Out per point, one uint32 each (the reference's uint8 widened: host/vk/device enables no 8-bit
// storage): 10 label (1 ground, 0 non-ground), 11 why (kWhy*).
// Invalid (no kPointValid): label 0, why kWhyInvalid; noise (valid and kPointNoise): label 0, why
// kWhyNoise; no pixel is read for either (point_pixel is kNone for an invalid point).
// Else pix = point_pixel[i], ground = pixel_label[pix] == kPixGround; a lost point
// (pixel_point[pix] != i) with coarse[i] == 0 on a ground pixel stays ground only within the
// gates: dr = |exact_Sqrt(r2) - f_range[pix]| <= bp_range_gate and
// dz = |zt - f_height[pix]| <= bp_height_gate (each a rounded float op, `precise`). The reference
// evaluates the cheap conditions first; the boolean is the same in any order (no side effects).
// No ties: each point is its own invocation.
#version 450
#extension GL_GOOGLE_include_directive : require

#include "common/params.h"
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
layout(std430, set = 0, binding = 10) writeonly buffer Label { uint label[]; };
layout(std430, set = 0, binding = 11) writeonly buffer Why { uint why[]; };

layout(push_constant) uniform Push { uint n; } pc;

const uint kPointValid = 1u;  // reference_cpu/frame.h
const uint kPointNoise = 2u;
const uint kPixGround = 1u;
const uint kWhyNonGround = 0u;
const uint kWhyGround = 1u;
const uint kWhyInvalid = 2u;
const uint kWhyNoise = 3u;

// One write of each output (lavapipe runs every branch under a lane mask: a write in the early
// return would be paid by every point).
void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= pc.n) return;
  uint flag = flags[i];
  bool counted = (flag & (kPointValid | kPointNoise)) == kPointValid;  // valid, not noise
  bool ground = false;
  if (counted) {
    uint pix = point_pixel[i];
    ground = pixel_label[pix] == kPixGround;
    if (ground && pixel_point[pix] != i && coarse[i] == 0u) {
      precise float range = exact_Sqrt(r2[i]);
      precise float dr = abs(range - f_range[pix]);
      precise float dz = abs(zt[i] - f_height[pix]);
      ground = dr <= p.bp_range_gate && dz <= p.bp_height_gate;
    }
  }
  label[i] = ground ? 1u : 0u;
  why[i] = ground                       ? kWhyGround
           : counted                    ? kWhyNonGround
           : (flag & kPointValid) != 0u ? kWhyNoise
                                        : kWhyInvalid;
}
