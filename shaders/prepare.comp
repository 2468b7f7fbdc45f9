// prepare (paper III-B.1, eq. 3): the GPU twin of reference_cpu/prepare.cpp, same bytes.
// One invocation per point i < n (push constant).
// In: binding 0 Params (uniform; has_ring says whether binding 2 holds one ring per point),
//     1 xyzi (vec4 per point: x, y, z m, raw intensity, which is not read), 2 ring (int per
//     point, or a dummy).
// Out per point: 3 flags (kPointValid 1, kPointNoise 2), 4 zt, 5 r2 (floats).
// Inputs and every result that can be subnormal go through exact_Ftz0 (subnormals and -0 to +0),
// as in the reference, so that a device that flushes gives the same bytes.
// Valid: x, y, z finite; not exactly (0, 0, 0) (-0 counts as 0); ring (when present)
// inside [0, beams); min_range2 <= r2 <= max_range2; z^2 <= max_range2. Everything of an invalid
// point is written as 0. Finiteness and the origin test look at the bits, so a device that flushes
// subnormals or folds NaN tests away agrees with the CPU.
// Operations, in this order, each one rounded float op (`precise`, never an FMA): xx = x*x,
// yy = y*y, r2 = xx + yy; zz = z*z; tx = k_xz*x, ty = k_yz*y, tilt = tx + ty, zt = z - tilt
// (eq. 3); noise = zt < h_noise.
// No ties: each point is its own invocation.
#version 450
#extension GL_GOOGLE_include_directive : require

#include "common/params.h"
#include "common/frame_codes.h"
#include "common/exact.glsl"

layout(local_size_x_id = 0) in;

layout(std140, set = 0, binding = 0) uniform ParamsBlock { Params p; };
layout(std430, set = 0, binding = 1) readonly buffer Points { vec4 xyzi[]; };
layout(std430, set = 0, binding = 2) readonly buffer Rings { int ring[]; };
layout(std430, set = 0, binding = 3) writeonly buffer Flags { uint flags[]; };
layout(std430, set = 0, binding = 4) writeonly buffer Zt { float zt[]; };
layout(std430, set = 0, binding = 5) writeonly buffer R2 { float r2[]; };

layout(push_constant) uniform Push { uint n; } pc;


bool Finite(float f) { return (floatBitsToUint(f) & 0x7F800000u) != 0x7F800000u; }

// One write of the point's three outputs, after every test, no early return
// (docs/decisions/prepare.md).
void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= pc.n) return;
  vec4 point = xyzi[i];
  float x = exact_Ftz0(point.x), y = exact_Ftz0(point.y), z = exact_Ftz0(point.z);
  precise float xx = exact_Ftz0(x * x);
  precise float yy = exact_Ftz0(y * y);
  precise float r = xx + yy;  // 0 or at least 2^-126: never subnormal
  precise float zz = exact_Ftz0(z * z);
  // Invalid: a NaN or infinity, the origin, a ring outside the beams, a planar range outside
  // [min_range, max_range], |z| beyond the sensor's range (garbage).
  uint bits = floatBitsToUint(x) | floatBitsToUint(y) | floatBitsToUint(z);
  bool valid = Finite(x) && Finite(y) && Finite(z) &&
               (bits & 0x7FFFFFFFu) != 0u &&
               (p.has_ring == 0u || (ring[i] >= 0 && uint(ring[i]) < p.beams)) &&
               r >= p.min_range2 && r <= p.max_range2 && zz <= p.max_range2;
  precise float tx = exact_Ftz0(p.k_xz * x);
  precise float ty = exact_Ftz0(p.k_yz * y);
  precise float tilt = exact_Ftz0(tx + ty);
  precise float height_out = exact_Ftz0(z - tilt);  // eq. 3
  uint f = kPointValid;
  if (height_out < p.h_noise) f |= kPointNoise;
  flags[i] = valid ? f : 0u;
  zt[i] = valid ? height_out : 0.0;
  r2[i] = valid ? r : 0.0;
}
