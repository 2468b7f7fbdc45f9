// The GLSL exact helpers (shaders/common/exact.glsl, run by shaders/test_exact.comp) against
// their C++ originals (reference_cpu/exact.h), bit for bit, on ~1e6 random and edge-case inputs:
// zeros, subnormals, huge values, powers of two, ties, the subnormal and overflow boundaries.
#include <gtest/gtest.h>

#include <algorithm>
#include <cinttypes>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "host/vk/buffer.h"
#include "host/vk/command_buffer.h"
#include "host/vk/fence.h"
#include "host/vk/kernel.h"
#include "reference_cpu/exact.h"
#include "shaders/common/test_exact.h"
#include "tests/vk_exact_run.h"
#include "tests/vk_test_util.h"

namespace lpir {
namespace {

using exact::Bits;
using exact::FromBits;

uint64_t Join(uint32_t lo, uint32_t hi) { return (uint64_t(hi) << 32) | lo; }

// The CPU results of one case, laid out as the shader writes them.
void Expected(const ExactCase& t, uint32_t* out) {
  const float a = FromBits(t.a), b = FromBits(t.b), c = FromBits(t.c), s = FromBits(t.s);
  const int64_t v = int64_t(Join(t.v_lo, t.v_hi));
  const uint64_t u = Join(t.u_lo, t.u_hi);
  auto put64 = [&](int slot, int64_t x) {
    out[slot] = uint32_t(uint64_t(x));
    out[slot + 1] = uint32_t(uint64_t(x) >> 32);
  };
  out[kExactOutDiv] = Bits(exact::Div(a, b));
  out[kExactOutSqrt] = Bits(exact::Sqrt(FromBits(t.a & 0x7FFFFFFFu)));
  out[kExactOutKey] = exact::Key(a);
  out[kExactOutFromKey] = Bits(exact::FromKey(t.a));
  out[kExactOutFtz] = Bits(exact::Ftz(a));
  out[kExactOutExponent] = uint32_t(exact::Exponent(a));
  out[kExactOutPow2] = Bits(exact::Pow2(int(t.u_lo % 254u) - 126));
  out[kExactOutI64ToFloat] = Bits(exact::I64ToFloat(v));
  put64(kExactOutToFixed, exact::ToFixed(c, s));
  put64(kExactOutFloorToInt, exact::FloorToInt(c));
  put64(kExactOutIsqrt, int64_t(exact::Isqrt(u)));
  // DivToZero negates its numerator: INT64_MIN is outside its domain (signed overflow in C++).
  put64(kExactOutDivToZero,
        v == std::numeric_limits<int64_t>::min() ? 0 : exact::DivToZero(v, int64_t(u >> 2) + 1));
  out[kExactOutFtz0] = Bits(exact::Ftz0(a));
  out[kExactOutMul] = Bits(a * b);
  out[kExactOutFtz0Mul] = Bits(exact::Ftz0(a * b));
}

bool IsNan(uint32_t bits) { return (bits & 0x7F800000u) == 0x7F800000u && (bits & 0x7FFFFFu); }

// The cases: random bit patterns, typical magnitudes, the edges, and families aimed at the
// rounding paths (subnormal boundary of Div, overflow, perfect squares, conversion ties).
class CaseMaker {
 public:
  explicit CaseMaker(uint32_t seed) : rng_(seed) {}

  uint32_t AnyFloat() {  // any bit pattern but Inf/NaN: every exponent, subnormals included
    uint32_t u;
    do u = uint32_t(rng_());
    while ((u & 0x7F800000u) == 0x7F800000u);
    return u;
  }
  uint32_t Typical(int lo, int hi) {  // random mantissa and sign, exponent in [lo, hi]
    const int e = lo + int(rng_() % uint32_t(hi - lo + 1));
    return (uint32_t(rng_()) & 0x807FFFFFu) | (uint32_t(e + 127) << 23);
  }
  uint32_t Edge() {
    static const uint32_t kEdges[] = {
        0x00000000u, 0x80000000u, 0x00000001u, 0x807FFFFFu, 0x007FFFFFu, 0x00400000u,
        0x00800000u, 0x80800000u, 0x00800001u, 0x00FFFFFFu, 0x7F7FFFFFu, 0xFF7FFFFFu,
        0x7F000000u, 0x3F800000u, 0xBF800000u, 0x3F800001u, 0x3F7FFFFFu, 0x3FFFFFFFu,
        0x40000000u, 0x3F000000u, 0x40400000u, 0x3EAAAAABu, 0x4B000000u, 0x4B7FFFFFu,
        0x4B800000u, 0xCB000001u, 0x5E800000u, 0x5F000000u, 0x7F800000u, 0xFF800000u,
        0x7FC00000u, 0x33800000u, 0x34000000u, 0x0C000000u, 0x1F800000u, 0x20000000u};
    return kEdges[rng_() % (sizeof(kEdges) / sizeof(kEdges[0]))];
  }
  uint32_t PowerOfTwo() { return (uint32_t(rng_()) & 0x80000000u) | ((1 + rng_() % 254) << 23); }

  int64_t AnyInt64() {
    const uint64_t m = rng_() >> (rng_() % 64);
    return (rng_() & 1) ? -int64_t(m >> 1) : int64_t(m >> 1);
  }
  int64_t Int64Tie() {  // m = q * 2^s + 2^(s-1): exactly between two floats
    const int s = 1 + int(rng_() % 39);
    const uint64_t q = (uint64_t(1) << 23) | (rng_() & 0x7FFFFFu);
    const uint64_t m = (q << s) | (uint64_t(1) << (s - 1));
    return (rng_() & 1) ? -int64_t(m) : int64_t(m);
  }
  uint64_t AnyUint64() { return rng_() >> (rng_() % 64); }

  ExactCase Make(uint64_t k) {
    ExactCase t{};
    switch (k % 8) {
      case 0:  // anything finite
        t.a = AnyFloat(), t.b = AnyFloat();
        break;
      case 1:  // everyday magnitudes
        t.a = Typical(-30, 30), t.b = Typical(-30, 30);
        break;
      case 2:  // edges against anything
        t.a = (rng_() & 1) ? Edge() : AnyFloat(), t.b = (rng_() & 1) ? Edge() : AnyFloat();
        break;
      case 3: {  // a / b close to 2^-126: rounding on the subnormal grid, ties, the flush
        const int ea = 1 + int(rng_() % 100), d = 125 + int(rng_() % 4);
        t.a = Typical(ea - 127, ea - 127);
        t.b = (rng_() & 1) ? ((rng_() % 2) << 31) | (uint32_t(ea + d) << 23)  // exact quotient
                           : Typical(ea + d - 127, ea + d - 127);
        if (rng_() % 4 == 0) t.a = (t.a & 0xFF800000u) | (0x7FFFFFu - uint32_t(rng_() % 4));
        break;
      }
      case 4: {  // a / b close to the largest float: rounding into Inf
        const int eb = 1 + int(rng_() % 120), d = 126 + int(rng_() % 3);
        t.a = Typical(std::min(eb + d, 254) - 127, std::min(eb + d, 254) - 127);
        t.b = Typical(eb - 127, eb - 127);
        break;
      }
      case 5: {  // perfect squares and their neighbours (sqrt), exact quotients (div)
        const uint32_t root = 1 + uint32_t(rng_() % 4096);
        t.a = Bits(float(root * root)) + uint32_t(int(rng_() % 3) - 1);
        t.b = (rng_() & 1) ? Bits(float(root)) : PowerOfTwo();
        break;
      }
      case 6: {  // squares of random floats: sqrt close to a representable value
        const float x = FromBits(Typical(-60, 60) & 0x7FFFFFFFu);
        t.a = Bits(x * x);
        t.b = Bits(x);
        break;
      }
      default:  // powers of two and subnormals
        t.a = (rng_() & 1) ? PowerOfTwo() : (uint32_t(rng_()) & 0x807FFFFFu);
        t.b = (rng_() & 1) ? PowerOfTwo() : AnyFloat();
        break;
    }
    if (t.b == 0u || t.b == 0x80000000u) t.b = (k % 16 == 0) ? t.b : 0x3F800000u;  // some a / 0

    // ToFixed / FloorToInt: |c| < 2^61 and |c * s| < 2^61.
    static const float kScales[] = {1.0f, 10.0f, 100.0f, 1000.0f, 1e4f, 16384.0f, 0.5f, 1.0f / 3};
    float c;
    switch (k % 5) {
      case 0:
        c = float(int(rng_() % 20001) - 10000) * 0.25f;  // halves: ties of +0.5
        break;
      case 1:
        c = FromBits(Typical(-40, 60));
        break;
      case 2:
        c = FromBits(uint32_t(rng_()) & 0x807FFFFFu);  // subnormal or zero
        break;
      case 3:
        c = FromBits(Typical(20, 26));  // around 2^23: integers and not
        break;
      default:
        c = FromBits(Typical(-10, 10));
        break;
    }
    float s = (k % 3 == 0) ? FromBits(Typical(-10, 20) & 0x7FFFFFFFu)
                           : kScales[rng_() % (sizeof(kScales) / sizeof(kScales[0]))];
    if (!(std::fabs(double(c) * double(s)) < 0x1p61)) s = 1.0f;
    t.c = Bits(c), t.s = Bits(s);

    int64_t v;
    switch (k % 4) {
      case 0:
        v = Int64Tie();
        break;
      case 1: {
        static const int64_t kInts[] = {0,
                                        1,
                                        -1,
                                        (int64_t(1) << 24) - 1,
                                        int64_t(1) << 24,
                                        (int64_t(1) << 24) + 1,
                                        (int64_t(1) << 24) + 3,
                                        -((int64_t(1) << 25) + 2),
                                        (int64_t(1) << 25) + 6,
                                        std::numeric_limits<int64_t>::max(),
                                        std::numeric_limits<int64_t>::min(),
                                        std::numeric_limits<int64_t>::min() + 1,
                                        (int64_t(1) << 62) + (int64_t(1) << 38),
                                        int64_t(0xFFFFFFFFll),
                                        int64_t(0x100000000ll)};
        v = kInts[rng_() % (sizeof(kInts) / sizeof(kInts[0]))];
        break;
      }
      default:
        v = AnyInt64();
        break;
    }
    t.v_lo = uint32_t(uint64_t(v)), t.v_hi = uint32_t(uint64_t(v) >> 32);

    uint64_t u;
    switch (k % 6) {
      case 0: {
        const uint64_t r = rng_() >> (32 + rng_() % 32);  // perfect squares and neighbours
        u = r * r + uint64_t(int64_t(rng_() % 3) - 1);
        break;
      }
      case 1:
        u = (rng_() & 1) ? ~uint64_t(0) : uint64_t(rng_() % 4);
        break;
      default:
        u = AnyUint64();
        break;
    }
    t.u_lo = uint32_t(u), t.u_hi = uint32_t(u >> 32);
    return t;
  }

 private:
  std::mt19937_64 rng_;
};

const char* SlotName(int slot) {
  switch (slot) {
    case kExactOutDiv:
      return "Div(a, b)";
    case kExactOutSqrt:
      return "Sqrt(|a|)";
    case kExactOutKey:
      return "Key(a)";
    case kExactOutFromKey:
      return "FromKey(a)";
    case kExactOutFtz:
      return "Ftz(a)";
    case kExactOutExponent:
      return "Exponent(a)";
    case kExactOutPow2:
      return "Pow2(u_lo % 254 - 126)";
    case kExactOutI64ToFloat:
      return "I64ToFloat(v)";
    case kExactOutToFixed:
      return "ToFixed(c, s)";
    case kExactOutFloorToInt:
      return "FloorToInt(c)";
    case kExactOutIsqrt:
      return "Isqrt(u)";
    case kExactOutDivToZero:
      return "DivToZero(v, (u >> 2) + 1)";
    case kExactOutFtz0:
      return "Ftz0(a)";
    case kExactOutMul:
      return "a * b";
    case kExactOutFtz0Mul:
      return "Ftz0(a * b)";
    default:
      return "?";
  }
}

std::string FloatText(uint32_t bits) {
  char text[64];
  std::snprintf(text, sizeof(text), "%.9g (0x%08x)", double(FromBits(bits)), bits);
  return text;
}

std::string CaseText(const ExactCase& t) {
  char text[320];
  const int64_t v = int64_t(Join(t.v_lo, t.v_hi));
  const uint64_t u = Join(t.u_lo, t.u_hi);
  std::snprintf(text, sizeof(text),
                "a %s, b %s, c %s, s %s, v %" PRId64 " (0x%016" PRIx64 "), u %" PRIu64
                " (0x%016" PRIx64 ")",
                FloatText(t.a).c_str(), FloatText(t.b).c_str(), FloatText(t.c).c_str(),
                FloatText(t.s).c_str(), v, uint64_t(v), u, u);
  return text;
}

class VkExact : public test::VkTest {};

TEST_F(VkExact, EveryHelperMatchesTheCpuBitForBit) {
  constexpr uint32_t kCases = 1u << 20;  // 1,048,576
  std::vector<ExactCase> cases(kCases);
  CaseMaker maker(20250801);
  for (uint32_t k = 0; k < kCases; ++k) cases[k] = maker.Make(k);

  std::vector<uint32_t> gpu_out;
  ASSERT_NO_FATAL_FAILURE(test::RunTestExact(device(), cases, 64, &gpu_out, nullptr));
  const uint32_t* gpu = gpu_out.data();
  uint64_t compared = 0, mismatches = 0;
  uint64_t per_slot[kExactOutputs] = {};
  for (uint32_t k = 0; k < kCases; ++k) {
    uint32_t cpu[kExactOutputs];
    Expected(cases[k], cpu);
    const uint32_t* got = gpu + uint64_t(k) * kExactOutputs;
    for (int slot = 0; slot < kExactOutputs;) {
      const bool wide = slot >= kExactOutToFixed && slot <= kExactOutDivToZero;
      const int width = wide ? 2 : 1;
      ++compared;
      ++per_slot[slot];
      bool same = cpu[slot] == got[slot] && (!wide || cpu[slot + 1] == got[slot + 1]);
      if (slot == kExactOutDivToZero && Join(cases[k].v_lo, cases[k].v_hi) == (uint64_t(1) << 63))
        same = true;  // outside DivToZero's domain
      const bool float_result = slot == kExactOutDiv || slot == kExactOutSqrt ||
                                slot == kExactOutMul || slot == kExactOutFtz0Mul;
      if (!same && float_result && IsNan(cpu[slot]) && IsNan(got[slot]))
        same = true;  // NaN payloads are not part of the contract
      auto tiny = [](uint32_t bits) { return (bits & 0x7F800000u) == 0u && (bits << 1) != 0u; };
      const bool tiny_operand = tiny(cases[k].a) || tiny(cases[k].b);
      // The exact product (exact in double: 24 x 24 bits) below FLT_MIN: a device that flushes
      // may do so even where IEEE rounding gives FLT_MIN (tininess detected before rounding).
      const bool tiny_product =
          std::fabs(double(FromBits(cases[k].a)) * double(FromBits(cases[k].b))) < 0x1p-126;
      if (!same && slot == kExactOutMul && (tiny_operand || tiny_product))
        same = true;  // subnormal operands or product: the device's mode decides
      if (!same && slot == kExactOutFtz0Mul && tiny_operand)
        same = true;  // subnormal operands, which no stage multiplies
      if (!same && ++mismatches <= 20) {
        const std::string cpu_text =
            wide ? std::to_string(int64_t(Join(cpu[slot], cpu[slot + 1]))) : FloatText(cpu[slot]);
        const std::string gpu_text =
            wide ? std::to_string(int64_t(Join(got[slot], got[slot + 1]))) : FloatText(got[slot]);
        ADD_FAILURE() << "exact: " << SlotName(slot) << " differs at case " << k << ": CPU "
                      << cpu_text << ", GPU " << gpu_text << "; inputs " << CaseText(cases[k]);
      }
      slot += width;
    }
  }
  std::printf("[exact] %u cases, %llu values compared (%llu per helper), %llu mismatches\n", kCases,
              static_cast<unsigned long long>(compared),
              static_cast<unsigned long long>(per_slot[0]),
              static_cast<unsigned long long>(mismatches));
  EXPECT_EQ(mismatches, 0u);
}

// A workgroup larger than the device allows is the device's largest, and the dispatch still
// covers every invocation (a case count that is no multiple of it): the same words as with 64.
TEST_F(VkExact, AnOversizedWorkgroupIsTheDevicesLargest) {
  CaseMaker maker(7);
  std::vector<ExactCase> cases(3001);
  for (uint32_t k = 0; k < cases.size(); ++k) cases[k] = maker.Make(k);
  const VkPhysicalDeviceLimits& limits = device().limits();
  std::vector<uint32_t> small, large;
  uint32_t used = 0;
  ASSERT_NO_FATAL_FAILURE(test::RunTestExact(device(), cases, 64, &small, nullptr));
  ASSERT_NO_FATAL_FAILURE(test::RunTestExact(device(), cases, 1u << 20, &large, &used));
  EXPECT_EQ(used,
            std::min(limits.maxComputeWorkGroupSize[0], limits.maxComputeWorkGroupInvocations));
  ASSERT_EQ(small.size(), large.size());
  size_t differ = 0;
  for (size_t k = 0; k < small.size(); ++k) differ += small[k] != large[k];
  EXPECT_EQ(differ, 0u) << differ << " of " << small.size() << " words differ";
}

// The rounding paths need the inputs above to reach them: check that they do (a silent change
// of the generator must not hollow the test out).
TEST(VkExactCases, ReachTheRoundingPaths) {
  CaseMaker maker(20250801);
  int div_to_min_normal = 0, div_flushed = 0, div_inf = 0, i64_ties = 0, fixed_ties = 0;
  for (uint32_t k = 0; k < (1u << 20); ++k) {
    const ExactCase t = maker.Make(k);
    const float a = exact::Ftz(FromBits(t.a)), b = exact::Ftz(FromBits(t.b));
    const uint32_t q = Bits(exact::Div(FromBits(t.a), FromBits(t.b)));
    if (b != 0.0f && a != 0.0f && std::isfinite(a) && std::isfinite(b)) {
      const double exact_q = std::fabs(double(a) / double(b));
      if ((q & 0x7FFFFFFFu) == 0x00800000u && exact_q < 0x1p-126) ++div_to_min_normal;
      if ((q & 0x7FFFFFFFu) == 0u && exact_q > 0x1p-127) ++div_flushed;
      if ((q & 0x7FFFFFFFu) == 0x7F800000u) ++div_inf;
    }
    const int64_t v = int64_t(Join(t.v_lo, t.v_hi));
    const uint64_t m = v < 0 ? uint64_t(0) - uint64_t(v) : uint64_t(v);
    if (m >= (uint64_t(1) << 25) && (m & (m - 1)) != 0) {
      const int shift = (63 - __builtin_clzll(m)) - 23;
      if ((m & ((uint64_t(1) << shift) - 1)) == (uint64_t(1) << (shift - 1))) ++i64_ties;
    }
    const float y = FromBits(t.c) * FromBits(t.s);
    if (y + 0.5f == std::floor(y + 0.5f) && y != std::floor(y)) ++fixed_ties;
  }
  std::printf(
      "[exact cases] Div rounded up to 2^-126: %d, flushed from above 2^-127: %d, overflowed: %d; "
      "I64ToFloat ties: %d; ToFixed ties: %d\n",
      div_to_min_normal, div_flushed, div_inf, i64_ties, fixed_ties);
  EXPECT_GT(div_to_min_normal, 10);
  EXPECT_GT(div_flushed, 1000);
  EXPECT_GT(div_inf, 1000);
  EXPECT_GT(i64_ties, 1000);
  EXPECT_GT(fixed_ties, 1000);
}

}  // namespace
}  // namespace lpir
