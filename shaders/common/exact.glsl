// The GLSL mirror of reference_cpu/exact.h, function for function: exact::F there is exact_F
// here, and both sides produce the same bits for the same inputs (tests/vk_exact_test.cpp checks
// it on ~1e6 inputs). Include it before any declaration (it enables 64-bit integers).
//
// Division and square root are correctly rounded by integer arithmetic (Vulkan promises correct
// rounding only for add, sub and mul): mantissas and exponents taken apart, a 64-bit integer
// quotient or integer square root with its remainder as sticky bit, round to nearest even, the
// result put back together. Subnormal inputs and results are flushed to signed zero as the CPU
// side does with exact::Ftz around IEEE `/` and `sqrt` (a result that IEEE rounds up from the
// subnormal range to 2^-126 survives the flush on both sides). Nothing here depends on how the
// device treats subnormal floats: every subnormal is handled as bits.
#ifndef LPIR_SHADERS_COMMON_EXACT_GLSL_
#define LPIR_SHADERS_COMMON_EXACT_GLSL_

#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require

uint exact_Bits(float f) { return floatBitsToUint(f); }
float exact_FromBits(uint u) { return uintBitsToFloat(u); }

// Flushes subnormals to (signed) zero.
float exact_Ftz(float f) {
  uint u = exact_Bits(f);
  return (u & 0x7F800000u) == 0u ? exact_FromBits(u & 0x80000000u) : f;
}

// Every value of magnitude at most FLT_MIN (subnormals, +-0, +-FLT_MIN) as +0, by its bits:
// wherever a stage's float result may be subnormal, so that a device that flushes it (to either
// zero, tininess detected before or after rounding) agrees with one that keeps it.
float exact_Ftz0(float f) { return (exact_Bits(f) & 0x7FFFFFFFu) <= 0x00800000u ? 0.0 : f; }
vec4 exact_Ftz0(vec4 f) {
  return mix(f, vec4(0.0),
             lessThanEqual(floatBitsToUint(f) & uvec4(0x7FFFFFFFu), uvec4(0x00800000u)));
}

// Monotone map float -> uint: a < b (as floats, -0 < +0) iff Key(a) < Key(b).
uint exact_Key(float f) {
  uint u = exact_Bits(f);
  return (u & 0x80000000u) != 0u ? ~u : (u | 0x80000000u);
}
float exact_FromKey(uint k) {
  return exact_FromBits((k & 0x80000000u) != 0u ? (k & 0x7FFFFFFFu) : ~k);
}

// Not in exact.h (its callers round inside IEEE operations): q / 2^shift rounded to nearest even,
// `sticky` when the exact value has non-zero bits below q. 1 <= shift <= 63.
uint64_t exact_RoundShift_(uint64_t q, int shift, bool sticky) {
  uint64_t kept = q >> shift;
  uint64_t rem = q & ((uint64_t(1) << shift) - uint64_t(1));
  uint64_t halfway = uint64_t(1) << (shift - 1);
  bool up = rem > halfway || (rem == halfway && (sticky || (kept & uint64_t(1)) != uint64_t(0)));
  return up ? kept + uint64_t(1) : kept;
}

// Correctly rounded a / b for finite a and finite non-zero b (subnormals flushed). Outside that
// contract: IEEE's infinities and zeros (a / +-0 = +-Inf, finite / Inf = +-0, Inf / finite =
// +-Inf); NaN results are a quiet NaN whose payload may differ from the CPU's.
float exact_Div(float a, float b) {
  uint ua = exact_Bits(exact_Ftz(a)), ub = exact_Bits(exact_Ftz(b));
  uint sign = (ua ^ ub) & 0x80000000u;
  uint ea = (ua >> 23) & 0xFFu, eb = (ub >> 23) & 0xFFu;
  bool a_nan = ea == 255u && (ua & 0x7FFFFFu) != 0u, b_nan = eb == 255u && (ub & 0x7FFFFFu) != 0u;
  if (a_nan || b_nan || (ea == 255u && eb == 255u) || (ea == 0u && eb == 0u))
    return exact_FromBits(0x7FC00000u);
  if (ea == 255u || eb == 0u) return exact_FromBits(sign | 0x7F800000u);  // Inf / x, x / 0
  if (ea == 0u || eb == 255u) return exact_FromBits(sign);                // 0 / x, x / Inf

  uint64_t ma = uint64_t((ua & 0x7FFFFFu) | 0x800000u), mb = uint64_t((ub & 0x7FFFFFu) | 0x800000u);
  // a / b = (ma / mb) * 2^(ea - eb) = q_exact * 2^(ea - eb - 40), q_exact in (2^39, 2^41).
  uint64_t num = ma << 40;
  uint64_t q = num / mb;
  bool sticky = num - q * mb != uint64_t(0);
  int top = q >= (uint64_t(1) << 40) ? 40 : 39;
  int shift = top - 23;                            // keeps 24 bits
  int e = int(ea) - int(eb) + (top - 40) + 127;    // biased exponent of the result
  if (e >= 1) {
    uint64_t m = exact_RoundShift_(q, shift, sticky);
    if (m == (uint64_t(1) << 24)) {
      m >>= 1;
      ++e;
    }
    if (e >= 255) return exact_FromBits(sign | 0x7F800000u);  // overflow rounds to Inf
    return exact_FromBits(sign | (uint(e) << 23) | (uint(m) & 0x7FFFFFu));
  }
  // Below 2^-126 IEEE rounds on the subnormal grid (steps of 2^-149): q_exact * 2^(e - top + 22)
  // steps. Ftz then keeps only a result that rounded up to 2^-126 (2^23 steps).
  int steps_shift = shift + 1 - e;
  if (steps_shift > 63) return exact_FromBits(sign);
  uint64_t steps = exact_RoundShift_(q, steps_shift, sticky);
  return exact_FromBits(steps >= (uint64_t(1) << 23) ? (sign | 0x800000u) : sign);
}

// floor(sqrt(v)), exact for every v. The same value as exact.h's bit-by-bit loop, computed
// another way (docs/decisions/exact.md): the device's float square root
// as a guess g (error under 2^12 for any square root within a few ulp, as Vulkan requires), one
// Newton step g + (v - g^2) / 2g with the exact residual and a float quotient (within 2 of the
// root), then integer checks that step to the exact value.
uint64_t exact_Isqrt(uint64_t v) {
  if (v == uint64_t(0)) return uint64_t(0);
  int64_t g = clamp(int64_t(sqrt(float(v))), int64_t(1), int64_t(0xFFFFFFFFu));
  int64_t residual = int64_t(v - uint64_t(g * g));  // |residual| < 2^45
  int64_t s = g + int64_t(float(residual) / (2.0 * float(g)));
  s = clamp(s, int64_t(0), int64_t(0xFFFFFFFFu));  // floor(sqrt(v)) <= 2^32 - 1
  uint64_t r = uint64_t(s);
  while (r * r > v) --r;
  while (r < uint64_t(0xFFFFFFFFu) && (r + uint64_t(1)) * (r + uint64_t(1)) <= v) ++r;
  return r;
}
// Correctly rounded sqrt(a) for finite a >= 0 (subnormals flushed; sqrt(-0) = -0). Outside that
// contract: sqrt(+Inf) = +Inf, a quiet NaN for negative or NaN a.
float exact_Sqrt(float a) {
  uint u = exact_Bits(exact_Ftz(a));
  if ((u & 0x7FFFFFFFu) == 0u) return exact_FromBits(u);  // +-0
  uint ex = (u >> 23) & 0xFFu;
  if ((u & 0x80000000u) != 0u || (ex == 255u && (u & 0x7FFFFFu) != 0u))
    return exact_FromBits(0x7FC00000u);
  if (ex == 255u) return a;  // +Inf
  // a = m * 2^e2 with e2 even, m < 2^25; sqrt(a) = sqrt(m * 2^38) * 2^(e2 / 2 - 19).
  uint64_t m = uint64_t((u & 0x7FFFFFu) | 0x800000u);
  int e2 = int(ex) - 150;
  if ((e2 & 1) != 0) {
    m <<= 1;
    --e2;
  }
  uint64_t big = m << 38;  // < 2^63
  uint64_t s = exact_Isqrt(big);  // in [2^30, 2^32)
  bool sticky = big != s * s;
  int top = findMSB(uint(s));
  int shift = top - 23;
  uint64_t r = exact_RoundShift_(s, shift, sticky);
  int e = top + (e2 >> 1) - 19 + 127;  // e2 even: the shift divides exactly
  if (r == (uint64_t(1) << 24)) {
    r >>= 1;
    ++e;
  }
  return exact_FromBits((uint(e) << 23) | (uint(r) & 0x7FFFFFu));
}

// floor(y) as an integer, exactly, for |y| < 2^62. Subnormals by their bits (floor is -1 for a
// negative one, 0 for a positive one), so a device that flushes them agrees with the CPU.
int64_t exact_FloorToInt(float y) {
  uint u = exact_Bits(y);
  if ((u & 0x7F800000u) == 0u)
    return ((u & 0x80000000u) != 0u && (u & 0x7FFFFFu) != 0u) ? int64_t(-1) : int64_t(0);
  return int64_t(floor(y));
}

// round(x * scale) to int64 as floor(x * scale + 0.5), each step one rounded float op; |x * scale|
// must stay below 2^62 (callers clamp).
int64_t exact_ToFixed(float x, float scale) {
  precise float y = x * scale;
  precise float z = y + 0.5;
  return exact_FloorToInt(z);
}

// Integer division of a signed numerator by a positive denominator, rounding toward zero, done on
// magnitudes only (shader integer division is only portable for non-negative operands).
int64_t exact_DivToZero(int64_t num, int64_t den) {
  uint64_t mag = num < int64_t(0) ? uint64_t(0) - uint64_t(num) : uint64_t(num);
  uint64_t q = mag / uint64_t(den);
  return num < int64_t(0) ? -int64_t(q) : int64_t(q);
}

// int64 -> float, rounded to nearest even by integer operations (Vulkan leaves the rounding of an
// inexact conversion to the device).
float exact_I64ToFloat(int64_t v) {
  uint sign = v < int64_t(0) ? 0x80000000u : 0u;
  uint64_t m = v < int64_t(0) ? uint64_t(0) - uint64_t(v) : uint64_t(v);
  if (m < (uint64_t(1) << 24)) return float(int(v));  // exact
  uint hi = uint(m >> 32);
  int top = hi != 0u ? 32 + findMSB(hi) : findMSB(uint(m));
  int shift = top - 23;  // the top bit to bit 23
  uint64_t q = exact_RoundShift_(m, shift, false);
  if (q == (uint64_t(1) << 24)) {
    q >>= 1;
    ++shift;
  }
  // value = q * 2^shift with q in [2^23, 2^24): exponent 23 + shift
  return exact_FromBits(sign | (uint(23 + shift + 127) << 23) | (uint(q) & 0x7FFFFFu));
}

// 2^e as a float, exactly, for -126 <= e <= 127.
float exact_Pow2(int e) { return exact_FromBits(uint(e + 127) << 23); }

// The unbiased exponent of a normal float (floor(log2(|f|))).
int exact_Exponent(float f) { return int((exact_Bits(f) >> 23) & 0xFFu) - 127; }

#endif  // LPIR_SHADERS_COMMON_EXACT_GLSL_
