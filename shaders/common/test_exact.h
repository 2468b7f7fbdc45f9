// The input and output layout of shaders/test_exact.comp, which runs every helper of
// shaders/common/exact.glsl for tests/vk_exact_test.cpp. Valid GLSL and C++ (scalars only).
#ifndef LPIR_SHADERS_COMMON_TEST_EXACT_H_
#define LPIR_SHADERS_COMMON_TEST_EXACT_H_

#ifdef __cplusplus
#include <cstdint>
namespace lpir {
using uint = uint32_t;
#endif

// One test case: float bit patterns and two 64-bit integers as (lo, hi) halves.
struct ExactCase {
  uint a;     // Div numerator; Sqrt (of |a|), Key, FromKey, Ftz, Ftz0, Exponent argument
  uint b;     // Div denominator; Mul's second factor
  uint c;     // ToFixed x and FloorToInt argument (|c * s| and |c| below 2^62)
  uint s;     // ToFixed scale
  uint v_lo;  // I64ToFloat argument, DivToZero numerator
  uint v_hi;
  uint u_lo;  // Isqrt argument; DivToZero denominator (u >> 2) + 1; Pow2 exponent u_lo % 254 - 126
  uint u_hi;
};

// Results: kExactOutputs uints per case, in this order.
#define kExactOutDiv 0          // Bits(Div(a, b))
#define kExactOutSqrt 1         // Bits(Sqrt(|a|))
#define kExactOutKey 2          // Key(a)
#define kExactOutFromKey 3      // Bits(FromKey(a))
#define kExactOutFtz 4          // Bits(Ftz(a))
#define kExactOutExponent 5     // uint(Exponent(a))
#define kExactOutPow2 6         // Bits(Pow2(u_lo % 254 - 126))
#define kExactOutI64ToFloat 7   // Bits(I64ToFloat(v))
#define kExactOutToFixed 8      // ToFixed(c, s): lo, hi
#define kExactOutFloorToInt 10  // FloorToInt(c): lo, hi
#define kExactOutIsqrt 12       // Isqrt(u): lo, hi
#define kExactOutDivToZero 14   // DivToZero(v, (u >> 2) + 1): lo, hi
#define kExactOutFtz0 16        // Bits(Ftz0(a))
#define kExactOutMul 17         // Bits(a * b), the device's own product: shows its denormal mode
#define kExactOutFtz0Mul 18     // Bits(Ftz0(a * b)): what a stage stores, the same on every device
#define kExactOutputs 19

#ifdef __cplusplus
static_assert(sizeof(ExactCase) == 32, "ExactCase is 8 uints (std430)");
}  // namespace lpir
#endif

#endif  // LPIR_SHADERS_COMMON_TEST_EXACT_H_
