// a < b and a <= b for floats as IEEE compares them, decided on the bits so that a device that
// flushes subnormals or folds NaN tests away still agrees with the CPU: -0 == +0, false when
// either is NaN, subnormals compared exactly. Include it after common/exact.glsl.
#ifndef LPIR_SHADERS_COMMON_COMPARE_GLSL_
#define LPIR_SHADERS_COMMON_COMPARE_GLSL_

bool IsNan(float f) { return (floatBitsToUint(f) & 0x7FFFFFFFu) > 0x7F800000u; }

// exact_Key with -0 taken as +0: monotone, and equal for -0 and +0.
uint OrderKey(float f) {
  uint u = floatBitsToUint(f);
  return exact_Key(uintBitsToFloat((u & 0x7FFFFFFFu) == 0u ? 0u : u));
}

bool Less(float a, float b) { return !IsNan(a) && !IsNan(b) && OrderKey(a) < OrderKey(b); }
bool LessEq(float a, float b) { return !IsNan(a) && !IsNan(b) && OrderKey(a) <= OrderKey(b); }

#endif  // LPIR_SHADERS_COMMON_COMPARE_GLSL_
