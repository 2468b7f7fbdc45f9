// The shared exact helpers: ordered keys, correctly rounded division and square root (checked
// against double precision, where the float result must be the nearest float), integer sqrt.
#include "reference_cpu/exact.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <limits>
#include <random>

namespace lpir::exact {
namespace {

TEST(Exact, KeyIsMonotoneAndInvertible) {
  const float values[] = {-1e30f, -3.5f, -1.0f, -1e-30f, -0.0f, 0.0f, 1e-30f, 0.5f, 2.0f, 1e30f};
  for (size_t i = 0; i + 1 < std::size(values); ++i) {
    EXPECT_LT(Key(values[i]), Key(values[i + 1])) << values[i] << " vs " << values[i + 1];
    EXPECT_EQ(Bits(FromKey(Key(values[i]))), Bits(values[i]));
  }
}

// The float nearest to `exact` (ties to even), the definition of a correctly rounded result.
bool IsNearestFloat(float got, double exact) {
  const double d = std::fabs(double(got) - exact);
  const double up = std::fabs(double(std::nextafter(got, INFINITY)) - exact);
  const double down = std::fabs(double(std::nextafter(got, -INFINITY)) - exact);
  return d <= up && d <= down;
}

TEST(Exact, DivAndSqrtAreCorrectlyRounded) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> mant(1.0f, 2.0f);
  std::uniform_int_distribution<int> expo(-40, 40);
  for (int k = 0; k < 200000; ++k) {
    const float a = std::ldexp(mant(rng), expo(rng)), b = std::ldexp(mant(rng), expo(rng));
    const float q = Div(a, b);
    ASSERT_TRUE(IsNearestFloat(q, double(a) / double(b))) << a << " / " << b;
    const float s = Sqrt(a);
    ASSERT_TRUE(IsNearestFloat(s, std::sqrt(double(a)))) << "sqrt " << a;
  }
}

TEST(Exact, SubnormalsFlushToZero) {
  EXPECT_EQ(Div(1e-30f, 1e10f), 0.0f);
  EXPECT_EQ(Sqrt(1e-40f), 0.0f);
}

// Ftz0: subnormals, FLT_MIN and -0, of either sign, become +0 (bits 0); every other value, the
// next float above FLT_MIN, NaN and the infinities included, is kept bit for bit.
TEST(Exact, Ftz0FlushesToPositiveZero) {
  for (uint32_t bits : {0x00000001u, 0x007FFFFFu, 0x80000001u, 0x807FFFFFu, 0x80000000u, 0u,
                        0x00800000u, 0x80800000u})
    EXPECT_EQ(Bits(Ftz0(FromBits(bits))), 0u) << std::hex << bits;
  for (uint32_t bits : {0x00800001u, 0x80800001u, 0x3F800000u, 0xBF800000u, 0x7F7FFFFFu,
                        0x7F800000u, 0xFF800000u, 0x7FC00000u, 0xFFC00001u})
    EXPECT_EQ(Bits(Ftz0(FromBits(bits))), bits) << std::hex << bits;
}

TEST(Exact, IsqrtIsFloorOfSquareRoot) {
  std::mt19937_64 rng(3);
  for (int k = 0; k < 100000; ++k) {
    const uint64_t v = rng() >> (rng() % 64);
    const uint64_t r = Isqrt(v);
    ASSERT_LE(static_cast<unsigned __int128>(r) * r, v);
    ASSERT_GT(static_cast<unsigned __int128>(r + 1) * (r + 1), v);
  }
  EXPECT_EQ(Isqrt(0), 0u);
  EXPECT_EQ(Isqrt(~uint64_t(0)), 4294967295u);
}

// int64 -> float rounded to nearest even in integer steps, as the shader mirror does it: the
// independent reference for the CPU helper.
float I64ToFloatByIntegers(int64_t v) {
  const uint64_t sign = v < 0 ? 0x80000000u : 0u;
  uint64_t m = v < 0 ? uint64_t(0) - uint64_t(v) : uint64_t(v);
  if (m < (uint64_t(1) << 24)) return static_cast<float>(v);  // exact: no rounding to check
  int shift = 0;
  while ((m >> shift) >= (uint64_t(1) << 24)) ++shift;
  uint64_t q = m >> shift;
  const uint64_t rem = m & ((uint64_t(1) << shift) - 1), half = uint64_t(1) << (shift - 1);
  if (rem > half || (rem == half && (q & 1))) ++q;
  if (q == (uint64_t(1) << 24)) q >>= 1, ++shift;
  return FromBits(uint32_t(sign | (uint64_t(23 + shift + 127) << 23) | (q & 0x7FFFFFu)));
}

TEST(Exact, I64ToFloatRoundsToNearestEven) {
  std::mt19937_64 rng(11);
  for (int k = 0; k < 200000; ++k) {
    const int64_t v = int64_t(rng() >> (rng() % 63)) * (k % 2 ? 1 : -1);
    ASSERT_EQ(Bits(I64ToFloat(v)), Bits(I64ToFloatByIntegers(v))) << v;
  }
  EXPECT_EQ(I64ToFloat((int64_t(1) << 24) + 1), 16777216.0f);  // tie to even
  EXPECT_EQ(I64ToFloat((int64_t(1) << 24) + 3), 16777220.0f);  // tie to even (up)
}

TEST(Exact, FloorToIntMatchesFloor) {
  const float values[] = {-2.5f, -2.0f, -0.5f, -0.0f, 0.0f, 0.5f, 1.0f, 7.99f, -1e7f, 3e9f};
  for (float y : values) EXPECT_EQ(FloorToInt(y), int64_t(std::floor(y))) << y;
}

TEST(Exact, DivToZeroAndToFixed) {
  EXPECT_EQ(DivToZero(-7, 2), -3);
  EXPECT_EQ(DivToZero(7, 2), 3);
  EXPECT_EQ(ToFixed(1.2345f, 1000.0f), 1235);  // 1234.5 rounds half up
  EXPECT_EQ(ToFixed(-1.2344f, 1000.0f), -1234);
  EXPECT_EQ(Pow2(-3), 0.125f);
  EXPECT_EQ(Exponent(10.0f), 3);
}

// The int32 path gives ToFixed's integer wherever it does not flag the value, and flags only
// values whose integer lies at or beyond 2^30 (there its callers take ToFixed's int64 path).
TEST(Exact, ToFixed32IsToFixedWithinItsRangeAndFlagsBeyond) {
  std::mt19937 rng(31);
  std::uniform_real_distribution<float> metres(-120000.0f, 120000.0f);  // x 1e4: beyond 2^30
  uint32_t flagged = 0;
  for (int k = 0; k < 200000; ++k) {
    const float x = metres(rng);
    uint32_t bad = 0;
    const int32_t q = ToFixed32(x, 10000.0f, bad);
    const int64_t want = ToFixed(x, 10000.0f);
    if (bad) {
      ++flagged;
      EXPECT_EQ(q, 0) << x;
      EXPECT_GE(std::llabs(want), (int64_t(1) << 30) - 1) << x;
    } else {
      EXPECT_EQ(q, want) << x;
    }
  }
  EXPECT_GT(flagged, 0u);
  EXPECT_LT(flagged, 200000u);
  uint32_t bad = 0;
  EXPECT_EQ(ToFixed32(std::numeric_limits<float>::infinity(), 1.0f, bad), 0);
  EXPECT_EQ(bad, 1u);
}

}  // namespace
}  // namespace lpir::exact
