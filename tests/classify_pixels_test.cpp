// classify_pixels (eqs. 8-12): every combination of the edge flag and the two votes
// against eq. 12 as completed in docs/spec.md, Readings of the paper (eq. 11's intensity vote taken
// as -1), with feature values derived from the Params thresholds.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "reference_cpu/stages.h"

namespace lpir {
namespace {

// Eq. 12 completed (docs/spec.md, Readings of the paper), s = f_slope + f_stdz + f_stdi with f_stdi
// = -1.
uint32_t Expected(bool edge, int s) {
  if (!edge) return s < 0 ? kPixGround : s > 0 ? kPixNonGround : kPixUnknown;
  return s > 0 ? kPixNonGround : kPixUnknown;
}

// A feature value casting `vote` under eqs. 9-10 (<= low: -1, >= high: +1, else 0).
float ValueFor(int vote, float low, float high) {
  if (vote < 0) return low * 0.5f;
  if (vote > 0) return high * 2.0f;
  return low + (high - low) * 0.5f;
}

struct Pixels {
  Params p = DefaultParams();
  Frame f;
  explicit Pixels(uint32_t count) {
    p.width = count;
    p.beams = 1;
    f.pixel_filled.assign(count, 1u);
    f.f_edge_l.assign(count, 0.0f);
    f.f_edge_r.assign(count, 0.0f);
    f.f_slope.assign(count, 0.0f);
    f.f_varz.assign(count, 0.0f);
  }
};

TEST(ClassifyPixels, ThresholdsAreOrdered) {
  const Params p = DefaultParams();
  EXPECT_GT(p.t_edge, 0.0f);
  EXPECT_LT(0.0f, p.t_slope_low);
  EXPECT_LT(p.t_slope_low, p.t_slope_high);
  EXPECT_LT(0.0f, p.t_stdz_low);
  EXPECT_LT(p.t_stdz_low, p.t_stdz_high);
}

TEST(ClassifyPixels, CompletedEquation12TruthTable) {
  // 2 edge states (from the left edge, the right edge, both or none) x 9 vote combinations; banks
  // off (bank_slope 0), so that eq. 12's non-ground shows.
  const int edge_kinds = 4;  // 0 none, 1 left, 2 right, 3 both
  Pixels px(edge_kinds * 9);
  px.p.bank_slope = 0.0f;
  const Params& p = px.p;
  struct Case {
    bool edge;
    int s;
    std::string what;
  };
  std::vector<Case> cases;
  uint32_t pix = 0;
  for (int e = 0; e < edge_kinds; ++e)
    for (int a = -1; a <= 1; ++a)
      for (int b = -1; b <= 1; ++b, ++pix) {
        px.f.f_edge_l[pix] = (e & 1) ? p.t_edge * 1.5f : p.t_edge * 0.5f;
        px.f.f_edge_r[pix] = (e & 2) ? p.t_edge * 1.5f : p.t_edge * 0.5f;
        px.f.f_slope[pix] = ValueFor(a, p.t_slope_low, p.t_slope_high);
        px.f.f_varz[pix] = ValueFor(b, p.t_stdz_low, p.t_stdz_high);
        cases.push_back({e != 0, a + b - 1,
                         "edge kind " + std::to_string(e) + " votes " + std::to_string(a) + " " +
                             std::to_string(b)});
      }
  ClassifyPixels(p, px.f);
  ASSERT_EQ(px.f.pixel_class.size(), cases.size());
  uint32_t seen[8] = {};
  for (uint32_t k = 0; k < cases.size(); ++k) {
    EXPECT_EQ(px.f.pixel_class[k], Expected(cases[k].edge, cases[k].s)) << cases[k].what;
    ++seen[px.f.pixel_class[k]];
  }
  EXPECT_GT(seen[kPixGround], 0u);
  EXPECT_GT(seen[kPixNonGround], 0u);
  EXPECT_GT(seen[kPixUnknown], 0u);
  EXPECT_EQ(seen[kPixEmpty], 0u);
}

TEST(ClassifyPixels, ANonGroundPixelSmoothAndNotTooSteepIsABank) {
  // Every pixel votes non-ground (slope and var_z over their high thresholds, no edge); a bank
  // when slope < bank_slope and var_z < bank_rough, both strict.
  Pixels px(6);
  const Params& p = px.p;
  ASSERT_LT(p.t_slope_high, p.bank_slope);
  ASSERT_LT(p.t_stdz_high, p.bank_rough);
  const float slope_mid = 0.5f * (p.t_slope_high + p.bank_slope);
  const float varz_mid = 0.5f * (p.t_stdz_high + p.bank_rough);
  const float slopes[6] = {slope_mid, p.bank_slope, slope_mid, slope_mid, 10.0f, p.t_slope_high};
  const float varzs[6] = {varz_mid, varz_mid, p.bank_rough, 1.0f, varz_mid, p.t_stdz_high};
  const uint32_t want[6] = {kPixBank,      kPixNonGround, kPixNonGround,
                            kPixNonGround, kPixNonGround, kPixBank};
  for (uint32_t k = 0; k < 6; ++k) px.f.f_slope[k] = slopes[k], px.f.f_varz[k] = varzs[k];
  ClassifyPixels(p, px.f);
  for (uint32_t k = 0; k < 6; ++k) EXPECT_EQ(px.f.pixel_class[k], want[k]) << "pixel " << k;
}

TEST(ClassifyPixels, ThresholdValuesThemselvesVote) {
  // Eqs. 8-10: edge >= t_edge is an edge; a value equal to low votes -1, equal to high votes +1
  // (banks off).
  Pixels px(6);
  px.p.bank_slope = 0.0f;
  const Params& p = px.p;
  // 0: every value exactly at its low threshold, no edge -> ground.
  px.f.f_slope[0] = p.t_slope_low, px.f.f_varz[0] = p.t_stdz_low;
  // 1: the same with edge_l exactly t_edge -> edge, sum -3 -> unknown.
  px.f.f_slope[1] = p.t_slope_low, px.f.f_varz[1] = p.t_stdz_low;
  px.f.f_edge_l[1] = p.t_edge;
  // 2: slope and var_z exactly at high -> +1 -> non-ground.
  px.f.f_slope[2] = p.t_slope_high, px.f.f_varz[2] = p.t_stdz_high;
  // 3: the same with edge_r exactly t_edge -> non-ground.
  px.f.f_slope[3] = p.t_slope_high, px.f.f_varz[3] = p.t_stdz_high;
  px.f.f_edge_r[3] = p.t_edge;
  // 4: slope exactly at high, var_z at low: sum -1 -> ground.
  px.f.f_slope[4] = p.t_slope_high, px.f.f_varz[4] = p.t_stdz_low;
  // 5: edges just under t_edge are no edge: all votes -1 -> ground.
  px.f.f_edge_l[5] = p.t_edge * 0.999f, px.f.f_edge_r[5] = p.t_edge * 0.999f;
  ClassifyPixels(p, px.f);
  EXPECT_EQ(px.f.pixel_class[0], kPixGround);
  EXPECT_EQ(px.f.pixel_class[1], kPixUnknown);
  EXPECT_EQ(px.f.pixel_class[2], kPixNonGround);
  EXPECT_EQ(px.f.pixel_class[3], kPixNonGround);
  EXPECT_EQ(px.f.pixel_class[4], kPixGround);
  EXPECT_EQ(px.f.pixel_class[5], kPixGround);
}

TEST(ClassifyPixels, EmptyPixelsStayEmpty) {
  Pixels px(4);
  // Features that would vote ground (all zero, no edge), but the pixels were never measured.
  px.f.pixel_filled = {0u, 1u, 2u, 0u};
  ClassifyPixels(px.p, px.f);
  EXPECT_EQ(px.f.pixel_class[0], kPixEmpty);
  EXPECT_EQ(px.f.pixel_class[1], kPixGround);
  EXPECT_EQ(px.f.pixel_class[2], kPixGround);  // a hole-filled pixel is classified like any other
  EXPECT_EQ(px.f.pixel_class[3], kPixEmpty);
}

TEST(ClassifyPixels, UndefinedSlopeVotesZero) {
  Pixels px(3);
  const Params& p = px.p;
  // 0: slope -1 (undefined), var_z +1: sum 0 -> unknown (were -1 a value <= low, the sum would be
  //    -1 -> ground).
  px.f.f_slope[0] = -1.0f, px.f.f_varz[0] = ValueFor(1, p.t_stdz_low, p.t_stdz_high);
  // 1: slope -1, var_z -1: sum -2 -> ground.
  px.f.f_slope[1] = -1.0f, px.f.f_varz[1] = ValueFor(-1, p.t_stdz_low, p.t_stdz_high);
  // 2: slope -1, var_z 0: sum -1 -> ground (were +1 a value >= high, the sum would be 0 ->
  //    unknown).
  px.f.f_slope[2] = -1.0f, px.f.f_varz[2] = ValueFor(0, p.t_stdz_low, p.t_stdz_high);
  ClassifyPixels(p, px.f);
  EXPECT_EQ(px.f.pixel_class[0], kPixUnknown);
  EXPECT_EQ(px.f.pixel_class[1], kPixGround);
  EXPECT_EQ(px.f.pixel_class[2], kPixGround);
}

}  // namespace
}  // namespace lpir
