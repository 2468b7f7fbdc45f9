// project (paper eq. 1): the GPU twin of reference_cpu/project.cpp, same bytes.
// Three passes of this shader (specialization constant kPass) in the order 0, 1, 2, with barriers
// between them, pixel_key and pixel_point cleared to kNone and the exact list's header to
// (0, 1, 1, 0) before the first (vkCmdFillBuffer, vkCmdUpdateBuffer).
// In: binding 0 Params (uniform; has_ring says whether binding 2 holds one ring per point),
//     1 xyzi (vec4 per point, the raw cloud), 2 ring (int per point, or a dummy), 3 flags and
//     4 r2 (prepare's outputs), 5 column_dir (width (cos, sin) pairs), 6 beam_bound and
//     7 beam_origin (beams - 1 floats each): the host Tables, the same bytes as the reference's.
// Out: 8 point_pixel (per point: v * width + u, kNone when invalid), 9 pixel_key (per pixel:
//     exact_Key of the smallest r2 among its valid non-noise points, kNone when none), 10
//     pixel_point (per pixel: the lowest point index among those whose key equals pixel_key).
// Scratch: 11 project_exact, the exact list: words 0-2 the indirect dispatch arguments of pass 1,
//     word 3 its length, then point indices.
// Pass 0, one invocation per kItems consecutive points (the device's shape, specialization
// constant 2: host/vk/shape.h): column and row of every valid point with
// the device's float products (MulFast), point_pixel and atomicMin of the key; a point for which
// one of them may differ from IEEE's (a subnormal operand, or a product under 2^-125 that the
// device may flush) goes on the exact list instead. Pass 1, one invocation per listed point: the
// same with the products by integer arithmetic (MulExact). Pass 2: among valid non-noise points
// whose key equals the pixel's, atomicMin of the index. Both reductions are integer minima,
// order-independent. The exact products run in pass 1 only (docs/decisions/project.md).
// Column: the reference starts from the previous point's column; here every point starts from
// GuessColumn's polynomial (exact_Div, exact_FloorToInt) and walks to the unique k with
// AngleBelow(p, dir_k) and not AngleBelow(p, dir_{k+1}): the same k, as the predicate is a prefix
// over k. The guess uses the exact division (docs/decisions/project.md). Row: as the reference's
// RowNear, the previous point's row of the chunk when it passes both boundary tests (two tests
// where the binary search takes six; scans come ring by ring), else RowOf's binary search: the
// same row, so the bytes do not depend on kItems (with kItems = 1 no point has a hint).
// Exactness against the CPU (gradual underflow): the raw cloud is read, so a coordinate may be
// subnormal, and products such as x * sin(phi) or h * |h| may round into the subnormal range.
// A device may flush those, so every float the predicates compare is produced by
// Mul() below (the device's product where it is IEEE's, else the point is recomputed with
// MulExact: IEEE binary32 product, round to nearest even, gradual underflow, by integer
// arithmetic) and compared by its bits; `a - b > 0` of the reference is `a > b` for finite floats
// (IEEE subtraction of two different finite floats is never zero), which Greater() decides.
#version 450
#extension GL_GOOGLE_include_directive : require

#include "common/params.h"
#include "common/frame_codes.h"
#include "common/exact.glsl"

layout(local_size_x_id = 0) in;

layout(std140, set = 0, binding = 0) uniform ParamsBlock { Params p; };
layout(std430, set = 0, binding = 1) readonly buffer Points { vec4 xyzi[]; };
layout(std430, set = 0, binding = 2) readonly buffer Rings { int ring[]; };
layout(std430, set = 0, binding = 3) readonly buffer Flags { uint flags[]; };
layout(std430, set = 0, binding = 4) readonly buffer R2 { float r2[]; };
layout(std430, set = 0, binding = 5) readonly buffer ColumnDir { float column_dir[]; };
layout(std430, set = 0, binding = 6) readonly buffer BeamBound { float beam_bound[]; };
layout(std430, set = 0, binding = 7) readonly buffer BeamOrigin { float beam_origin[]; };
layout(std430, set = 0, binding = 8) buffer PointPixel { uint point_pixel[]; };
layout(std430, set = 0, binding = 9) buffer PixelKey { uint pixel_key[]; };
layout(std430, set = 0, binding = 10) buffer PixelPoint { uint pixel_point[]; };
layout(std430, set = 0, binding = 11) buffer ProjectExact { uint project_exact[]; };

layout(constant_id = 1) const uint kPass = 0u;  // a pipeline per pass (host/vk/kernel.h)
layout(constant_id = 2) const uint kItems = 1u;  // points per invocation of pass 0 (the shape)

layout(push_constant) uniform Push {
  uint n;
} pc;

const uint kListLength = 3u, kListStart = 4u;  // project_exact words (0-2: dispatch arguments)

// --- float predicates by their bits (no device float op touches a subnormal) ---

bool IsZero(uint u) { return (u & 0x7FFFFFFFu) == 0u; }
bool Positive(uint u) { return (u & 0x80000000u) == 0u && !IsZero(u); }  // f > 0
bool Negative(uint u) { return (u & 0x80000000u) != 0u && !IsZero(u); }  // f < 0

// a > b for finite floats given as bits (+0 == -0).
bool Greater(uint a, uint b) {
  if (IsZero(a) && IsZero(b)) return false;
  return exact_Key(uintBitsToFloat(a)) > exact_Key(uintBitsToFloat(b));
}

// The bits of a * b as IEEE binary32 rounds it (nearest even, gradual underflow, overflow to
// Inf) for finite a and b, subnormals included.
uint MulExact(uint ua, uint ub) {
  uint sign = (ua ^ ub) & 0x80000000u;
  if (IsZero(ua) || IsZero(ub)) return sign;
  uint ea = (ua >> 23) & 0xFFu, eb = (ub >> 23) & 0xFFu;
  // value = m * 2^e
  uint64_t ma = uint64_t(ea == 0u ? (ua & 0x7FFFFFu) : ((ua & 0x7FFFFFu) | 0x800000u));
  uint64_t mb = uint64_t(eb == 0u ? (ub & 0x7FFFFFu) : ((ub & 0x7FFFFFu) | 0x800000u));
  int e = (ea == 0u ? -149 : int(ea) - 150) + (eb == 0u ? -149 : int(eb) - 150);
  uint64_t q = ma * mb;  // < 2^48, non-zero
  uint hi = uint(q >> 32);
  int top = hi != 0u ? 32 + findMSB(hi) : findMSB(uint(q));
  int biased = top + e + 127;  // of the leading bit
  if (biased >= 1) {           // normal (or overflow)
    int shift = top - 23;
    uint64_t m = shift > 0 ? exact_RoundShift_(q, shift, false) : (q << (-shift));
    // m in [2^23, 2^24]: a carry into bit 24 moves into the exponent by the addition.
    uint bits = (uint(biased - 1) << 23) + uint(m);
    if (bits >= 0x7F800000u) return sign | 0x7F800000u;
    return sign | bits;
  }
  // Subnormal result: steps of 2^-149, q * 2^(e + 149) of them, rounded (2^23 steps is the
  // smallest normal, encoded by the same bits).
  int up = e + 149;
  if (up >= 0) return sign | uint(q << up);  // exact (below 2^23 here)
  int shift = -up;
  if (shift > 63) return sign;
  return sign | uint(exact_RoundShift_(q, shift, false));
}

bool g_inexact = false;  // pass 0: a MulFast product may not be IEEE's

bool Subnormal(uint u) { return (u & 0x7F800000u) == 0u && (u & 0x7FFFFFu) != 0u; }

// The device's product of finite a and b (Vulkan rounds it correctly, but may flush subnormal
// operands and results): IEEE's unless an operand is subnormal or a non-zero product is under
// 2^-125 in magnitude (one that rounds to 2^-126 may have been flushed); g_inexact says so.
uint MulFast(uint ua, uint ub) {
  precise float r = uintBitsToFloat(ua) * uintBitsToFloat(ub);
  uint ur = floatBitsToUint(r);
  bool tiny = !IsZero(ua) && !IsZero(ub) && (ur & 0x7F800000u) < 0x01000000u;  // exponent < 2
  if (Subnormal(ua) || Subnormal(ub) || tiny) g_inexact = true;
  return ur;
}

uint Mul(uint ua, uint ub) { return kPass == 1u ? MulExact(ua, ub) : MulFast(ua, ub); }

// --- eq. 1, column ---

// True when the angle is in the upper half-plane (0, pi].
bool Upper(uint x, uint y) { return Positive(y) || (IsZero(y) && Negative(x)); }

// atan2(py, px) < atan2(by, bx), as the reference decides it.
bool AngleBelow(uint px, uint py, uint bx, uint by) {
  bool up = Upper(px, py), bup = Upper(bx, by);
  if (up != bup) return bup;
  return Greater(Mul(px, by), Mul(py, bx));
}

bool BelowDir(uint x, uint y, int k) {
  return AngleBelow(x, y, floatBitsToUint(column_dir[2 * k]),
                    floatBitsToUint(column_dir[2 * k + 1]));
}

// The reference's GuessColumn, operation for operation (only a starting point: any guess walks
// to the same column).
int GuessColumn(float x, float y, uint width) {
  float ax = abs(x), ay = abs(y);
  float lo = min(ax, ay), hi = max(ax, ay);
  float t = exact_Div(lo, hi);
  precise float t2 = t * t;
  precise float a = 0.0208351 * t2;
  a = (a - 0.0851330) * t2;
  a = (a + 0.1801410) * t2;
  a = (a - 0.3302995) * t2;
  a = (a + 0.9998660) * t;  // atan(lo / hi) in [0, pi/4]
  if (ay > ax) a = 1.57079637 - a;
  if (x < 0.0) a = 3.14159274 - a;
  if (y < 0.0) a = -a;                              // theta = atan2(y, x)
  precise float turns = (3.14159274 - a) * 0.159154937;  // (pi - theta) / (2 pi), eq. 1
  precise float scaled = turns * float(width);
  int64_t g = exact_FloorToInt(scaled);
  // Clamped here already (a NaN guess, x = y = 0, converts to anything).
  return int(clamp(g, int64_t(0), int64_t(width) - int64_t(1)));
}

uint ColumnOf(float xf, float yf, uint width) {
  uint x = floatBitsToUint(xf), y = floatBitsToUint(yf);
  int u = GuessColumn(xf, yf, width);
  while (u + 1 < int(width) && BelowDir(x, y, u + 1)) ++u;
  while (u > 0 && !BelowDir(x, y, u)) --u;
  return uint(u);
}

// --- eq. 1, row ---

// z - origin, bits: exact for origin = +-0 (whatever the device does with a subnormal z); a
// non-zero origin is metres, far from the subnormal range.
uint Height(float z, float origin) {
  uint uo = floatBitsToUint(origin);
  if (IsZero(uo)) {
    uint uz = floatBitsToUint(z);
    // z - (+0) = z; z - (-0) = z + 0 = z, except -0 + 0 = +0.
    if ((uo & 0x80000000u) != 0u && uz == 0x80000000u) return 0u;
    return uz;
  }
  precise float h = z - origin;
  return floatBitsToUint(h);
}

// Boundary b lies above the point: bound[b] * r2 > h * |h|, h = z - origin[b].
bool BoundAbove(float z, uint r2u, uint b) {
  uint h = Height(z, beam_origin[b]);
  uint abs_h = Negative(h) ? (h ^ 0x80000000u) : h;  // the reference's (h < 0 ? -h : h)
  uint hh = Mul(h, abs_h);
  uint s = Mul(floatBitsToUint(beam_bound[b]), r2u);
  return Greater(s, hh);
}

uint RowOf(float z, uint r2u, uint beams) {
  uint lo = 0u, hi = beams - 1u;
  while (lo < hi) {
    uint mid = (lo + hi + 1u) >> 1;  // boundary index mid - 1
    if (BoundAbove(z, r2u, mid - 1u)) lo = mid;
    else hi = mid - 1u;
  }
  return lo;
}

// RowOf with the row of an earlier point of the invocation's chunk as a hint (kNone: none), as
// the reference's RowNear: the row is the unique v with boundary v - 1 above the point and
// boundary v not, so a hint that passes both tests is RowOf's answer; else RowOf decides.
uint RowNear(float z, float r2f, uint beams, uint hint) {
  uint r2u = floatBitsToUint(r2f);
  if (hint != kNone && (hint == 0u || BoundAbove(z, r2u, hint - 1u)) &&
      !(hint + 1u < beams && BoundAbove(z, r2u, hint)))
    return hint;
  return RowOf(z, r2u, beams);
}

// Pass 0 (through MulFast) and pass 1 (MulExact) for valid point i: its pixel and key; in pass 0
// a point whose products may not be IEEE's goes on the exact list instead. `row` is a hint for
// RowNear (kNone: none), then the point's row when it has one.
void PixelOf(uint i, uint f, inout uint row) {
  g_inexact = false;
  vec4 point = xyzi[i];
  uint u = ColumnOf(point.x, point.y, p.width);
  uint v;
  if (p.has_ring != 0u) {
    uint r = uint(ring[i]);
    v = p.ring_zero_is_top != 0u ? r : p.beams - 1u - r;
  } else {
    v = RowNear(point.z, r2[i], p.beams, row);
  }
  if (g_inexact) {
    row = kNone;
    uint slot = atomicAdd(project_exact[kListLength], 1u);
    project_exact[kListStart + slot] = i;
    atomicMax(project_exact[0], slot / gl_WorkGroupSize.x + 1u);
    return;
  }
  row = v;
  uint pix = v * p.width + u;
  point_pixel[i] = pix;
  if ((f & kPointNoise) != 0u) return;
  atomicMin(pixel_key[pix], exact_Key(r2[i]));
}

void main() {
  uint i = gl_GlobalInvocationID.x;
  uint row = kNone;
  if (kPass == 1u) {
    if (i >= project_exact[kListLength]) return;
    i = project_exact[kListStart + i];
    PixelOf(i, flags[i], row);
    return;
  }
  if (kPass == 0u) {  // kItems consecutive points, each row the next one's hint
    uint end = min(pc.n, i * kItems + kItems);
    for (uint k = i * kItems; k < end; ++k) {
      uint f = flags[k];
      if ((f & kPointValid) == 0u) point_pixel[k] = kNone;
      else PixelOf(k, f, row);
    }
    return;
  }
  if (i >= pc.n) return;  // pass 2
  uint f = flags[i];
  if ((f & kPointValid) == 0u || (f & kPointNoise) != 0u) return;
  uint pix = point_pixel[i];
  if (exact_Key(r2[i]) == pixel_key[pix]) atomicMin(pixel_point[pix], i);
}
