// Stage 6, classify pixels (eqs. 8-12): every combination of the edge flag and the three votes
// against eq. 12 as completed in SPEC section 2, with feature values derived from the Params
// thresholds.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "reference_cpu/stages.h"

namespace lpir {
namespace {

// Eq. 12 completed (SPEC section 2), s = f_slope + f_stdz + f_stdi.
uint32_t Expected(bool edge, int s) {
  if (!edge) return s < 0 ? kPixGround : s > 0 ? kPixNonGround : kPixUnknown;
  return s > 0 ? kPixNonGround : kPixUnknown;
}

// A feature value casting `vote` under eqs. 9-11 (<= low: -1, >= high: +1, else 0).
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
    f.f_vari.assign(count, 0.0f);
  }
};

TEST(ClassifyPixels, ThresholdsAreOrdered) {
  const Params p = DefaultParams();
  EXPECT_GT(p.t_edge, 0.0f);
  EXPECT_LT(0.0f, p.t_slope_low);
  EXPECT_LT(p.t_slope_low, p.t_slope_high);
  EXPECT_LT(0.0f, p.t_stdz_low);
  EXPECT_LT(p.t_stdz_low, p.t_stdz_high);
  EXPECT_LT(0.0f, p.t_stdi_low);
  EXPECT_LT(p.t_stdi_low, p.t_stdi_high);
}

TEST(ClassifyPixels, CompletedEquation12TruthTable) {
  // 2 edge states (from the left edge, the right edge, both or none) x 27 vote combinations.
  const int edge_kinds = 4;  // 0 none, 1 left, 2 right, 3 both
  Pixels px(edge_kinds * 27);
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
      for (int b = -1; b <= 1; ++b)
        for (int c = -1; c <= 1; ++c, ++pix) {
          px.f.f_edge_l[pix] = (e & 1) ? p.t_edge * 1.5f : p.t_edge * 0.5f;
          px.f.f_edge_r[pix] = (e & 2) ? p.t_edge * 1.5f : p.t_edge * 0.5f;
          px.f.f_slope[pix] = ValueFor(a, p.t_slope_low, p.t_slope_high);
          px.f.f_varz[pix] = ValueFor(b, p.t_stdz_low, p.t_stdz_high);
          px.f.f_vari[pix] = ValueFor(c, p.t_stdi_low, p.t_stdi_high);
          cases.push_back({e != 0, a + b + c,
                           "edge kind " + std::to_string(e) + " votes " + std::to_string(a) + " " +
                               std::to_string(b) + " " + std::to_string(c)});
        }
  ClassifyPixels(p, px.f);
  ASSERT_EQ(px.f.pixel_class.size(), cases.size());
  uint32_t seen[4] = {0, 0, 0, 0};
  for (uint32_t k = 0; k < cases.size(); ++k) {
    EXPECT_EQ(px.f.pixel_class[k], Expected(cases[k].edge, cases[k].s)) << cases[k].what;
    ++seen[px.f.pixel_class[k]];
  }
  EXPECT_GT(seen[kPixGround], 0u);
  EXPECT_GT(seen[kPixNonGround], 0u);
  EXPECT_GT(seen[kPixUnknown], 0u);
  EXPECT_EQ(seen[kPixEmpty], 0u);
}

TEST(ClassifyPixels, ThresholdValuesThemselvesVote) {
  // Eqs. 8-11: edge >= t_edge is an edge; a value equal to low votes -1, equal to high votes +1.
  Pixels px(6);
  const Params& p = px.p;
  auto mid = [](float lo, float hi) { return lo + (hi - lo) * 0.5f; };
  // 0: every value exactly at its low threshold, no edge -> ground.
  px.f.f_slope[0] = p.t_slope_low, px.f.f_varz[0] = p.t_stdz_low, px.f.f_vari[0] = p.t_stdi_low;
  // 1: the same with edge_l exactly t_edge -> edge, sum -3 -> unknown.
  px.f.f_slope[1] = p.t_slope_low, px.f.f_varz[1] = p.t_stdz_low, px.f.f_vari[1] = p.t_stdi_low;
  px.f.f_edge_l[1] = p.t_edge;
  // 2: slope exactly at high, the others in the middle -> +1 -> non-ground.
  px.f.f_slope[2] = p.t_slope_high;
  px.f.f_varz[2] = mid(p.t_stdz_low, p.t_stdz_high);
  px.f.f_vari[2] = mid(p.t_stdi_low, p.t_stdi_high);
  // 3: var_z exactly at high with edge_r exactly t_edge -> non-ground.
  px.f.f_slope[3] = mid(p.t_slope_low, p.t_slope_high);
  px.f.f_varz[3] = p.t_stdz_high;
  px.f.f_vari[3] = mid(p.t_stdi_low, p.t_stdi_high);
  px.f.f_edge_r[3] = p.t_edge;
  // 4: var_i exactly at high -> non-ground.
  px.f.f_slope[4] = mid(p.t_slope_low, p.t_slope_high);
  px.f.f_varz[4] = mid(p.t_stdz_low, p.t_stdz_high);
  px.f.f_vari[4] = p.t_stdi_high;
  // 5: edges just under t_edge are no edge: all votes -1 -> ground.
  px.f.f_edge_l[5] = p.t_edge * 0.999f, px.f.f_edge_r[5] = p.t_edge * 0.999f;
  ClassifyPixels(p, px.f);
  EXPECT_EQ(px.f.pixel_class[0], kPixGround);
  EXPECT_EQ(px.f.pixel_class[1], kPixUnknown);
  EXPECT_EQ(px.f.pixel_class[2], kPixNonGround);
  EXPECT_EQ(px.f.pixel_class[3], kPixNonGround);
  EXPECT_EQ(px.f.pixel_class[4], kPixNonGround);
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
  Pixels px(4);
  const Params& p = px.p;
  const float vz_low = ValueFor(-1, p.t_stdz_low, p.t_stdz_high);
  const float vz_high = ValueFor(1, p.t_stdz_low, p.t_stdz_high);
  const float vi_low = ValueFor(-1, p.t_stdi_low, p.t_stdi_high);
  const float vi_mid = ValueFor(0, p.t_stdi_low, p.t_stdi_high);
  // 0: slope -1 (undefined), var_z +1, var_i -1: sum 0 -> unknown (were -1 a value <= low, the
  //    sum would be -1 -> ground).
  px.f.f_slope[0] = -1.0f, px.f.f_varz[0] = vz_high, px.f.f_vari[0] = vi_low;
  // 1: slope -1, var_z -1, var_i 0: sum -1 -> ground.
  px.f.f_slope[1] = -1.0f, px.f.f_varz[1] = vz_low, px.f.f_vari[1] = vi_mid;
  // 2: slope -1, var_z +1, var_i 0: sum +1 -> non-ground.
  px.f.f_slope[2] = -1.0f, px.f.f_varz[2] = vz_high, px.f.f_vari[2] = vi_mid;
  // 3: slope -1 and both variances in the middle: sum 0 -> unknown.
  px.f.f_slope[3] = -1.0f;
  px.f.f_varz[3] = ValueFor(0, p.t_stdz_low, p.t_stdz_high);
  px.f.f_vari[3] = vi_mid;
  ClassifyPixels(p, px.f);
  EXPECT_EQ(px.f.pixel_class[0], kPixUnknown);
  EXPECT_EQ(px.f.pixel_class[1], kPixGround);
  EXPECT_EQ(px.f.pixel_class[2], kPixNonGround);
  EXPECT_EQ(px.f.pixel_class[3], kPixUnknown);
}

}  // namespace
}  // namespace lpir
