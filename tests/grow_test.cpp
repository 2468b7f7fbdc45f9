// grow (Alg. 1, IV-A): region growing from ground seeds through unknown pixels, its
// schedule independence against an independent Jacobi fixed point, and the connectivity
// constraint. Inputs (pixel_fused and the feature maps) by hand.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "reference_cpu/stages.h"
#include "tests/grow_images.h"

namespace lpir {
namespace {

using Image = test::GrowImage;

// The height change one step between neighbours q and r may make (contract: grow_dz +
// grow_grade * (|dr| + min(r_q, r_r) * column_arc when the column changes): symmetric).
float Allowed(const Params& p, const Frame& f, uint32_t q, uint32_t r) {
  float step = std::fabs(f.f_range[r] - f.f_range[q]);
  if (r % p.width != q % p.width) step = step + std::min(f.f_range[q], f.f_range[r]) * p.column_arc;
  return p.grow_dz + p.grow_grade * step;
}

TEST(Grow, StopsAtAHeightStep) {
  // One row of unknown pixels between empty rows; a seed at column 2. Going right: small steps,
  // then a height jump at column 7; going left: a drop between columns 1 and 0.
  const uint32_t w = 16;
  Image im(w, 3);
  im.p.min_component = 0;
  const float allowed = im.p.grow_dz + im.p.grow_grade * (10.0f * im.p.column_arc);
  const float small = 0.4f * im.p.grow_dz;
  float z = -1.7f;
  for (uint32_t u = 0; u < w; ++u) {
    if (u == 7) z += allowed + 0.02f;  // too high a step
    im.Set(1, u, kPixUnknown, z);
    z += small;
  }
  im.Set(1, 0, kPixUnknown, im.f.f_height[im.Pix(1, 0)] - allowed - 0.02f);
  im.Set(1, 2, kPixGround, im.f.f_height[im.Pix(1, 2)]);
  im.Run();
  for (uint32_t u = 0; u < w; ++u) {
    const bool ground = u >= 1 && u <= 6;
    EXPECT_EQ(im.Grown(1, u), ground ? kPixGround : kPixNonGround) << "column " << u;
  }
  // The empty rows stay empty; no unknown survives.
  for (uint32_t u = 0; u < w; ++u) {
    EXPECT_EQ(im.Grown(0, u), kPixEmpty);
    EXPECT_EQ(im.Grown(2, u), kPixEmpty);
  }
}

TEST(Grow, StepsWithinTheThresholdsAllGrow) {
  // Changes just under the limit (height 0.99 of the allowance) grow;
  // non-ground and empty pixels block.
  Image im(8, 1);
  im.p.min_component = 0;
  const float allowed = im.p.grow_dz + im.p.grow_grade * (10.0f * im.p.column_arc);
  im.Set(0, 0, kPixGround, -1.7f);
  im.Set(0, 1, kPixUnknown, -1.7f + 0.99f * allowed);
  im.Set(0, 2, kPixUnknown, -1.7f);    // a step back down from column 1: still allowed
  im.Set(0, 3, kPixNonGround, -1.7f);  // non-ground blocks
  im.Set(0, 4, kPixUnknown, -1.7f);
  im.Set(0, 5, kPixEmpty, -1.7f);  // empty blocks
  im.Set(0, 6, kPixUnknown, -1.7f);
  im.Set(0, 7, kPixEmpty, -1.7f);
  im.Run();
  EXPECT_EQ(im.Grown(0, 1), kPixGround);
  EXPECT_EQ(im.Grown(0, 2), kPixGround);
  EXPECT_EQ(im.Grown(0, 3), kPixNonGround);
  EXPECT_EQ(im.Grown(0, 4), kPixNonGround);
  EXPECT_EQ(im.Grown(0, 5), kPixEmpty);
  EXPECT_EQ(im.Grown(0, 6), kPixNonGround);
}

TEST(Grow, GrowsAcrossTheColumnWrapAndDiagonally) {
  const uint32_t w = 10;
  Image im(w, 4);
  im.p.min_component = 0;
  // Seed at (1, 0); column 1 is non-ground, so the only way is left across the wrap: (1, 9),
  // then diagonally down to (2, 8), then (3, 7).
  im.Set(1, 0, kPixGround, -1.7f);
  im.Set(1, 1, kPixNonGround, -1.7f);
  im.Set(1, 9, kPixUnknown, -1.7f);
  im.Set(2, 8, kPixUnknown, -1.7f);
  im.Set(3, 7, kPixUnknown, -1.7f);
  im.Set(3, 2, kPixUnknown, -1.7f);  // unreachable: (2,1) (2,2) (2,3) are empty
  im.Run();
  EXPECT_EQ(im.Grown(1, 9), kPixGround);
  EXPECT_EQ(im.Grown(2, 8), kPixGround);
  EXPECT_EQ(im.Grown(3, 7), kPixGround);
  EXPECT_EQ(im.Grown(3, 2), kPixNonGround);
  EXPECT_EQ(im.Grown(1, 1), kPixNonGround);
}

TEST(Grow, GradeTermCountsTheStepLength) {
  // With grow_grade > 0 a step across columns far from the sensor may climb more than one at the
  // same range change near it (the planar step includes r * column_arc).
  Image im(64, 1);
  im.p.min_component = 0;
  im.p.grow_grade = 0.05f;
  const float near_r = 5.0f, far_r = 60.0f;
  const float climb = im.p.grow_dz + im.p.grow_grade * (30.0f * im.p.column_arc);
  ASSERT_GT(im.p.grow_dz + im.p.grow_grade * far_r * im.p.column_arc, climb);
  ASSERT_LT(im.p.grow_dz + im.p.grow_grade * near_r * im.p.column_arc, climb);
  im.Set(0, 0, kPixGround, -1.7f, near_r);
  im.Set(0, 1, kPixUnknown, -1.7f + climb, near_r);
  im.Set(0, 10, kPixGround, -1.7f, far_r);
  im.Set(0, 11, kPixUnknown, -1.7f + climb, far_r);
  im.Run();
  EXPECT_EQ(im.Grown(0, 1), kPixNonGround);
  EXPECT_EQ(im.Grown(0, 11), kPixGround);
}

TEST(Grow, APixelOffTheCoarseGroundIsClimbedUpItsColumnAtTheBanksGrade) {
  // Columns 0, 2, 4, 6, 8 apart (empty between them); each a seed and unknown pixels above or
  // below it. The bank's step: up its column, to a pixel farther and no lower, rising at most
  // grow_dz + bank_slope * (range difference), where either pixel is kPixUnknownOff.
  Image im(10, 4);
  im.p.min_component = 0;
  const float z = -1.7f, rise_max = im.p.grow_dz + im.p.bank_slope * 1.0f;  // per metre farther
  // 0: climbs one row (rise within the grade), not the next (too steep).
  im.Set(3, 0, kPixGround, z, 10.0f);
  im.Set(2, 0, kPixUnknownOff, z + 0.9f * rise_max, 11.0f);
  im.Set(1, 0, kPixUnknownOff, z + 0.9f * rise_max + 1.1f * rise_max, 12.0f);
  // 2: the same rise, but the pixel's coarse label is ground (kPixUnknown): only the flat step.
  im.Set(3, 2, kPixGround, z, 10.0f);
  im.Set(2, 2, kPixUnknown, z + 0.9f * rise_max, 11.0f);
  // 4: nearer than the seed (an object's face): no climb.
  im.Set(3, 4, kPixGround, z, 10.0f);
  im.Set(2, 4, kPixUnknownOff, z + 0.5f, 9.0f);
  // 6: farther but lower (ground seen past an object's top): no climb.
  im.Set(3, 6, kPixGround, z, 10.0f);
  im.Set(2, 6, kPixUnknownOff, z - 0.2f, 11.0f);
  // 8: the seed above, the bank below it: the step is the same edge, taken from either end.
  im.Set(1, 8, kPixGround, z + 0.5f, 12.0f);
  im.Set(2, 8, kPixUnknownOff, z, 11.0f);
  im.Run();
  EXPECT_EQ(im.Grown(2, 0), kPixGround);
  EXPECT_EQ(im.Grown(1, 0), kPixNonGround);
  EXPECT_EQ(im.Grown(2, 2), kPixNonGround);
  EXPECT_EQ(im.Grown(2, 4), kPixNonGround);
  EXPECT_EQ(im.Grown(2, 6), kPixNonGround);
  EXPECT_EQ(im.Grown(2, 8), kPixGround);
}

TEST(Grow, StepTestIsSymmetric) {
  // A step across columns between a near and a far pixel is allowed or not whichever of the two is
  // the seed (the arc term takes the nearer range), so growing is the components of an
  // undirected graph. The climb fits the far pixel's arc but not the near one's.
  const float near_r = 5.0f, far_r = 60.0f;
  for (int seed_far = 0; seed_far < 2; ++seed_far)
    for (float climb_share : {0.5f, 2.0f}) {
      Image im(64, 1);
      im.p.min_component = 0;
      im.p.grow_grade = 0.05f;
      const float near_allowed =
          im.p.grow_dz + im.p.grow_grade * (far_r - near_r + near_r * im.p.column_arc);
      const float climb = climb_share < 1.0f
                              ? 0.9f * near_allowed
                              : near_allowed + 0.5f * im.p.grow_grade * far_r * im.p.column_arc;
      im.Set(0, 0, seed_far ? kPixGround : kPixUnknown, -1.7f, far_r);
      im.Set(0, 1, seed_far ? kPixUnknown : kPixGround, -1.7f + climb, near_r);
      im.Run();
      EXPECT_EQ(im.Grown(0, seed_far ? 1 : 0), climb_share < 1.0f ? kPixGround : kPixNonGround)
          << "seed " << (seed_far ? "far" : "near") << ", climb " << climb;
    }
}

// The bank's step (contract) from pixel lo up to pixel up, the one above it in its column, where
// either is kPixUnknownOff: up farther, no lower, rising at most grow_dz + bank_slope * (r_up -
// r_lo), each float op rounded as the contract has it.
bool BankStepAllowed(const Params& p, const Frame& f, uint32_t up, uint32_t lo) {
  if (f.pixel_fused[up] != kPixUnknownOff && f.pixel_fused[lo] != kPixUnknownOff) return false;
  const float d = f.f_range[up] - f.f_range[lo];
  const float rise = f.f_height[up] - f.f_height[lo];
  const float allowed = p.grow_dz + p.bank_slope * d;
  return d > 0.0f && rise >= 0.0f && rise <= allowed;
}

bool IsUnknown(uint32_t c) { return c == kPixUnknown || c == kPixUnknownOff; }

// The independent Jacobi schedule: every sweep reads the previous sweep's labels only; an unknown
// pixel with a ground 8-neighbour (columns wrap, rows do not) whose step passes, or whose bank's
// step passes (the neighbour straight above or below), becomes ground; repeat until nothing
// changes; left-over unknowns are non-ground.
std::vector<uint32_t> JacobiGrow(const Params& p, const Frame& f) {
  const int w = int(p.width), h = int(p.beams);
  std::vector<uint32_t> cur = f.pixel_fused;
  for (bool changed = true; changed;) {
    changed = false;
    std::vector<uint32_t> next = cur;
    for (int v = 0; v < h; ++v)
      for (int u = 0; u < w; ++u) {
        const uint32_t r = uint32_t(v * w + u);
        if (!IsUnknown(cur[r])) continue;
        for (int dv = -1; dv <= 1 && IsUnknown(next[r]); ++dv)
          for (int du = -1; du <= 1; ++du) {
            if ((dv == 0 && du == 0) || v + dv < 0 || v + dv >= h) continue;
            const uint32_t q = uint32_t((v + dv) * w + (u + du + w) % w);
            if (cur[q] != kPixGround) continue;
            const bool bank =
                du == 0 && (dv < 0 ? BankStepAllowed(p, f, q, r) : BankStepAllowed(p, f, r, q));
            if (std::fabs(f.f_height[r] - f.f_height[q]) <= Allowed(p, f, q, r) || bank) {
              next[r] = kPixGround;
              changed = true;
              break;
            }
          }
      }
    cur.swap(next);
  }
  for (uint32_t& c : cur)
    if (IsUnknown(c)) c = kPixNonGround;
  return cur;
}

// A random label image of the classes fuse gives (tests/grow_images.h).
Image RandomImage(uint32_t seed, float grow_grade) {
  return test::RandomGrowImage(seed, grow_grade, {8, 48, 2, 16}, false);
}

TEST(Grow, EqualsTheJacobiFixedPointOnRandomImages) {
  uint32_t grown_total = 0, seeds_total = 0;
  for (float grade : {DefaultParams().grow_grade, 0.05f})
    for (uint32_t seed = 0; seed < 200; ++seed) {
      Image im = RandomImage(seed, grade);
      const std::vector<uint32_t> want = JacobiGrow(im.p, im.f);
      im.Run();
      ASSERT_EQ(im.f.pixel_grown, want)
          << "seed " << seed << " grade " << grade << " size " << im.p.beams << " x " << im.p.width;
      for (uint32_t pix = 0; pix < want.size(); ++pix) {
        seeds_total += im.f.pixel_fused[pix] == kPixGround;
        grown_total += IsUnknown(im.f.pixel_fused[pix]) && want[pix] == kPixGround;
      }
    }
  // The images exercise growth, not just the seeds.
  EXPECT_GT(grown_total, seeds_total);
}

TEST(Grow, SmallComponentsBecomeNonGroundAndComponentsAreLabelledByTheirLowestPixel) {
  const uint32_t m = DefaultParams().min_component;
  ASSERT_GE(m, 2u) << "the connectivity constraint must remove something";
  const uint32_t w = std::max(64u, 2 * m), h = 8;
  Image im(w, h);
  // A: exactly m ground pixels on row 3, wrapping round from column w - m/2 -> survives; its
  // lowest pixel index is row 3, column 0.
  for (uint32_t k = 0; k < m; ++k) im.Set(3, (w - m / 2 + k) % w, kPixGround, -1.7f);
  // B: m - 1 pixels on row 5 in two diagonal-touching pieces -> removed.
  for (uint32_t k = 0; k + 1 < m; ++k) im.Set(k < m / 2 ? 5 : 6, 3 + k, kPixGround, -1.7f);
  // C: m pixels in two pieces joined only diagonally across the wrap (rows 0 and 1) -> survives;
  // its lowest index is on row 0.
  for (uint32_t k = 0; k < m; ++k) {
    if (k < m / 2)
      im.Set(0, w - 1 - k, kPixGround, -1.7f);  // row 0, columns w-1 down
    else
      im.Set(1, k - m / 2, kPixGround, -1.7f);  // row 1, columns 0 up
  }
  im.p.min_component = m;
  im.p.comp_seed_share = 2.0f;  // every pixel here is a seed: keep no component for its seeds
  im.Run();
  const uint32_t comp_a = im.Pix(3, 0), comp_c = im.Pix(0, w - m / 2);
  uint32_t a = 0, b = 0, c = 0;
  for (uint32_t v = 0; v < h; ++v)
    for (uint32_t u = 0; u < w; ++u) {
      const uint32_t pix = im.Pix(v, u);
      if (im.f.pixel_grown[pix] != kPixGround) {
        EXPECT_EQ(im.f.pixel_comp[pix], kNone) << "pixel " << pix;
        EXPECT_EQ(im.f.pixel_label[pix], im.f.pixel_grown[pix]) << "pixel " << pix;
        continue;
      }
      if (v == 3) {
        ++a;
        EXPECT_EQ(im.f.pixel_comp[pix], comp_a) << "pixel " << pix;
        EXPECT_EQ(im.f.pixel_label[pix], kPixGround) << "pixel " << pix;
      } else if (v == 5 || v == 6) {
        ++b;
        EXPECT_EQ(im.f.pixel_label[pix], kPixNonGround) << "pixel " << pix;
      } else {
        ++c;
        EXPECT_EQ(im.f.pixel_comp[pix], comp_c) << "pixel " << pix;
        EXPECT_EQ(im.f.pixel_label[pix], kPixGround) << "pixel " << pix;
      }
    }
  EXPECT_EQ(a, m);
  EXPECT_EQ(b, m - 1);
  EXPECT_EQ(c, m);
  // Empty stays empty in the final label.
  EXPECT_EQ(im.f.pixel_label[im.Pix(4, 40)], kPixEmpty);
}

// A component under min_component stays ground when at least comp_seed_share of its pixels are
// seeds (fused ground) and it has at least comp_seed_min pixels; one grown mostly from unknown
// pixels, or too small, does not.
TEST(Grow, SmallComponentsOfSeedsStayGround) {
  Image im(64, 8);
  im.p.min_component = 40;
  im.p.comp_seed_min = 10;
  im.p.comp_seed_share = 0.8f;
  // A: 20 pixels on row 1, 16 seeds then 4 unknown grown from them: share 0.8 -> kept.
  for (uint32_t u = 0; u < 20; ++u) im.Set(1, u, u < 16 ? kPixGround : kPixUnknown, -1.7f);
  // B: 20 pixels on row 4, 15 seeds then 5 unknown: share 0.75 -> removed.
  for (uint32_t u = 0; u < 20; ++u) im.Set(4, u, u < 15 ? kPixGround : kPixUnknown, -1.7f);
  // C: 9 seeds on row 6: under comp_seed_min -> removed.
  for (uint32_t u = 0; u < 9; ++u) im.Set(6, u, kPixGround, -1.7f);
  im.Run();
  for (uint32_t u = 0; u < 20; ++u) {
    EXPECT_EQ(im.Grown(1, u), kPixGround) << "column " << u;
    EXPECT_EQ(im.f.pixel_label[im.Pix(1, u)], kPixGround) << "column " << u;
    EXPECT_EQ(im.Grown(4, u), kPixGround) << "column " << u;
    EXPECT_EQ(im.f.pixel_label[im.Pix(4, u)], kPixNonGround) << "column " << u;
  }
  for (uint32_t u = 0; u < 9; ++u) EXPECT_EQ(im.f.pixel_label[im.Pix(6, u)], kPixNonGround);
  im.p.comp_seed_share = 2.0f;  // above 1: no component is kept for its seeds
  im.Run();
  for (uint32_t u = 0; u < 20; ++u) EXPECT_EQ(im.f.pixel_label[im.Pix(1, u)], kPixNonGround);
}

TEST(Grow, ComponentLabelsAreTheLowestIndexOnRandomImages) {
  // Independent check by union-find: every ground pixel of pixel_grown carries the lowest pixel
  // index of its 8-connected component; pixel_label is ground exactly for components of at least
  // min_component pixels, or of at least comp_seed_min pixels comp_seed_share of which are seeds.
  const float shares[] = {0.0f, 0.5f, 0.8f, 1.0f, 2.0f};
  for (uint32_t seed = 0; seed < 60; ++seed) {
    Image im = RandomImage(1000 + seed, 0.0f);
    im.p.min_component = 1 + seed % 12;
    im.p.comp_seed_min = seed % 5;
    im.p.comp_seed_share = shares[seed % 5];
    im.Run();
    const uint32_t w = im.p.width, h = im.p.beams, pixels = w * h;
    std::vector<uint32_t> parent(pixels);
    for (uint32_t k = 0; k < pixels; ++k) parent[k] = k;
    auto find = [&](uint32_t x) {
      while (parent[x] != x) x = parent[x] = parent[parent[x]];
      return x;
    };
    for (uint32_t v = 0; v < h; ++v)
      for (uint32_t u = 0; u < w; ++u) {
        const uint32_t a = v * w + u;
        if (im.f.pixel_grown[a] != kPixGround) continue;
        for (int dv = 0; dv <= 1; ++dv)
          for (int du = -1; du <= 1; ++du) {
            if (dv == 0 && du <= 0) continue;
            if (v + dv >= h) continue;
            const uint32_t b = (v + dv) * w + (u + w + uint32_t(du + 1) - 1) % w;
            if (im.f.pixel_grown[b] != kPixGround) continue;
            const uint32_t ra = find(a), rb = find(b);
            if (ra != rb) parent[std::max(ra, rb)] = std::min(ra, rb);
          }
      }
    std::vector<uint32_t> size(pixels, 0), seeds(pixels, 0);
    for (uint32_t k = 0; k < pixels; ++k)
      if (im.f.pixel_grown[k] == kPixGround) {
        ++size[find(k)];
        seeds[find(k)] += im.f.pixel_fused[k] == kPixGround;
      }
    for (uint32_t k = 0; k < pixels; ++k) {
      if (im.f.pixel_grown[k] != kPixGround) {
        ASSERT_EQ(im.f.pixel_comp[k], kNone);
        continue;
      }
      const uint32_t root = find(k);  // the lowest index of the component (roots are minima)
      const bool by_seeds = size[root] >= im.p.comp_seed_min &&
                            double(seeds[root]) >= double(im.p.comp_seed_share) * size[root];
      const bool keep = size[root] >= im.p.min_component || by_seeds;
      ASSERT_EQ(im.f.pixel_label[k], keep ? kPixGround : kPixNonGround)
          << "seed " << seed << " pixel " << k;
      if (keep) {
        ASSERT_EQ(im.f.pixel_comp[k], root) << "seed " << seed << " pixel " << k;
      }
    }
  }
}

// The veto's lift: a vetoed pixel ends ground when the pixel above it ends ground (its ray not
// passed under that pixel) or when both row neighbours end ground with allowed steps to it; one
// step, judged on the labels before any lift; pixel_grown keeps kPixVetoed.
TEST(Grow, AVetoedPixelIsLiftedWhereTheGroundGoesOnAroundIt) {
  Image im(32, 8);
  im.p.min_component = 4;
  im.p.comp_seed_share = 2.0f;  // no component kept for its seeds
  const float z = -1.7f, r = 10.0f;
  for (uint32_t u = 0; u < 32; ++u) im.Set(2, u, kPixGround, z, r + 1.0f);  // ground above
  // A curb's foot: vetoed under ground that ends ground, farther away.
  im.Set(3, 1, kPixVetoed, z - 0.15f, r);
  // Two vetoed pixels stacked: the upper one is lifted, the lower one reads it unlifted.
  im.Set(3, 4, kPixVetoed, z - 0.1f, r);
  im.Set(4, 4, kPixVetoed, z - 0.2f, r - 0.5f);
  // Seen under the ground pixel above (reflection noise under the road): not lifted.
  const float under = r * (1.0f + 4.0f * im.p.occ_pass / (z - 1.0f));  // nearer, cleared by 4x
  im.Set(2, 7, kPixGround, z, under);
  im.Set(3, 7, kPixVetoed, z - 1.0f, r);
  // Row 0 has nothing above; no ground beside it either.
  im.Set(0, 10, kPixVetoed, z, r);
  // Ground on both sides, steps allowed: lifted (a pole's foot). Row 5, columns 12..14 and a
  // component of at least min_component pixels on each side.
  for (uint32_t u = 9; u <= 17; ++u) im.Set(5, u, kPixGround, z, r);
  im.Set(5, 13, kPixVetoed, z, r);
  // Ground on both sides but one step too high: not lifted.
  for (uint32_t u = 19; u <= 29; ++u) im.Set(6, u, kPixGround, z, r);
  im.Set(6, 24, kPixVetoed, z + 2.0f * im.p.grow_dz, r);
  // Above a ground pixel whose component is removed (one pixel): not lifted.
  im.Set(6, 2, kPixGround, z, r + 1.0f);
  im.Set(7, 2, kPixVetoed, z - 0.1f, r);
  im.Run();
  auto label = [&](uint32_t v, uint32_t u) { return im.f.pixel_label[im.Pix(v, u)]; };
  EXPECT_EQ(label(3, 1), kPixGround);
  EXPECT_EQ(label(3, 4), kPixGround);
  EXPECT_EQ(label(4, 4), kPixNonGround) << "one step only";
  EXPECT_EQ(label(3, 7), kPixNonGround) << "seen under the pixel above";
  EXPECT_EQ(label(0, 10), kPixNonGround);
  EXPECT_EQ(label(5, 13), kPixGround);
  EXPECT_EQ(label(6, 24), kPixNonGround) << "a step the growing would not take";
  EXPECT_EQ(label(6, 2), kPixNonGround) << "a removed component";
  EXPECT_EQ(label(7, 2), kPixNonGround);
  for (uint32_t pix = 0; pix < 32 * 8; ++pix)
    if (im.f.pixel_fused[pix] == kPixVetoed) {
      EXPECT_EQ(im.f.pixel_grown[pix], kPixVetoed) << "pixel " << pix;
      EXPECT_EQ(im.f.pixel_comp[pix], kNone) << "pixel " << pix;
    }
}

// The adversarial images (tests/grow_images.h; the kernel runs on them in tests/grow_vk_test.cpp):
// nothing grows without a seed, a serpentine corridor grows whole, and a bank's column climbed
// from its seed grows alone.
TEST(Grow, AdversarialImagesGrowAsTheirShapesSay) {
  for (test::SeededAdversary& a : test::SeededAdversaries()) {
    ASSERT_FALSE(a.unknown.empty()) << a.name;
    a.im.Run();
    size_t grown = 0;
    for (uint32_t pix : a.unknown) grown += a.im.f.pixel_grown[pix] == kPixGround;
    if (!a.seeded) {
      EXPECT_EQ(grown, 0u) << a.name << ": nothing grows without a seed";
    } else if (a.name.rfind("serpentine", 0) == 0) {
      EXPECT_EQ(grown, a.unknown.size()) << a.name << ": the whole corridor grows";
    } else if (a.name.rfind("banks", 0) == 0) {
      EXPECT_EQ(grown, 200u) << a.name << ": the seed's column, and only it, grows";
    }
  }
}

}  // namespace
}  // namespace lpir
