// grid_reduce: ring and sector of eq. 4 and the per-cell min / max / count.
#include <gtest/gtest.h>

#include "reference_cpu/exact.h"
#include "reference_cpu/stages.h"
#include "tests/stage_test_util.h"

namespace lpir {
namespace {

TEST(GridReduce, RingsFollowTheSquaredBoundaries) {
  const std::vector<float> bound2 = {4.0f, 16.0f, 36.0f};
  EXPECT_EQ(RingOf(0.5f, bound2.data(), 3), 0u);
  EXPECT_EQ(RingOf(3.99f, bound2.data(), 3), 0u);
  EXPECT_EQ(RingOf(4.0f, bound2.data(), 3), 1u);  // a boundary belongs to the outer ring
  EXPECT_EQ(RingOf(35.0f, bound2.data(), 3), 2u);
  EXPECT_EQ(RingOf(36.0f, bound2.data(), 3), 3u);  // beyond the grid
}

TEST(GridReduce, CellsAndTheirHeightStatistics) {
  const SensorProfile s = test::SmallSensor();
  const Params p = ParamsForSensor(s);
  const Tables t = MakeTables(s, p);
  ASSERT_EQ(p.sectors_near, 64u);
  Cloud c;
  c.Push(3.0f, 0.01f, -1.70f, 0.3f);  // 0: near ring 1 (2-4 m), ahead
  c.Push(3.2f, 0.01f, -1.50f, 0.3f);  // 1: same cell, higher
  c.Push(3.1f, 0.01f, -1.60f, 0.3f);  // 2: same cell
  c.Push(3.1f, 0.01f, -5.00f, 0.0f);  // 3: same cell, reflection noise: excluded
  const float far_r = p.ring_res_near * float(p.rings_near) + 0.5f * p.ring_res_far;
  c.Push(far_r, 0.01f, -1.6f, 0.3f);  // 4: first far ring
  Frame f;
  Prepare(c, p, f);
  ASSERT_TRUE(f.flags[3] & kPointNoise);
  Project(c, p, t, f);
  GridReduce(p, t, f);
  const uint32_t u = f.point_pixel[0] % p.width;
  const uint32_t near_cell = 1 * p.sectors_near + u / (p.width / p.sectors_near);
  EXPECT_EQ(f.point_cell[0], near_cell);
  EXPECT_EQ(f.point_cell[1], near_cell);
  EXPECT_EQ(f.point_cell[2], near_cell);
  EXPECT_EQ(f.point_cell[3], kNone);
  EXPECT_EQ(f.cell_count[near_cell], 3u);
  EXPECT_EQ(exact::FromKey(f.cell_zmin[near_cell]), f.zt[0]);
  EXPECT_EQ(exact::FromKey(f.cell_zmax[near_cell]), f.zt[1]);
  const uint32_t u4 = f.point_pixel[4] % p.width;
  EXPECT_EQ(f.point_cell[4],
            p.rings_near * p.sectors_near + 0 * p.sectors_far + u4 / (p.width / p.sectors_far));
  uint32_t total = 0;
  for (uint32_t n : f.cell_count) total += n;
  EXPECT_EQ(total, 4u);
  EXPECT_EQ(f.cell_count.size(), CellCount(p));
}

}  // namespace
}  // namespace lpir
