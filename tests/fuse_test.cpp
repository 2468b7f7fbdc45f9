// fuse (III-D.2): the pixel class against the winning point's coarse label, hole-filled
// pixels, and the occlusion veto (our addition, see reference_cpu/fuse.cpp). Inputs by hand.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "reference_cpu/stages.h"
#include "tests/fuse_images.h"

namespace lpir {
namespace {

const char* Name(uint32_t c) {
  switch (c) {
    case kPixNonGround:
      return "non-ground";
    case kPixGround:
      return "ground";
    case kPixUnknown:
      return "unknown";
    case kPixVetoed:
      return "vetoed";
    case kPixBank:
      return "bank";
    case kPixUnknownOff:
      return "unknown off the coarse ground";
    default:
      return "empty";
  }
}

using Image = test::FuseImage;

// The reference's verdict on every threshold column of `images` (tests/fuse_images.h; the
// kernel runs on the same images in tests/fuse_vk_test.cpp).
void ExpectVerdicts(std::vector<test::FuseVerdicts> images) {
  for (test::FuseVerdicts& c : images) {
    Fuse(c.im.p, c.im.f);
    size_t vetoes = 0, spared = 0;
    for (const auto& [col, veto] : c.expect) {
      EXPECT_EQ(c.im.Fused(c.row, col), veto ? kPixVetoed : kPixGround)
          << c.what << ", column " << col << ": got " << Name(c.im.Fused(c.row, col));
      vetoes += veto, spared += !veto;
    }
    EXPECT_GT(vetoes, 0u) << c.what;
    EXPECT_EQ(spared > 0, c.spares) << c.what;
  }
}

TEST(Fuse, PixelClassAgainstTheCoarseLabel) {
  // Contract: agreement keeps the class; ground vs non-ground disagreement -> unknown; an unknown
  // pixel takes ground from a coarse-ground point and stays unknown otherwise; a bank is
  // non-ground that never agrees. Unknown is kPixUnknownOff where the coarse label is non-ground.
  struct Row {
    uint32_t cls;
    bool coarse;
    uint32_t want;
  };
  const Row table[] = {
      {kPixGround, true, kPixGround},     {kPixGround, false, kPixUnknownOff},
      {kPixNonGround, true, kPixUnknown}, {kPixNonGround, false, kPixNonGround},
      {kPixUnknown, true, kPixGround},    {kPixUnknown, false, kPixUnknownOff},
      {kPixBank, true, kPixUnknown},      {kPixBank, false, kPixUnknownOff},
  };
  for (uint32_t occ_rows : {0u, 2u}) {  // isolated pixels: the veto must not matter
    Image im(8, 3);
    im.p.occ_rows = occ_rows;
    // Every case on row 1 in a column of its own (the veto looks up its own column only).
    uint32_t u = 0;
    for (const Row& r : table) im.Measure(1, u++, r.cls, r.coarse);
    Fuse(im.p, im.f);
    u = 0;
    for (const Row& r : table) {
      EXPECT_EQ(im.Fused(1, u), r.want)
          << "class " << Name(r.cls) << ", coarse " << (r.coarse ? "ground" : "non-ground")
          << ", occ_rows " << occ_rows << ": got " << Name(im.Fused(1, u));
      ++u;
    }
    for (uint32_t pix = 0; pix < im.f.pixel_fused.size(); ++pix)
      if (im.f.pixel_class[pix] == kPixEmpty) {
        EXPECT_EQ(im.f.pixel_fused[pix], kPixEmpty);
      }
  }
}

TEST(Fuse, HoleFilledPixelHasNoCoarseOpinionAndIsUnknown) {
  Image im(8, 2);
  im.p.occ_rows = 0;
  im.Fill(1, 1, kPixGround);
  im.Fill(1, 3, kPixNonGround);
  im.Fill(1, 5, kPixUnknown);
  im.Fill(1, 7, kPixBank);
  Fuse(im.p, im.f);
  EXPECT_EQ(im.Fused(1, 1), kPixUnknownOff);
  EXPECT_EQ(im.Fused(1, 3), kPixUnknownOff);
  EXPECT_EQ(im.Fused(1, 5), kPixUnknownOff);
  EXPECT_EQ(im.Fused(1, 7), kPixUnknownOff);
}

// The occlusion veto: a pixel with an occluder among the occ_rows pixels above it in its column
// (nearer than range + occ_margin + occ_grade * range^2, at most range + occ_front when the pixel's
// class is ground, and higher by more than occ_rise) is non-ground.
class FuseVeto : public ::testing::Test {
 protected:
  Image im{8, 6};
  const uint32_t v = 4;  // the pixel under test sits on row 4
  const float r = 15.0f, z = -1.7f;
  float reach = 0, reach_ground = 0;  // for a pixel of any class; of class ground
  // Nearer than the pixel by so little that its ray clears that range by half occ_pass: where an
  // object's foot stands (the pass rule does not spare it).
  float foot = 0;
  void SetUp() override {
    if (im.p.occ_rows == 0) im.p.occ_rows = 2;  // the default may disable it; test the rule
    ASSERT_LE(im.p.occ_rows, v) << "the image is too short for the veto's reach";
    reach = r + im.p.occ_margin + im.p.occ_grade * r * r;
    reach_ground = std::min(reach, r + im.p.occ_front);
    foot = r * (1.0f + 0.5f * im.p.occ_pass / z);
    ASSERT_LT(foot, r);
    ASSERT_LT(reach_ground, reach) << "the defaults no longer shorten a ground pixel's reach";
  }
  // Ground pixel (class and coarse agree) at (v, u).
  void Ground(uint32_t u) { im.Measure(v, u, kPixGround, true, r, z); }
};

TEST_F(FuseVeto, NearerAndHigherPixelJustAboveVetoesGround) {
  Ground(0);
  im.Measure(v - 1, 0, kPixNonGround, false, foot, z + im.p.occ_rise + 0.1f);
  // An occluder occ_rows above, ranged just inside the reach (a ground pixel's shorter one).
  Ground(2);
  im.Measure(v - im.p.occ_rows, 2, kPixNonGround, false, reach_ground - 0.01f,
             z + im.p.occ_rise + 0.01f);
  im.Measure(v, 3, kPixUnknown, true, r, z);  // a coarse-ground seed of unknown class
  im.Measure(v - im.p.occ_rows, 3, kPixNonGround, false, reach - 0.01f, z + im.p.occ_rise + 0.01f);
  // A hole-filled occluder counts too (it is filled, with a range and a height).
  Ground(4);
  im.Fill(v - 1, 4, kPixNonGround, r, z + 1.0f);
  Fuse(im.p, im.f);
  EXPECT_EQ(im.Fused(v, 0), kPixVetoed);
  EXPECT_EQ(im.Fused(v, 2), kPixVetoed);
  EXPECT_EQ(im.Fused(v, 3), kPixVetoed);
  EXPECT_EQ(im.Fused(v, 4), kPixVetoed);
}

// An object standing at least occ_front behind a pixel of class ground leaves that pixel ground
// (it lies in front of the object, not on its face); a pixel of another class is still vetoed.
TEST_F(FuseVeto, AnObjectBehindAGroundPixelLeavesItGround) {
  const float high = z + im.p.occ_rise + 0.5f;
  Ground(0);
  im.Measure(v - 1, 0, kPixNonGround, false, reach_ground, high);  // exactly at the bound
  Ground(1);
  im.Measure(v - 1, 1, kPixNonGround, false, 0.5f * (reach_ground + reach), high);
  im.Measure(v, 2, kPixUnknown, true, r, z);
  im.Measure(v - 1, 2, kPixNonGround, false, 0.5f * (reach_ground + reach), high);
  Fuse(im.p, im.f);
  EXPECT_EQ(im.Fused(v, 0), kPixGround);
  EXPECT_EQ(im.Fused(v, 1), kPixGround);
  EXPECT_EQ(im.Fused(v, 2), kPixVetoed);
}

// A step in the ground spares an occluded pixel: the column above climbs no higher than occ_step
// (plus occ_step_grade per metre beyond the pixel) within occ_step_reach, onto a pixel of class
// ground farther away. A curb's foot stays ground; a wall's, a hedge's or a car's does not.
TEST_F(FuseVeto, AStepOntoGroundSparesTheFootOfACurb) {
  ASSERT_GE(im.p.occ_step_rows, 3u) << "the default no longer looks three rows up";
  const float curb = z + 0.5f * (im.p.occ_rise + im.p.occ_step);  // above top, below base
  // A curb: its face one row up (at the pixel's range), the sidewalk on (class ground, farther).
  Ground(0);
  im.Measure(v - 1, 0, kPixNonGround, false, r, curb);
  im.Measure(v - 2, 0, kPixGround, true, r + 0.5f, curb);
  im.Measure(v - 3, 0, kPixGround, true, r + 1.0f, curb + 0.05f);  // rising gently beyond
  // A wall: the same face, then higher than the step at the same range.
  Ground(1);
  im.Measure(v - 1, 1, kPixNonGround, false, r, curb);
  im.Measure(v - 2, 1, kPixGround, true, r + 0.5f, curb);
  im.Measure(v - 3, 1, kPixNonGround, false, r, z + im.p.occ_step + 0.3f);
  // A low step with nothing of class ground beyond it (a low box, a hedge's foot).
  Ground(2);
  im.Measure(v - 1, 2, kPixNonGround, false, r, curb);
  im.Measure(v - 2, 2, kPixUnknown, true, r + 0.5f, curb);
  // The landing beyond occ_step_reach does not count.
  Ground(3);
  im.Measure(v - 1, 3, kPixNonGround, false, r, curb);
  im.Measure(v - 2, 3, kPixGround, true, r + im.p.occ_step_reach + 0.5f, curb);
  // A class-ground pixel above, but one that rises off a car body nearer than the pixel.
  Ground(4);
  im.Measure(v - 1, 4, kPixNonGround, false, foot, z + 0.6f);
  im.Measure(v - 2, 4, kPixGround, true, r + 0.5f, curb);
  Fuse(im.p, im.f);
  EXPECT_EQ(im.Fused(v, 0), kPixGround);
  for (uint32_t u = 1; u <= 4; ++u) EXPECT_EQ(im.Fused(v, u), kPixVetoed) << "column " << u;
  im.p.occ_step_rows = 0;  // no rows looked at: the curb's foot is vetoed too
  Fuse(im.p, im.f);
  EXPECT_EQ(im.Fused(v, 0), kPixVetoed);
}

// A pixel of class ground whose ray passed the occluder's range with at least occ_pass of clearance
// (z * (range above - r) / r above the pixel's height) is ground seen under or past the object.
TEST_F(FuseVeto, GroundSeenUnderAnObjectIsNotItsFoot) {
  const float high = z + 1.0f;
  const float passed = r * (1.0f + 1.5f * im.p.occ_pass / z);  // 1.5 x the clearance needed
  ASSERT_GT(im.p.occ_pass, 0.0f);
  Ground(0);
  im.Measure(v - 1, 0, kPixNonGround, false, passed, high);  // a crown or a raised body
  im.Measure(v, 1, kPixUnknown, true, r, z);                 // a seed, but not of class ground
  im.Measure(v - 1, 1, kPixNonGround, false, passed, high);
  Ground(2);
  im.Measure(v - 1, 2, kPixNonGround, false, foot, high);
  Ground(3);  // passed under the first occluder, not the second, on its face
  im.Measure(v - 1, 3, kPixNonGround, false, passed, high);
  im.Measure(v - 2, 3, kPixNonGround, false, r, high);
  Fuse(im.p, im.f);
  EXPECT_EQ(im.Fused(v, 0), kPixGround);
  EXPECT_EQ(im.Fused(v, 1), kPixVetoed);
  EXPECT_EQ(im.Fused(v, 2), kPixVetoed);
  EXPECT_EQ(im.Fused(v, 3), kPixVetoed);
  im.p.occ_pass = 1000.0f;  // no ray passes that high: the veto holds
  Fuse(im.p, im.f);
  EXPECT_EQ(im.Fused(v, 0), kPixVetoed);
}

TEST_F(FuseVeto, VetoOverridesAnUnknownCoarseGroundSeed) {
  im.Measure(v, 0, kPixUnknown, true, r, z);  // would become ground without the veto
  im.Measure(v - 1, 0, kPixNonGround, false, r, z + 1.0f);
  Fuse(im.p, im.f);
  EXPECT_EQ(im.Fused(v, 0), kPixVetoed);
}

// The veto takes only what the vote would make ground or unknown: a pixel that class and coarse
// label both call non-ground stays non-ground under an occluder (grow never lifts it).
TEST_F(FuseVeto, AnOccludedNonGroundVoteStaysNonGround) {
  im.Measure(v, 0, kPixNonGround, false, r, z);
  im.Measure(v - 1, 0, kPixNonGround, false, r, z + 1.0f);
  im.Measure(v, 1, kPixNonGround, true, r, z);  // they disagree: unknown, so vetoed
  im.Measure(v - 1, 1, kPixNonGround, false, r, z + 1.0f);
  Fuse(im.p, im.f);
  EXPECT_EQ(im.Fused(v, 0), kPixNonGround);
  EXPECT_EQ(im.Fused(v, 1), kPixVetoed);
}

TEST_F(FuseVeto, LowerOrFartherPixelsDoNotVeto) {
  // Not higher by more than occ_rise.
  Ground(0);
  im.Measure(v - 1, 0, kPixNonGround, false, foot, z + im.p.occ_rise * 0.5f);
  // Lower.
  Ground(1);
  im.Measure(v - 1, 1, kPixNonGround, false, foot, z - 0.5f);
  // Farther than the reach (flat ground's next beam up lies there).
  Ground(2);
  im.Measure(v - 1, 2, kPixGround, true, reach + 0.05f, z + im.p.occ_rise + 0.5f);
  // Beyond occ_rows above.
  Ground(3);
  im.Measure(v - im.p.occ_rows - 1, 3, kPixNonGround, false, foot, z + 1.0f);
  // Below (rows further down are nearer; they never occlude).
  Ground(4);
  im.Measure(v + 1, 4, kPixNonGround, false, foot, z + 1.0f);
  // In the neighbouring column.
  Ground(5);
  im.Measure(v - 1, 6, kPixNonGround, false, foot, z + 1.0f);
  Fuse(im.p, im.f);
  for (uint32_t u = 0; u <= 5; ++u) EXPECT_EQ(im.Fused(v, u), kPixGround) << "column " << u;
}

TEST_F(FuseVeto, TopRowsHaveNothingAboveAndZeroRowsDisablesIt) {
  im.Measure(0, 0, kPixGround, true, r, z);  // row 0: no rows above
  Ground(1);
  im.Measure(v - 1, 1, kPixNonGround, false, foot, z + 1.0f);  // an occluder ...
  Fuse(im.p, im.f);
  EXPECT_EQ(im.Fused(0, 0), kPixGround);
  EXPECT_EQ(im.Fused(v, 1), kPixVetoed);
  im.p.occ_rows = 0;  // ... ignored once the veto is off
  Fuse(im.p, im.f);
  EXPECT_EQ(im.Fused(v, 1), kPixGround);
}

// Occluders exactly on the veto's reach and top, one ulp either side, measured or hole filled,
// and on an empty pixel: only nearer and higher than both bounds vetoes.
TEST(Fuse, VetoAtItsExactThresholds) { ExpectVerdicts(test::VetoThresholdImages()); }

// A landing and a candidate exactly on the step spare's bound and far limit, one ulp beside.
TEST(Fuse, StepSpareAtItsExactThresholds) { ExpectVerdicts(test::StepSpareThresholdImages()); }

// Occluders whose clearance is exactly occ_pass or one ulp short: only ground is passed under.
TEST(Fuse, PassedUnderAtItsExactThresholds) { ExpectVerdicts(test::PassedUnderThresholdImages()); }

}  // namespace
}  // namespace lpir
