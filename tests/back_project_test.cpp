// back_project (III-D.2): every point's final label and why, from its pixel's label,
// the winner gates and its own coarse label. Inputs by hand.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "reference_cpu/exact.h"
#include "reference_cpu/stages.h"

namespace lpir {
namespace {

// Pixels on one row; AddPoint() appends a point, Win() makes it its pixel's winner and gives the
// pixel its features (range = Sqrt(r2), height = z_t, as feature_maps does).
struct Scene {
  Params p = DefaultParams();
  Frame f;
  explicit Scene(uint32_t width) {
    p.width = width;
    p.beams = 1;
    f.pixel_point.assign(width, kNone);
    f.pixel_label.assign(width, kPixEmpty);
    f.f_range.assign(width, 0.0f);
    f.f_height.assign(width, 0.0f);
  }
  uint32_t AddPoint(uint32_t flags, uint32_t pix, float range, float z, bool coarse) {
    f.flags.push_back(flags);
    f.point_pixel.push_back(flags & kPointValid ? pix : kNone);
    f.r2.push_back(flags & kPointValid ? range * range : 0.0f);
    f.zt.push_back(flags & kPointValid ? z : 0.0f);
    f.coarse.push_back(coarse ? 1u : 0u);
    return f.n++;
  }
  uint32_t Win(uint32_t pix, uint32_t label, float range, float z, bool coarse) {
    const uint32_t i = AddPoint(kPointValid, pix, range, z, coarse);
    f.pixel_point[pix] = i;
    f.pixel_label[pix] = label;
    f.f_range[pix] = exact::Sqrt(f.r2[i]);
    f.f_height[pix] = z;
    return i;
  }
  void Run() { BackProject(p, f); }
};

TEST(BackProject, InvalidAndNoisePointsAreNonGround) {
  Scene s(4);
  s.Win(0, kPixGround, 10.0f, -1.7f, true);
  const uint32_t invalid = s.AddPoint(0u, 0, 0.0f, 0.0f, true);
  // A noise point got a pixel (a ground one) but never competed for it.
  const uint32_t noise = s.AddPoint(kPointValid | kPointNoise, 0, 10.0f, -1.7f, true);
  s.Run();
  EXPECT_EQ(s.f.label[invalid], 0u);
  EXPECT_EQ(s.f.why[invalid], kWhyInvalid);
  EXPECT_EQ(s.f.label[noise], 0u);
  EXPECT_EQ(s.f.why[noise], kWhyNoise);
  EXPECT_EQ(s.f.label[0], 1u);
}

TEST(BackProject, TheWinnerTakesThePixelLabel) {
  Scene s(4);
  // The coarse label of a winner does not matter: the pixel's label is final.
  const uint32_t a = s.Win(0, kPixGround, 10.0f, -1.7f, false);
  const uint32_t b = s.Win(1, kPixNonGround, 10.0f, -1.7f, true);
  const uint32_t c = s.Win(2, kPixGround, 30.0f, -1.2f, true);
  const uint32_t d = s.Win(3, kPixNonGround, 12.0f, 0.5f, false);
  s.Run();
  EXPECT_EQ(s.f.label[a], 1u);
  EXPECT_EQ(s.f.why[a], kWhyGround);
  EXPECT_EQ(s.f.label[b], 0u);
  EXPECT_EQ(s.f.why[b], kWhyNonGround);
  EXPECT_EQ(s.f.label[c], 1u);
  EXPECT_EQ(s.f.label[d], 0u);
  EXPECT_EQ(s.f.why[d], kWhyNonGround);
}

TEST(BackProject, LoserWithinTheGatesTakesThePixelLabel) {
  Scene s(2);
  const float r = 10.0f, z = -1.7f;
  const float dr = 0.5f * s.p.bp_range_gate, dz = 0.5f * s.p.bp_height_gate;
  s.Win(0, kPixGround, r, z, true);
  s.Win(1, kPixNonGround, r, z, false);
  // Losers of the ground pixel, their own coarse label disagreeing: they take ground.
  const uint32_t g1 = s.AddPoint(kPointValid, 0, r + dr, z + dz, false);
  const uint32_t g2 = s.AddPoint(kPointValid, 0, r + dr, z - dz, false);
  // Losers of the non-ground pixel with coarse ground: they take non-ground.
  const uint32_t n1 = s.AddPoint(kPointValid, 1, r + dr, z + dz, true);
  const uint32_t n2 = s.AddPoint(kPointValid, 1, r, z - dz, true);
  s.Run();
  for (uint32_t i : {g1, g2}) {
    EXPECT_EQ(s.f.label[i], 1u) << "point " << i;
    EXPECT_EQ(s.f.why[i], kWhyGround) << "point " << i;
  }
  for (uint32_t i : {n1, n2}) {
    EXPECT_EQ(s.f.label[i], 0u) << "point " << i;
    EXPECT_EQ(s.f.why[i], kWhyNonGround) << "point " << i;
  }
}

TEST(BackProject, LoserOutsideTheGatesIsGroundOnlyWhenItsCoarseLabelAndThePixelAgree) {
  // Contract: outside either gate a lost point is ground only when both its own coarse label and
  // the pixel's label say ground.
  Scene s(2);
  const float r = 10.0f, z = -1.7f;
  const float far_r = r + 2.0f * s.p.bp_range_gate, high_z = z + 2.0f * s.p.bp_height_gate;
  s.Win(0, kPixGround, r, z, true);
  s.Win(1, kPixNonGround, r, z, true);
  struct Case {
    uint32_t pix;
    float range, z;
    bool coarse;
    uint8_t want;
    const char* what;
  };
  const Case cases[] = {
      {0, far_r, z, true, 1, "beyond the range gate, coarse ground, pixel ground"},
      {0, far_r, z, false, 0, "beyond the range gate, coarse non-ground, pixel ground"},
      {0, r, high_z, true, 1, "beyond the height gate, coarse ground, pixel ground"},
      {0, r, high_z, false, 0, "beyond the height gate, coarse non-ground, pixel ground"},
      {0, far_r, high_z, false, 0, "beyond both gates, coarse non-ground, pixel ground"},
      {1, far_r, z, true, 0, "beyond the range gate, coarse ground, pixel non-ground"},
      {1, r, high_z, true, 0, "beyond the height gate, coarse ground, pixel non-ground"},
      {1, far_r, high_z, false, 0, "beyond both gates, coarse non-ground, pixel non-ground"},
  };
  const uint32_t first = s.f.n;
  for (const Case& c : cases) s.AddPoint(kPointValid, c.pix, c.range, c.z, c.coarse);
  s.Run();
  for (uint32_t k = 0; k < sizeof(cases) / sizeof(cases[0]); ++k) {
    EXPECT_EQ(s.f.label[first + k], cases[k].want) << cases[k].what;
    EXPECT_EQ(s.f.why[first + k], cases[k].want ? kWhyGround : kWhyNonGround) << cases[k].what;
  }
}

TEST(BackProject, GatesAreMeasuredOnPlanarRangeAndCorrectedHeight) {
  // A nearer point below the winner within both gates, the range compared as Sqrt(r2) of each.
  Scene s(1);
  const float r = 20.0f, z = -1.7f;
  s.Win(0, kPixGround, r, z, true);
  const uint32_t in = s.AddPoint(kPointValid, 0, r - 0.9f * s.p.bp_range_gate,
                                 z - 0.9f * s.p.bp_height_gate, false);
  const uint32_t out = s.AddPoint(kPointValid, 0, r - 1.1f * s.p.bp_range_gate, z, false);
  const uint32_t out_z = s.AddPoint(kPointValid, 0, r, z - 1.1f * s.p.bp_height_gate, false);
  s.Run();
  EXPECT_EQ(s.f.label[in], 1u);
  EXPECT_EQ(s.f.label[out], 0u);
  EXPECT_EQ(s.f.label[out_z], 0u);
}

TEST(BackProject, EveryPointGetsOneLabelAndOneReason) {
  Scene s(3);
  s.Win(0, kPixGround, 10.0f, -1.7f, true);
  s.Win(1, kPixNonGround, 11.0f, -1.0f, false);
  s.AddPoint(0u, 0, 0, 0, false);
  s.AddPoint(kPointValid | kPointNoise, 2, 30.0f, -3.0f, false);
  s.AddPoint(kPointValid, 0, 10.05f, -1.69f, false);
  s.Run();
  ASSERT_EQ(s.f.label.size(), s.f.n);
  ASSERT_EQ(s.f.why.size(), s.f.n);
  for (uint32_t i = 0; i < s.f.n; ++i) {
    EXPECT_LE(s.f.label[i], 1u);
    EXPECT_EQ(s.f.label[i] == 1, s.f.why[i] == kWhyGround) << "point " << i;
  }
}

// label_why packs bit 0 the label and bits 1-2 the why: non-ground 0, ground 3, invalid 4, noise
// 6 (what the GPU writes and a frame downloads, one byte a point).
TEST(BackProject, LabelWhyPacksLabelAndReasonInOneByte) {
  Scene s(3);
  s.Win(0, kPixGround, 10.0f, -1.7f, true);
  s.Win(1, kPixNonGround, 11.0f, -1.0f, false);
  const uint32_t invalid = s.AddPoint(0u, 0, 0, 0, false);
  const uint32_t noise = s.AddPoint(kPointValid | kPointNoise, 2, 30.0f, -3.0f, false);
  s.Run();
  ASSERT_EQ(s.f.label_why.size(), s.f.n);
  EXPECT_EQ(s.f.label_why[0], 3u);  // the winner of the ground pixel
  EXPECT_EQ(s.f.label_why[1], 0u);  // the winner of the non-ground pixel
  EXPECT_EQ(s.f.label_why[invalid], 4u);
  EXPECT_EQ(s.f.label_why[noise], 6u);
  for (uint32_t i = 0; i < s.f.n; ++i) {
    EXPECT_EQ(s.f.label_why[i], PackLabelWhy(s.f.label[i], s.f.why[i])) << "point " << i;
    EXPECT_EQ(LabelOf(s.f.label_why[i]), s.f.label[i]) << "point " << i;
    EXPECT_EQ(WhyOf(s.f.label_why[i]), s.f.why[i]) << "point " << i;
  }
}

}  // namespace
}  // namespace lpir
