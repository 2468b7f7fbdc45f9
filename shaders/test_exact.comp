// Runs every helper of common/exact.glsl on a batch of cases for tests/vk_exact_test.cpp, which
// compares the bits with reference_cpu/exact.h. One invocation per case i < n (push constant).
// In: binding 0 ExactCase per case. Out: binding 1, kExactOutputs uints per case (test_exact.h).
#version 450
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require

#include "common/exact.glsl"
#include "common/test_exact.h"

layout(local_size_x_id = 0) in;

layout(std430, set = 0, binding = 0) readonly buffer Cases { ExactCase cases[]; };
layout(std430, set = 0, binding = 1) writeonly buffer Results { uint results[]; };

layout(push_constant) uniform Push { uint n; } pc;

uint64_t Join(uint lo, uint hi) { return (uint64_t(hi) << 32) | uint64_t(lo); }

void Put64(uint base, int64_t v) {
  results[base] = uint(uint64_t(v));
  results[base + 1u] = uint(uint64_t(v) >> 32);
}

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= pc.n) return;
  ExactCase t = cases[i];
  float a = uintBitsToFloat(t.a), b = uintBitsToFloat(t.b);
  float c = uintBitsToFloat(t.c), s = uintBitsToFloat(t.s);
  int64_t v = int64_t(Join(t.v_lo, t.v_hi));
  uint64_t u = Join(t.u_lo, t.u_hi);
  uint base = i * uint(kExactOutputs);
  results[base + kExactOutDiv] = exact_Bits(exact_Div(a, b));
  results[base + kExactOutSqrt] = exact_Bits(exact_Sqrt(uintBitsToFloat(t.a & 0x7FFFFFFFu)));
  results[base + kExactOutKey] = exact_Key(a);
  results[base + kExactOutFromKey] = exact_Bits(exact_FromKey(t.a));
  results[base + kExactOutFtz] = exact_Bits(exact_Ftz(a));
  results[base + kExactOutExponent] = uint(exact_Exponent(a));
  results[base + kExactOutPow2] = exact_Bits(exact_Pow2(int(t.u_lo % 254u) - 126));
  results[base + kExactOutI64ToFloat] = exact_Bits(exact_I64ToFloat(v));
  Put64(base + kExactOutToFixed, exact_ToFixed(c, s));
  Put64(base + kExactOutFloorToInt, exact_FloorToInt(c));
  Put64(base + kExactOutIsqrt, int64_t(exact_Isqrt(u)));
  Put64(base + kExactOutDivToZero, exact_DivToZero(v, int64_t(u >> 2) + int64_t(1)));
  results[base + kExactOutFtz0] = exact_Bits(exact_Ftz0(a));
  precise float product = a * b;
  results[base + kExactOutMul] = exact_Bits(product);
  results[base + kExactOutFtz0Mul] = exact_Bits(exact_Ftz0(product));
}
