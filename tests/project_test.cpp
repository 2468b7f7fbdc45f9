// project: the exact column and row lookups of eq. 1 and the pixel winner rule.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "reference_cpu/exact.h"
#include "reference_cpu/stages.h"
#include "tests/stage_test_util.h"

namespace lpir {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Column by definition: how many boundaries phi_k (k >= 1) lie above the point's angle, each
// decided by the exact-order predicate evaluated one by one.
uint32_t ColumnByCount(float x, float y, const Tables& t, uint32_t width) {
  uint32_t u = 0;
  for (uint32_t k = 1; k < width; ++k) {
    const float bx = t.column_dir[2 * k], by = t.column_dir[2 * k + 1];
    const bool up = y > 0.0f || (y == 0.0f && x < 0.0f);
    const bool bup = by > 0.0f || (by == 0.0f && bx < 0.0f);
    bool below;
    if (up != bup) {
      below = bup;
    } else {
      const float a = x * by, b = y * bx;
      below = a - b > 0.0f;
    }
    u += below;
  }
  return u;
}

TEST(Project, ColumnWalkEqualsTheBoundaryCount) {
  for (uint32_t width : {256u, 1800u, 2048u}) {
    SensorProfile s = test::SmallSensor();
    s.width = width;
    s.overrides.clear();
    s.overrides = {{"sectors_near", 8}, {"sectors_far", 8}};
    const Params p = ParamsForSensor(s);
    const Tables t = MakeTables(s, p);
    std::mt19937 rng(width);
    std::uniform_real_distribution<float> coord(-80.0f, 80.0f);
    for (int k = 0; k < 3000; ++k) {
      float x = coord(rng), y = coord(rng);
      if (k % 10 == 0) x = 0.0f;  // on the axes too
      if (k % 10 == 1) y = 0.0f;
      if (x == 0.0f && y == 0.0f) continue;
      ASSERT_EQ(ColumnOf(x, y, t.column_dir.data(), width), ColumnByCount(x, y, t, width))
          << "x " << x << " y " << y << " width " << width;
    }
    // Points exactly on boundary directions.
    for (uint32_t k = 1; k < width; k += 7) {
      const float x = 30.0f * t.column_dir[2 * k], y = 30.0f * t.column_dir[2 * k + 1];
      ASSERT_EQ(ColumnOf(x, y, t.column_dir.data(), width), ColumnByCount(x, y, t, width));
    }
  }
}

TEST(Project, ColumnFollowsEq1AwayFromBoundaries) {
  SensorProfile s = test::SmallSensor();
  const Params p = ParamsForSensor(s);
  const Tables t = MakeTables(s, p);
  for (double theta = -3.1; theta < 3.14; theta += 0.0137) {
    const double u = 0.5 * (1.0 - theta / kPi) * p.width;
    if (std::fabs(u - std::round(u)) < 1e-3) continue;
    const float x = float(20.0 * std::cos(theta)), y = float(20.0 * std::sin(theta));
    EXPECT_EQ(ColumnOf(x, y, t.column_dir.data(), p.width), uint32_t(std::floor(u)))
        << "theta " << theta;
  }
  // Straight behind (theta = pi) is column 0, straight ahead (theta = 0) the middle column.
  EXPECT_EQ(ColumnOf(-10.0f, 0.0f, t.column_dir.data(), p.width), 0u);
  EXPECT_EQ(ColumnOf(10.0f, 0.001f, t.column_dir.data(), p.width), p.width / 2 - 1);
  EXPECT_EQ(ColumnOf(10.0f, -0.001f, t.column_dir.data(), p.width), p.width / 2);
}

TEST(Project, RowIsTheBeamNearestInElevation) {
  SensorProfile s = test::SmallSensor();
  const Params p = ParamsForSensor(s);
  const Tables t = MakeTables(s, p);
  for (uint32_t b = 0; b < s.beams; ++b) {
    for (double off : {-0.3, 0.0, 0.3}) {  // within half the 1-degree spacing
      const double e = (s.elevation_deg[b] + off) * kPi / 180.0;
      const float r = 25.0f, z = float(25.0 * std::tan(e));
      EXPECT_EQ(RowOf(z, r * r, t.beam_bound.data(), t.beam_origin.data(), p.beams), b)
          << "beam " << b << " " << off;
    }
  }
  // Beyond the table's ends: the top and bottom rows.
  EXPECT_EQ(RowOf(100.0f, 1.0f, t.beam_bound.data(), t.beam_origin.data(), p.beams), 0u);
  EXPECT_EQ(RowOf(-100.0f, 1.0f, t.beam_bound.data(), t.beam_origin.data(), p.beams), p.beams - 1);
}

TEST(Project, RowEqualsTheBoundaryCount) {
  SensorProfile s = test::SmallSensor();
  s.beam_origin_z.assign(s.beams, 0.2f);
  for (unsigned b = s.beams / 2; b < s.beams; ++b) s.beam_origin_z[b] = 0.1f;  // two blocks
  const Params p = ParamsForSensor(s);
  const Tables t = MakeTables(s, p);
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> range(1.0f, 90.0f), height(-30.0f, 10.0f);
  for (int k = 0; k < 20000; ++k) {
    const float r = range(rng), z = height(rng), r2 = r * r;
    uint32_t count = 0;
    for (uint32_t b = 0; b + 1 < p.beams; ++b) {
      const float h = z - t.beam_origin[b];
      const float hh = h * (h < 0.0f ? -h : h);
      const float bound = t.beam_bound[b] * r2;
      count += bound > hh;
    }
    ASSERT_EQ(RowOf(z, r2, t.beam_bound.data(), t.beam_origin.data(), p.beams), count)
        << "z " << z << " r " << r;
  }
}

// The reference starts each column search next to the previous point's column; the answer must
// not depend on that, so a sweep-ordered cloud and a shuffled copy map every point alike.
TEST(Project, PixelsDoNotDependOnPointOrder) {
  SensorProfile s = test::SmallSensor();
  const Params p = ParamsForSensor(s);
  const Tables t = MakeTables(s, p);
  Cloud sweep;
  for (unsigned b = 0; b < s.beams; ++b) {
    for (int k = 0; k < 700; ++k) {
      const double az = 3.0 * kPi * k / 700.0;  // one and a half turns: hints wrap around
      const double e = s.elevation_deg[b] * kPi / 180.0, r = 4.0 + 0.01 * k;
      sweep.Push(float(r * std::cos(az)), float(r * std::sin(az)), float(r * std::tan(e)), 0.3f);
    }
  }
  std::vector<uint32_t> order(sweep.size());
  for (uint32_t i = 0; i < order.size(); ++i) order[i] = i;
  std::mt19937 rng(9);
  std::shuffle(order.begin(), order.end(), rng);
  Cloud shuffled;
  for (uint32_t i : order) shuffled.Push(sweep.x(i), sweep.y(i), sweep.z(i), sweep.intensity(i));
  Frame a, b;
  Prepare(sweep, p, a);
  Project(sweep, p, t, a);
  Prepare(shuffled, p, b);
  Project(shuffled, p, t, b);
  for (uint32_t k = 0; k < order.size(); ++k)
    ASSERT_EQ(b.point_pixel[k], a.point_pixel[order[k]]) << "point " << order[k];
}

TEST(Project, NearestPointWinsThenLowestIndexAndNoiseNeverWins) {
  SensorProfile s = test::SmallSensor();
  const Params p = ParamsForSensor(s);
  const Tables t = MakeTables(s, p);
  Cloud c;
  c.Push(20.0f, 0.01f, -1.0f, 0.3f);    // 0: behind 1 on the same ray
  c.Push(10.0f, 0.005f, -0.5f, 0.3f);   // 1: nearest
  c.Push(10.0f, 0.005f, -0.5f, 0.3f);   // 2: same r2 as 1, higher index
  c.Push(5.0f, 0.0025f, -0.25f, 0.0f);  // 3: nearer still but reflection noise (set below)
  c.Push(0.0f, 0.0f, 0.0f, 0.3f);       // 4: invalid
  Frame f;
  Prepare(c, p, f);
  f.flags[3] |= kPointNoise;
  Project(c, p, t, f);
  const uint32_t pix = f.point_pixel[1];
  ASSERT_NE(pix, kNone);
  EXPECT_EQ(f.point_pixel[0], pix);
  EXPECT_EQ(f.point_pixel[2], pix);
  EXPECT_EQ(f.point_pixel[3], pix);   // noise has a pixel...
  EXPECT_EQ(f.pixel_point[pix], 1u);  // ...but the nearest non-noise point, lowest index, wins
  EXPECT_EQ(f.pixel_key[pix], exact::Key(f.r2[1]));
  EXPECT_EQ(f.point_pixel[4], kNone);
}

TEST(Project, RingIndexGivesTheRowInEitherOrder) {
  SensorProfile s = test::SmallSensor();
  Cloud c;
  c.Push(10.0f, 0.0f, -1.0f, 0.3f);
  c.ring = {3};
  for (bool top : {false, true}) {
    s.ring_zero_is_top = top;
    const Params p = ParamsForSensor(s);
    const Tables t = MakeTables(s, p);
    Frame f;
    Prepare(c, p, f);
    Project(c, p, t, f);
    EXPECT_EQ(f.point_pixel[0] / p.width, top ? 3u : s.beams - 1 - 3);
  }
}

}  // namespace
}  // namespace lpir
