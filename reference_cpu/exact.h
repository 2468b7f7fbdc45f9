// The only arithmetic helpers the stages may use beyond float add/sub/mul/compare/floor and
// integer operations (docs/spec.md, The bit-exact contract). The shaders use their GLSL mirror,
// shaders/common/exact.glsl, function for function; both sides must produce the same bits for the
// same inputs.
//
// Division and square root: IEEE-754 binary32 `/` and `sqrt` on the CPU are correctly rounded
// (round to nearest even), which is the definition the shader helpers implement with integer
// arithmetic. Subnormal inputs and results are flushed to zero on both sides, so devices that
// flush denormals agree too.
#pragma once
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

namespace lpir::exact {

static_assert(std::numeric_limits<float>::is_iec559, "IEEE-754 binary32 required");

inline uint32_t Bits(float f) {
  uint32_t u;
  std::memcpy(&u, &f, 4);
  return u;
}
inline float FromBits(uint32_t u) {
  float f;
  std::memcpy(&f, &u, 4);
  return f;
}

// Flushes subnormals to (signed) zero. In float operations rather than bits, so that loops over it
// become vector code (reference_cpu/prepare.cpp).
inline float Ftz(float f) {
  return std::fabs(f) < std::numeric_limits<float>::min() ? std::copysign(0.0f, f) : f;
}

// A float result that may be subnormal, with every value of magnitude at most FLT_MIN (the
// subnormals, +-0 and +-FLT_MIN itself) as +0: a device may flush a subnormal result to a zero of
// either sign, and one that detects tininess before rounding (NVIDIA) flushes a product whose
// exact value lies just below FLT_MIN where IEEE rounding gives FLT_MIN, so FLT_MIN goes too; the
// stages apply this wherever such a result can arise and every device gives these bits. A mask on
// the bits: GCC turns loops over it into vector code (a float compare and select there kept
// prepare's loop scalar).
inline float Ftz0(float f) {
  const uint32_t u = Bits(f);
  return FromBits(u & (0u - uint32_t((u & 0x7FFFFFFFu) > 0x00800000u)));
}

// Monotone map float -> uint32: a < b (as floats, -0 < +0) iff Key(a) < Key(b). Reductions of
// floats use integer atomics on these keys (min/max), so their result is order-independent.
inline uint32_t Key(float f) {
  uint32_t u = Bits(f);
  return (u & 0x80000000u) ? ~u : (u | 0x80000000u);
}
inline float FromKey(uint32_t k) { return FromBits((k & 0x80000000u) ? (k & 0x7FFFFFFFu) : ~k); }

// Correctly rounded a / b for finite a and finite non-zero b (subnormals flushed).
inline float Div(float a, float b) { return Ftz(Ftz(a) / Ftz(b)); }

// Correctly rounded sqrt(a) for finite a >= 0 (subnormals flushed).
inline float Sqrt(float a) { return Ftz(std::sqrt(Ftz(a))); }

// floor(y) as an integer, exactly, for |y| < 2^62 (GLSL floor() is exact too). Truncation, then
// one step down for negative non-integers: a float of magnitude >= 2^23 is an integer already, and
// below that the truncated value converts back exactly. No libm call (docs/decisions/exact.md).
inline int64_t FloorToInt(float y) {
  const int64_t t = static_cast<int64_t>(y);
  return static_cast<float>(t) > y ? t - 1 : t;
}

// round(x * scale) to int64 as floor(x * scale + 0.5), each step one rounded float op; |x * scale|
// must stay below 2^62 (callers clamp).
inline int64_t ToFixed(float x, float scale) {
  float y = x * scale;
  y = y + 0.5f;
  return FloorToInt(y);
}

// ToFixed(x, scale) as an int32 when |x * scale + 0.5| <= 2^30, in int32 conversions (four per SSE
// instruction, so loops over it become vector code; the CPU's alone: the shaders use ToFixed): the
// truncation is the same integer, and it converts back to the same float. Larger (or non-finite)
// values give 0 and set `bad`, for the caller to take ToFixed's int64 path.
inline int32_t ToFixed32(float x, float scale, uint32_t& bad) {
  float y = x * scale;
  y = y + 0.5f;
  const uint32_t ok = uint32_t(y >= -1073741824.0f) & uint32_t(y <= 1073741824.0f);
  bad |= ok ^ 1u;
  y = FromBits(Bits(y) & (0u - ok));
  const int32_t t = int32_t(y);
  return t - int32_t(float(t) > y);
}

// floor(sqrt(v)) for v >= 0, exact (bit by bit, no float).
inline uint64_t Isqrt(uint64_t v) {
  uint64_t result = 0;
  uint64_t bit = uint64_t(1) << 62;
  while (bit > v) bit >>= 2;
  while (bit != 0) {
    if (v >= result + bit) {
      v -= result + bit;
      result = (result >> 1) + bit;
    } else {
      result >>= 1;
    }
    bit >>= 2;
  }
  return result;
}

// Integer division of a signed numerator by a positive denominator, rounding toward zero, done on
// magnitudes only (shader integer division is only portable for non-negative operands).
inline int64_t DivToZero(int64_t num, int64_t den) {
  const uint64_t mag = num < 0 ? uint64_t(0) - uint64_t(num) : uint64_t(num);  // no signed overflow
  const uint64_t q = mag / uint64_t(den);
  return num < 0 ? -int64_t(q) : int64_t(q);
}

// int64 -> float, rounded to nearest even. Vulkan leaves the rounding of an inexact conversion to
// the device, so the shader mirror (shaders/common/exact.glsl) does it in integer steps; on the CPU
// the IEEE conversion in the default rounding mode is that same function (tests/exact_test.cpp
// checks it against an integer implementation), and much cheaper than branching on the data.
static_assert(std::numeric_limits<float>::round_style == std::round_to_nearest,
              "int64 -> float must round to nearest");
inline float I64ToFloat(int64_t v) { return static_cast<float>(v); }

// 2^e as a float, exactly, for -126 <= e <= 127.
inline float Pow2(int e) { return FromBits(uint32_t(e + 127) << 23); }

// The unbiased exponent of a normal float (floor(log2(|f|))).
inline int Exponent(float f) { return int((Bits(f) >> 23) & 0xFFu) - 127; }

}  // namespace lpir::exact
