// feature_maps (III-D.1, Fig. 6 and 10): hand-made pixel images (pixel_point and the
// per-point r2, zt of prepare and project) against hand-checked feature values.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "reference_cpu/exact.h"
#include "reference_cpu/stages.h"
#include "tests/feature_maps_images.h"

namespace lpir {
namespace {

// A small range image: each Set() adds one point and makes it its pixel's winner.
struct Image {
  Params p;
  Frame f;
  Image(uint32_t width, uint32_t beams) {
    p = DefaultParams();
    p.width = width;
    p.beams = beams;
    f.pixel_point.assign(size_t(width) * beams, kNone);
  }
  uint32_t Pix(uint32_t v, uint32_t u) const { return v * p.width + u; }
  void Set(uint32_t v, uint32_t u, float r2, float z) {
    f.pixel_point[Pix(v, u)] = f.n++;
    f.flags.push_back(kPointValid);
    f.r2.push_back(r2);
    f.zt.push_back(z);
  }
  // A point at planar range r (r2 = r * r rounded).
  void SetRange(uint32_t v, uint32_t u, float r, float z) { Set(v, u, r * r, z); }
  void Run() { FeatureMaps(p, f); }
  float Range(uint32_t v, uint32_t u) const { return f.f_range[Pix(v, u)]; }
  float Height(uint32_t v, uint32_t u) const { return f.f_height[Pix(v, u)]; }
  uint32_t Filled(uint32_t v, uint32_t u) const { return f.pixel_filled[Pix(v, u)]; }
};

// Correctly rounded float quotient / root, computed independently of exact.h (double then float
// is correctly rounded for / and sqrt of floats).
float Quotient(float a, float b) { return float(double(a) / double(b)); }
float Root(float a) { return float(std::sqrt(double(a))); }

TEST(FeatureMaps, MeasuredPixelsTakeTheirWinnersValues) {
  Image im(32, 6);
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> r2(6.25f, 14400.0f), z(-3.0f, 2.0f);
  std::bernoulli_distribution filled(0.6);
  for (uint32_t v = 0; v < 6; ++v)
    for (uint32_t u = 0; u < 32; ++u)
      if (filled(rng)) im.Set(v, u, r2(rng), z(rng));
  im.Run();
  uint32_t measured = 0, empty = 0;
  for (uint32_t pix = 0; pix < 32 * 6; ++pix) {
    const uint32_t i = im.f.pixel_point[pix];
    if (i != kNone) {
      ++measured;
      EXPECT_EQ(im.f.pixel_filled[pix], 1u);
      EXPECT_EQ(exact::Bits(im.f.f_range[pix]), exact::Bits(exact::Sqrt(im.f.r2[i])));
      EXPECT_EQ(exact::Bits(im.f.f_range[pix]), exact::Bits(Root(im.f.r2[i])));
      EXPECT_EQ(im.f.f_height[pix], im.f.zt[i]);
    } else if (im.f.pixel_filled[pix] == 0) {
      ++empty;  // empty pixels hold 0 in every feature
      for (const std::vector<float>* m : {&im.f.f_range, &im.f.f_height, &im.f.f_slope,
                                          &im.f.f_edge_l, &im.f.f_edge_r, &im.f.f_varz})
        EXPECT_EQ((*m)[pix], 0.0f) << "pixel " << pix;
    }
  }
  EXPECT_GT(measured, 50u);
  EXPECT_GT(empty, 10u);
}

TEST(FeatureMaps, OnePixelHolesAreFilledWhenTheNeighboursAgree) {
  Image im(8, 5);
  const float gap = im.p.hole_gap;
  ASSERT_GT(gap, 0.0f);
  // Row 0: neighbours within hole_gap -> filled with their average.
  im.SetRange(0, 2, 10.0f, -1.70f);
  im.SetRange(0, 4, 10.0f + 0.5f * gap, -1.60f);
  // Row 1: neighbours further apart than hole_gap -> stays empty.
  im.SetRange(1, 2, 10.0f, -1.70f);
  im.SetRange(1, 4, 10.0f + 2.0f * gap, -1.70f);
  // Row 2: a hole at column 0 between columns width-1 and 1 (the image wraps).
  im.SetRange(2, 7, 20.0f, -1.72f);
  im.SetRange(2, 1, 20.0f, -1.68f);
  // Row 3: a hole at column width-1 between columns width-2 and 0.
  im.SetRange(3, 6, 30.0f, -1.50f);
  im.SetRange(3, 0, 30.0f + 0.25f * gap, -1.52f);
  // Row 4: a two-pixel gap is not a one-pixel hole (filled pixels never feed the filling).
  im.SetRange(4, 1, 12.0f, -1.70f);
  im.SetRange(4, 4, 12.0f, -1.70f);
  im.Run();

  auto expect_average = [&](uint32_t v, uint32_t u, uint32_t l, uint32_t r) {
    SCOPED_TRACE("hole at row " + std::to_string(v) + " column " + std::to_string(u));
    EXPECT_EQ(im.Filled(v, u), 2u);
    EXPECT_EQ(im.Range(v, u), (im.Range(v, l) + im.Range(v, r)) * 0.5f);
    EXPECT_EQ(im.Height(v, u), (im.Height(v, l) + im.Height(v, r)) * 0.5f);
  };
  expect_average(0, 3, 2, 4);
  EXPECT_EQ(im.Filled(1, 3), 0u);
  EXPECT_EQ(im.Range(1, 3), 0.0f);
  expect_average(2, 0, 7, 1);
  expect_average(3, 7, 6, 0);
  EXPECT_EQ(im.Filled(4, 2), 0u);
  EXPECT_EQ(im.Filled(4, 3), 0u);
  // Nothing else got filled, the measured pixels stay measured.
  uint32_t holes = 0, measured = 0;
  for (uint32_t s : im.f.pixel_filled) holes += s == 2, measured += s == 1;
  EXPECT_EQ(holes, 3u);
  EXPECT_EQ(measured, im.f.n);
}

TEST(FeatureMaps, EdgesAreHeightStepsToTheLeftAndRightNeighbours) {
  Image im(6, 2);
  const float z[6] = {-1.70f, -1.65f, -0.90f, -0.95f, -1.72f, -1.71f};
  for (uint32_t u = 0; u < 6; ++u) im.SetRange(0, u, 10.0f, z[u]);
  im.Run();
  auto el = [&](uint32_t u) { return im.f.f_edge_l[im.Pix(0, u)]; };
  auto er = [&](uint32_t u) { return im.f.f_edge_r[im.Pix(0, u)]; };
  // edge_l = |z - z(u-1)|, edge_r = |z(u+1) - z|; columns wrap.
  for (uint32_t u = 0; u < 6; ++u) {
    EXPECT_EQ(el(u), std::fabs(z[u] - z[(u + 5) % 6])) << "column " << u;
    EXPECT_EQ(er(u), std::fabs(z[(u + 1) % 6] - z[u])) << "column " << u;
  }
  EXPECT_EQ(el(0), std::fabs(z[0] - z[5]));  // across the wrap
  EXPECT_EQ(er(5), std::fabs(z[0] - z[5]));
  EXPECT_GT(er(1), 0.7f);  // the step onto the object shows on both sides of it
  EXPECT_GT(el(2), 0.7f);
  EXPECT_GT(er(3), 0.7f);
  EXPECT_LT(el(0), 0.02f);
  // The row without points has no edges.
  for (uint32_t u = 0; u < 6; ++u) EXPECT_EQ(im.f.f_edge_l[im.Pix(1, u)], 0.0f);
}

TEST(FeatureMaps, EdgeIsZeroNextToAnEmptyPixel) {
  Image im(8, 1);
  const float gap = im.p.hole_gap;
  im.SetRange(0, 2, 10.0f, -1.7f);
  im.SetRange(0, 4, 10.0f + 3.0f * gap, 0.5f);  // too far for the hole at 3 to be filled
  im.Run();
  ASSERT_EQ(im.Filled(0, 3), 0u);
  EXPECT_EQ(im.f.f_edge_l[2], 0.0f);
  EXPECT_EQ(im.f.f_edge_r[2], 0.0f);
  EXPECT_EQ(im.f.f_edge_l[4], 0.0f);
  EXPECT_EQ(im.f.f_edge_r[4], 0.0f);
}

TEST(FeatureMaps, SlopeLooksAtTheNextRowDown) {
  // Contract: slope = |z(v+1) - z| / |r(v+1) - r| (Div), -1 when that neighbour is empty, when
  // the pixel is on the last row, or when the two ranges are equal.
  Image im(8, 4);
  const float gap = im.p.hole_gap;
  im.SetRange(0, 1, 12.0f, -1.50f);
  im.SetRange(1, 1, 10.0f, -1.70f);  // below (0,1): slope 0.2 / 2
  im.SetRange(2, 1, 9.0f, -1.30f);   // below (1,1): slope 0.4 / 1
  im.SetRange(3, 1, 8.5f, -1.30f);   // last row
  // (0,5) has neighbours left and right (u+1 is measured) but nothing below: undefined.
  im.SetRange(0, 5, 10.0f, -1.70f);
  im.SetRange(0, 6, 11.0f, -1.20f);
  // (2,5) over (3,5) at the same range (a vertical surface seen edge-on): undefined.
  im.SetRange(2, 5, 7.0f, -1.00f);
  im.SetRange(3, 5, 7.0f, -1.40f);
  im.Run();
  auto slope = [&](uint32_t v, uint32_t u) { return im.f.f_slope[im.Pix(v, u)]; };
  auto want = [&](uint32_t v, uint32_t u) {
    return Quotient(std::fabs(im.Height(v + 1, u) - im.Height(v, u)),
                    std::fabs(im.Range(v + 1, u) - im.Range(v, u)));
  };
  EXPECT_EQ(slope(0, 1), want(0, 1));
  EXPECT_NEAR(slope(0, 1), 0.1f, 1e-5f);
  EXPECT_EQ(slope(1, 1), want(1, 1));
  EXPECT_NEAR(slope(1, 1), 0.4f, 1e-5f);
  EXPECT_EQ(slope(2, 1), 0.0f);   // dz 0, dr 0.5: flat
  EXPECT_EQ(slope(3, 1), -1.0f);  // last row
  ASSERT_EQ(im.Filled(1, 5), 0u);
  EXPECT_EQ(slope(0, 5), -1.0f);
  EXPECT_EQ(slope(2, 5), -1.0f);
  // A hole-filled pixel below counts as a neighbour.
  Image h(8, 2);
  h.SetRange(0, 3, 10.0f, -1.5f);
  h.SetRange(1, 2, 8.0f, -1.7f);
  h.SetRange(1, 4, 8.0f + 0.5f * gap, -1.7f);
  h.Run();
  ASSERT_EQ(h.Filled(1, 3), 2u);
  EXPECT_EQ(h.f.f_slope[h.Pix(0, 3)], Quotient(std::fabs(h.Height(1, 3) - h.Height(0, 3)),
                                               std::fabs(h.Range(1, 3) - h.Range(0, 3))));
  EXPECT_GT(h.f.f_slope[h.Pix(0, 3)], 0.0f);
}

// Variance of height about the line in range of the filled pixels of the 3x3 window around
// (v, u), rows clamped, columns wrapping, in double precision from the values quantised as the
// contract says (heights and ranges to 0.1 mm, round half up): Vz = n sum z^2 - (sum z)^2,
// Vr = n sum r^2 - (sum r)^2, C = n sum r z - sum r sum z, b = C / Vr clamped to [-1, 1] (0 when
// Vr is 0), var = (Vz - 2 b C + b^2 Vr) / n^2 * quantum^2. The tests keep their values on that
// grid, so the quantisation itself is exact.
void WindowVariance(const Image& im, uint32_t v, uint32_t u, double* var_z, uint32_t* count) {
  const uint32_t w = im.p.width, h = im.p.beams;
  double n = 0, sz = 0, szz = 0, sr = 0, srr = 0, srz = 0;
  for (int dv = -1; dv <= 1; ++dv) {
    const int vv = int(v) + dv;
    if (vv < 0 || vv >= int(h)) continue;
    for (int du = -1; du <= 1; ++du) {
      const uint32_t uu = (u + w + uint32_t(du + 1) - 1) % w;
      const uint32_t pix = uint32_t(vv) * w + uu;
      if (!im.f.pixel_filled[pix]) continue;
      const double z = std::floor(double(im.f.f_height[pix]) * 1e4 + 0.5);
      const double r = std::floor(double(im.f.f_range[pix]) * 1e4 + 0.5);
      n += 1, sz += z, szz += z * z, sr += r, srr += r * r, srz += r * z;
    }
  }
  const double vz = n * szz - sz * sz, vr = n * srr - sr * sr, c = n * srz - sr * sz;
  const double b = vr > 0 ? std::min(std::max(c / vr, -1.0), 1.0) : 0.0;
  *var_z = std::max(vz - 2 * b * c + b * b * vr, 0.0) / (n * n) * 1e-8;
  *count = uint32_t(n);
}

TEST(FeatureMaps, VariancesOfTheThreeByThreeWindow) {
  Image im(6, 4);
  const float far = 10.0f + 3.0f * im.p.hole_gap;  // too far from 10 m for any hole filling
  // Hand-checked centre window: rows 0-2, columns 1-3, every pixel measured.
  const float zc[3][3] = {
      {-1.70f, -1.68f, -1.71f}, {-1.66f, -1.50f, -1.69f}, {-1.70f, -1.72f, -1.67f}};
  for (uint32_t v = 0; v < 3; ++v)
    for (uint32_t u = 0; u < 3; ++u) im.SetRange(v, u + 1, 10.0f, zc[v][u]);
  // Columns 5 and 0 meet across the wrap; a sparse last row.
  im.SetRange(0, 5, far, -1.2f);
  im.SetRange(1, 5, far, -1.3f);
  im.SetRange(1, 0, far, -1.4f);
  im.SetRange(3, 2, 9.0f, -1.9f);
  im.Run();
  for (uint32_t s : im.f.pixel_filled) ASSERT_NE(s, 2u) << "no hole may be filled here";
  // By hand: z mean -15.03 / 9 = -1.67, squared deviations (0.03^2 + 0.01^2 + 0.04^2 + 0.01^2 +
  // 0.17^2 + 0.02^2 + 0.03^2 + 0.05^2 + 0) = 0.0354 -> 0.0039333.
  EXPECT_NEAR(im.f.f_varz[im.Pix(1, 2)], 0.0354 / 9.0, 1e-6);
  // Every filled pixel, the border ones included (rows clamped, columns wrapping, fewer than 9
  // filled pixels), matches the definition evaluated in double precision.
  double vz;
  uint32_t count, checked = 0, partial = 0;
  for (uint32_t v = 0; v < im.p.beams; ++v)
    for (uint32_t u = 0; u < im.p.width; ++u) {
      if (!im.Filled(v, u)) continue;
      WindowVariance(im, v, u, &vz, &count);
      const uint32_t pix = im.Pix(v, u);
      EXPECT_NEAR(im.f.f_varz[pix], vz, 1e-4 * vz + 1e-8) << "row " << v << " column " << u;
      ++checked;
      partial += count < 9;
    }
  EXPECT_EQ(checked, 13u);
  EXPECT_EQ(partial, 12u);
  // (1,0) sees column 5 across the wrap: (0,5), (1,5), itself and column 1's three pixels.
  WindowVariance(im, 1, 0, &vz, &count);
  EXPECT_EQ(count, 6u);
  EXPECT_GT(im.f.f_varz[im.Pix(1, 0)], 0.001f);
}

TEST(FeatureMaps, VarianceIsTakenAboutTheLineInRange) {
  // Three columns of three rows, each row at its own range: z rising with r at a slope of 0.5
  // (a bank) reads 0, as flat ground does; at 2 (steeper than the clamp's 45 degrees) it reads
  // the variance of z - r; a wall (one range, heights stacked) keeps its plain variance.
  const float rs[3] = {10.0f, 10.5f, 11.0f};  // rows 0 (top, farthest) .. 2
  auto window = [&](float slope, bool wall) {
    Image im(3, 3);
    for (uint32_t v = 0; v < 3; ++v)
      for (uint32_t u = 0; u < 3; ++u) {
        const float r = wall ? 10.0f : rs[2 - v];
        im.SetRange(v, u, r, -1.7f + slope * (wall ? 0.5f * float(2 - v) : r - 10.0f));
      }
    im.Run();
    return im.f.f_varz[im.Pix(1, 1)];
  };
  EXPECT_EQ(window(0.0f, false), 0.0f);
  EXPECT_EQ(window(0.5f, false), 0.0f);
  // slope 2: z - r goes 0, 0.5, 1.0 m over the rows; its variance 1/6 m^2.
  EXPECT_NEAR(window(2.0f, false), 1.0 / 6.0, 1e-5);
  // A wall with the same heights as slope 0.5: 0, 0.25, 0.5 m, variance 1/24 m^2.
  EXPECT_NEAR(window(0.5f, true), 1.0 / 24.0, 1e-5);
}

TEST(FeatureMaps, IsolatedPixelHasZeroVariance) {
  Image im(8, 3);
  im.SetRange(1, 4, 10.0f, -1.7f);
  im.Run();
  EXPECT_EQ(im.f.f_varz[im.Pix(1, 4)], 0.0f);
  EXPECT_EQ(im.f.f_slope[im.Pix(1, 4)], -1.0f);
  EXPECT_EQ(im.f.f_edge_l[im.Pix(1, 4)], 0.0f);
  EXPECT_EQ(im.f.f_edge_r[im.Pix(1, 4)], 0.0f);
}

// Holes between neighbours whose ranges differ by hole_gap give or take a few ulps of r2
// (tests/feature_maps_images.h; the kernel runs on the same image in feature_maps_vk_test.cpp):
// both sides of the bound occur, some filled and some left empty.
TEST(FeatureMaps, HolesAroundTheHoleGapFallOnBothSides) {
  const Params p = test::SmallImage(1024, 16);
  std::vector<uint32_t> holes;
  Frame f = test::HoleGapImage(p, &holes);
  FeatureMaps(p, f);
  size_t filled = 0;
  for (uint32_t pix : holes) filled += f.pixel_filled[pix] == 2u;
  EXPECT_GT(filled, 0u);
  EXPECT_LT(filled, holes.size());
}

}  // namespace
}  // namespace lpir
