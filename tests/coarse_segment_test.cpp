// coarse_segment (eqs. 5-7): seeds, the per-cell integer plane fit, the point-to-plane
// threshold and the coarse label. Inputs are built by hand (prepare and grid_reduce buffers from
// the cloud, following those stages' contracts), so only coarse_segment is under test. Thresholds
// come from Params.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <numeric>
#include <random>
#include <vector>

#include "reference_cpu/exact.h"
#include "reference_cpu/stages.h"
#include "tests/coarse_segment_inputs.h"
#include "tests/stage_test_util.h"

namespace lpir {
namespace {

constexpr int64_t kQ = 16384;  // Q14 unit normal

struct Small {
  SensorProfile sensor = test::SmallSensor();
  Params p = ParamsForSensor(sensor);
  Tables t = MakeTables(sensor, p);
};

// coarse_segment's inputs by hand (tests/coarse_segment_inputs.h).
Frame Inputs(const Cloud& c, const Small& s) { return test::CoarseInputs(c, s.p, s.t); }

Frame Coarse(const Cloud& c, const Small& s) {
  Frame f = Inputs(c, s);
  CoarseSegment(c, s.p, s.t, f);
  return f;
}

const int32_t* Plane(const Frame& f, uint32_t cell) { return &f.cell_plane[size_t(cell) * 8]; }

// The cells holding at least `min_points` points.
std::vector<uint32_t> BusyCells(const Frame& f, uint32_t min_points) {
  std::vector<uint32_t> out;
  for (uint32_t c = 0; c < f.cell_count.size(); ++c)
    if (f.cell_count[c] >= min_points) out.push_back(c);
  return out;
}

using test::AddPlane;

// The mean in mm and the least-squares normal (double precision, Eigen, oriented up) of all the
// cell's points: the reference for the stage's integer fit where every point is a seed.
struct Fit {
  double mean[3] = {0, 0, 0};
  Eigen::Vector3d normal;
};
Fit FitCell(const Cloud& c, const Frame& f, uint32_t cell) {
  Fit fit;
  std::vector<Eigen::Vector3d> pts;
  for (uint32_t i = 0; i < f.n; ++i) {
    if (f.point_cell[i] != cell) continue;
    pts.emplace_back(std::round(double(c.x(i)) * 1000), std::round(double(c.y(i)) * 1000),
                     std::round(double(f.zt[i]) * 1000));
  }
  Eigen::Vector3d m = Eigen::Vector3d::Zero();
  for (const auto& q : pts) m += q;
  m /= double(pts.size());
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (const auto& q : pts) cov += (q - m) * (q - m).transpose();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(cov);
  fit.normal = es.eigenvectors().col(0);
  if (fit.normal.z() < 0) fit.normal = -fit.normal;
  for (int k = 0; k < 3; ++k) fit.mean[k] = m[k];
  return fit;
}

TEST(CoarseSegment, FlatNoisyPlaneIsGroundWithAVerticalNormal) {
  const Small s;
  // Noise well inside every tolerance the stage has (seed band, whole-cell spread, plane floor).
  const float amp = 0.1f * std::min({s.p.plane_dist_floor, s.p.h_athr, s.p.seed_margin});
  Cloud c;
  AddPlane(&c, 4.2f, 9.8f, -1.5f, 1.5f, 0.1f, -s.p.sensor_height, 0, 0, amp, 1);
  const Frame f = Coarse(c, s);
  for (uint32_t i = 0; i < f.n; ++i) ASSERT_EQ(f.coarse[i], 1u) << "point " << i;
  const std::vector<uint32_t> cells = BusyCells(f, 20);
  ASSERT_GE(cells.size(), 8u);
  for (uint32_t cell : cells) {
    SCOPED_TRACE("cell " + std::to_string(cell));
    const int32_t* pl = Plane(f, cell);
    EXPECT_NE(f.cell_seed_mode[cell], 0u);
    EXPECT_EQ(uint32_t(pl[7]), f.cell_count[cell]);  // every point is a seed
    const Fit fit = FitCell(c, f, cell);
    for (int k = 0; k < 3; ++k) EXPECT_LE(std::fabs(pl[3 + k] - fit.mean[k]), 1.0) << "axis " << k;
    // Q14 unit normal, nearly vertical (noise of a few mm over a cell tilts it by < 1 %) and
    // within a few units of the least-squares normal.
    EXPECT_GE(pl[2], kQ - 3);
    EXPECT_LE(pl[2], kQ);
    EXPECT_LE(std::abs(pl[0]), kQ / 100);
    EXPECT_LE(std::abs(pl[1]), kQ / 100);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(pl[k], fit.normal[k] * kQ, 3.0) << "normal axis " << k;
    // The threshold is at least the floor, in mm * 2^14.
    EXPECT_GE(pl[6], exact::ToFixed(s.p.plane_dist_floor, 16384000.0f) - 1);
  }
}

TEST(CoarseSegment, TiltedPlaneNormalMatchesTheTilt) {
  const Small s;
  const float gx = 0.05f, gy = 0.03f;  // a 5 % grade ahead, 3 % to the left
  ASSERT_LT(std::hypot(gx, gy), s.p.slope_max) << "the test plane must be a legal ground slope";
  Cloud c;
  AddPlane(&c, 4.2f, 9.8f, -1.5f, 1.5f, 0.05f, -s.p.sensor_height, gx, gy, 0.0f, 2);
  const Frame f = Coarse(c, s);
  for (uint32_t i = 0; i < f.n; ++i) ASSERT_EQ(f.coarse[i], 1u) << "point " << i;
  const double norm = std::sqrt(1.0 + double(gx) * gx + double(gy) * gy);
  const double want[3] = {-gx / norm * kQ, -gy / norm * kQ, 1.0 / norm * kQ};
  const std::vector<uint32_t> cells = BusyCells(f, 50);
  ASSERT_GE(cells.size(), 8u);
  for (uint32_t cell : cells) {
    SCOPED_TRACE("cell " + std::to_string(cell));
    const int32_t* pl = Plane(f, cell);
    EXPECT_EQ(uint32_t(pl[7]), f.cell_count[cell]);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(pl[k], want[k], 4.0) << "normal axis " << k;
    const int64_t len2 = int64_t(pl[0]) * pl[0] + int64_t(pl[1]) * pl[1] + int64_t(pl[2]) * pl[2];
    EXPECT_NEAR(std::sqrt(double(len2)), double(kQ), 3.0);  // a unit vector in Q14
  }
}

TEST(CoarseSegment, VerticalWallIsNeverGround) {
  const Small s;
  // A wall across the view at x = 5 m (inside near ring 2), from the road up to 2.7 m above it,
  // filling several sectors; nothing else in the scene.
  Cloud c;
  for (float y = -1.2f; y <= 1.2f; y += 0.05f)
    for (float z = -s.p.sensor_height; z <= 1.0f; z += 0.05f) c.Push(5.0f, y, z, 0.3f);
  const Frame f = Coarse(c, s);
  for (uint32_t i = 0; i < f.n; ++i) ASSERT_EQ(f.coarse[i], 0u) << "wall point " << i;
  const std::vector<uint32_t> cells = BusyCells(f, 1);
  ASSERT_GE(cells.size(), 3u);
  for (uint32_t cell : cells) {
    const int32_t* pl = Plane(f, cell);
    // Either no seeds, or a normal too steep for ground (threshold -1).
    EXPECT_TRUE(f.cell_seed_mode[cell] == 0 || pl[6] < 0) << "cell " << cell;
    if (f.cell_seed_mode[cell] != 0) {
      EXPECT_LT(int64_t(pl[2]) * pl[2], exact::ToFixed(s.p.normal_min_z2, float(kQ * kQ)));
    }
  }
}

TEST(CoarseSegment, BoxStandingOnTheRoadIsNotGround) {
  const Small s;
  const float road = -s.p.sensor_height;
  // A car body 0.3 .. 1.5 m above the road; if lambda grew past 0.3 m the lowest face would be
  // seed-eligible by definition, so the body then starts just above lambda.
  const float lambda = s.p.ring_res_near * s.p.slope_max + s.p.seed_margin;
  const float bottom = road + std::max(0.3f, lambda + 0.05f), top = road + 1.5f;
  const float bx0 = 8.0f, bx1 = 12.0f, by = 0.9f;
  Cloud c;
  // The road around it (not under it: the body shadows it).
  for (float x = 4.2f; x <= 15.8f; x += 0.05f)
    for (float y = -2.5f; y <= 2.5f; y += 0.1f)
      if (!(x >= bx0 && x <= bx1 && std::fabs(y) <= by)) c.Push(x, y, road, 0.2f);
  const uint32_t road_points = uint32_t(c.size());
  for (float y = -by; y <= by; y += 0.05f)  // the face toward the sensor
    for (float z = bottom; z <= top; z += 0.05f) c.Push(bx0, y, z, 0.5f);
  for (float x = bx0 + 0.05f; x <= bx1; x += 0.05f)  // the roof
    for (float y = -by; y <= by; y += 0.05f) c.Push(x, y, top, 0.5f);
  const Frame f = Coarse(c, s);
  for (uint32_t i = 0; i < road_points; ++i) EXPECT_EQ(f.coarse[i], 1u) << "road point " << i;
  uint32_t above = 0;
  for (uint32_t i = road_points; i < f.n; ++i) {
    if (f.zt[i] - road <= s.p.plane_dist_floor) continue;
    ++above;
    EXPECT_EQ(f.coarse[i], 0u) << "box point " << i << " at " << c.x(i) << ", " << c.y(i) << ", "
                               << c.z(i);
  }
  EXPECT_GT(above, 500u);
  // The road cells' planes are horizontal through the road.
  for (uint32_t i = 0; i < road_points; i += 97) {
    const int32_t* pl = Plane(f, f.point_cell[i]);
    EXPECT_NEAR(pl[5], road * 1000, 1.0);
    EXPECT_EQ(pl[2], kQ);
  }
}

TEST(CoarseSegment, CellRisingAboveItsNeighboursHasNoSeeds) {
  const Small s;
  const float road = -s.p.sensor_height;
  const float lambda = s.p.ring_res_near * s.p.slope_max + s.p.seed_margin;
  const float raised = road + lambda + s.p.rise_margin + 0.1f;
  // Road in near rings 2 and 4, a flat horizontal platform (a car roof) filling ring 3.
  Cloud c;
  for (float x = 4.1f; x <= 9.9f; x += 0.1f)
    for (float y = -0.5f; y <= 0.5f; y += 0.1f) {
      const float r = std::hypot(x, y);
      const bool ring3 = r >= 6.0f && r < 8.0f;
      c.Push(x, y, ring3 ? raised : road, 0.3f);
    }
  const Frame f = Coarse(c, s);
  uint32_t platform = 0;
  for (uint32_t i = 0; i < f.n; ++i) {
    const uint32_t ring = f.point_cell[i] / s.p.sectors_near;
    if (ring == 3) {
      ++platform;
      EXPECT_EQ(f.cell_seed_mode[f.point_cell[i]], 0u);
      EXPECT_EQ(f.coarse[i], 0u) << "platform point " << i;
    } else {
      EXPECT_EQ(f.coarse[i], 1u) << "road point " << i;
    }
  }
  EXPECT_GT(platform, 50u);
}

TEST(CoarseSegment, CellFarAboveTheSlopePriorHasNoSeeds) {
  const Small s;
  // A lone flat surface (no neighbours to compare with) higher than any ground the slope limit
  // can reach from under the sensor: -sensor_height + ground_max_above + slope_max * r_inner.
  const float inner = s.t.ring_inner[2];
  const float prior = -s.p.sensor_height + s.p.ground_max_above + s.p.slope_max * inner;
  Cloud c;
  AddPlane(&c, 4.2f, 5.8f, -0.2f, 0.2f, 0.1f, prior + 0.1f, 0, 0, 0, 3);
  AddPlane(&c, 4.2f, 5.8f, 2.0f, 2.4f, 0.1f, prior - 0.1f, 0, 0, 0, 3);  // just under it: ground
  const Frame f = Coarse(c, s);
  for (uint32_t i = 0; i < f.n; ++i) {
    const bool high = c.z(i) > prior;
    EXPECT_EQ(f.coarse[i], high ? 0u : 1u) << "point " << i << " z " << c.z(i);
    if (high) {
      EXPECT_EQ(f.cell_seed_mode[f.point_cell[i]], 0u);
    }
  }
}

// rise_carry: a raised surface over rings 4-9 (an object's side along the sector, no ground in
// its cells) rises above the road of rings 2-3 but not above its own neighbours, so the 3x3 rule
// takes only ring 4; the ground carried out from the road (+ slope_max x 2 m a ring) takes rings
// 5 and 6, and from ring 7 on the carried ground has climbed near enough.
TEST(CoarseSegment, RiseCarryHoldsAFootChainToTheGroundCarriedFromTheSensor) {
  Small s;
  const float road = -s.p.sensor_height;
  const float lambda = s.p.ring_res_near * s.p.slope_max + s.p.seed_margin;
  const float reach = s.p.ring_res_near * s.p.slope_max;
  const float raised = road + lambda + s.p.rise_margin + 0.5f;
  Cloud c;
  for (float x = 4.1f; x <= 19.9f; x += 0.1f)
    for (float y = -0.5f; y <= 0.5f; y += 0.1f) {
      const float r = std::hypot(x, y);
      c.Push(x, y, r < 8.0f ? road : raised, 0.3f);
    }
  ASSERT_LT(reach, 0.5f * (raised - road - lambda - s.p.rise_margin));
  for (uint32_t carry = 0; carry <= 1; ++carry) {
    s.p.rise_carry = carry;
    const Frame f = Coarse(c, s);
    for (uint32_t i = 0; i < f.n; ++i) {
      const uint32_t ring = f.point_cell[i] / s.p.sectors_near;
      const bool none = ring == 4 || (carry && (ring == 5 || ring == 6));
      EXPECT_EQ(f.cell_seed_mode[f.point_cell[i]] == 0u, none)
          << "rise_carry " << carry << " ring " << ring;
    }
  }
}

// rise_carry: a point far under the road (reflection noise) does not carry the ground down with
// it: the road beyond it keeps its seeds (ring 4, the noise's 3x3 neighbour, loses them to the 3x3
// rule either way).
TEST(CoarseSegment, RiseCarryIsNotDraggedDownByAPointUnderTheRoad) {
  Small s;
  s.p.rise_carry = 1;
  const float road = -s.p.sensor_height;
  Cloud c;
  for (float x = 4.1f; x <= 13.9f; x += 0.1f)
    for (float y = -0.5f; y <= 0.5f; y += 0.1f) c.Push(x, y, road, 0.3f);
  c.Push(7.0f, 0.0f, road - 1.0f, 0.3f);  // ring 3
  const Frame f = Coarse(c, s);
  for (uint32_t i = 0; i < f.n; ++i) {
    const uint32_t ring = f.point_cell[i] / s.p.sectors_near;
    if (ring >= 5) {
      EXPECT_EQ(f.coarse[i], 1u) << "road point " << i << " ring " << ring;
    }
  }
}

TEST(CoarseSegment, CollinearSeedsFallBackToTheHorizontalPlane) {
  const Small s;
  const float road = -s.p.sensor_height;
  Cloud c;
  // One scan line reduced to a straight segment across the view (x = 5 m, constant height), one
  // along the ray ahead-left (a radial line), and a cell with only two points.
  for (float y = 0.02f; y <= 0.45f; y += 0.02f) c.Push(5.0f, y, road, 0.3f);
  const uint32_t n_across = uint32_t(c.size());
  for (float r = 6.1f; r <= 7.9f; r += 0.1f) c.Push(r, 0.1f, road + 0.01f, 0.3f);
  const uint32_t n_radial = uint32_t(c.size());
  c.Push(-5.0f, 0.1f, road, 0.3f);
  c.Push(-5.5f, 0.1f, road + 0.02f, 0.3f);
  const Frame f = Coarse(c, s);
  const uint32_t cells[3] = {f.point_cell[0], f.point_cell[n_across], f.point_cell[n_radial]};
  ASSERT_NE(cells[0], cells[1]);
  ASSERT_NE(cells[1], cells[2]);
  for (uint32_t cell : cells) {
    SCOPED_TRACE("cell " + std::to_string(cell));
    const int32_t* pl = Plane(f, cell);
    EXPECT_NE(f.cell_seed_mode[cell], 0u);
    EXPECT_EQ(pl[0], 0);
    EXPECT_EQ(pl[1], 0);
    EXPECT_EQ(pl[2], kQ);
    EXPECT_EQ(uint32_t(pl[7]), f.cell_count[cell]);
    EXPECT_GE(pl[6], 0);
  }
  // Horizontal plane through the seed mean: z of the mean in mm.
  EXPECT_NEAR(Plane(f, cells[2])[5], (road + 0.01f) * 1000, 1.0);
  for (uint32_t i = 0; i < f.n; ++i) EXPECT_EQ(f.coarse[i], 1u) << "point " << i;
}

// A straight line of seeds climbing along one ray is collinear up to the mm rounding, which leaves
// the x-z moments of rank 2 with yy = 0: the fit must still take it as collinear and give the
// horizontal fallback through the seed mean (threshold >= 0), not the vertical plane y = const
// (threshold -1), which would take the cell's ground away.
TEST(CoarseSegment, CollinearSlopedSeedsFallBackToTheHorizontalPlane) {
  const Small s;
  // Any plane through the line fits it; the contract picks the horizontal one through the mean.
  // The line's points are all within the floor of it, so they are ground.
  const float road = -s.p.sensor_height, grade = 0.04f;
  ASSERT_LT(grade * 1.0f, s.p.plane_dist_floor);
  Cloud c;
  for (float x = 4.05f; x <= 5.95f; x += 0.01f) c.Push(x, 0.1f, road + grade * (x - 4.0f), 0.3f);
  const Frame f = Coarse(c, s);
  const uint32_t cell = f.point_cell[0];
  for (uint32_t i = 0; i < f.n; ++i) ASSERT_EQ(f.point_cell[i], cell);
  const int32_t* pl = Plane(f, cell);
  EXPECT_EQ(pl[0], 0);
  EXPECT_EQ(pl[1], 0);
  EXPECT_EQ(pl[2], kQ);
  EXPECT_GE(pl[6], 0);
  for (uint32_t i = 0; i < f.n; ++i) EXPECT_EQ(f.coarse[i], 1u) << "point " << i;
}

TEST(CoarseSegment, EmptyCloud) {
  const Small s;
  const Cloud c;
  const Frame f = Coarse(c, s);
  EXPECT_TRUE(f.coarse.empty());
  ASSERT_EQ(f.cell_seed_mode.size(), CellCount(s.p));
  ASSERT_EQ(f.cell_plane.size(), size_t(CellCount(s.p)) * 8);
  for (uint32_t m : f.cell_seed_mode) EXPECT_EQ(m, 0u);
  for (int32_t v : f.cell_plane) EXPECT_EQ(v, 0);
}

TEST(CoarseSegment, PointOrderDoesNotChangeThePlanes) {
  const Small s;
  Cloud c;
  AddPlane(&c, 4.2f, 17.8f, -3.0f, 3.0f, 0.1f, -s.p.sensor_height, 0.02f, -0.01f, 0.02f, 4);
  for (float y = -0.9f; y <= 0.9f; y += 0.05f)  // an object on it
    for (float z = -1.2f; z <= 0.0f; z += 0.05f) c.Push(10.0f, y, z, 0.6f);
  for (float x = 25.0f; x <= 40.0f; x += 0.2f)  // and some far-zone ground
    for (float y = -4.0f; y <= 4.0f; y += 0.2f) c.Push(x, y, -s.p.sensor_height + 0.01f * x, 0.2f);
  const Frame a = Coarse(c, s);
  std::vector<uint32_t> perm(c.size());
  std::iota(perm.begin(), perm.end(), 0u);
  for (uint32_t trial = 0; trial < 3; ++trial) {
    std::mt19937 rng(100 + trial);
    std::shuffle(perm.begin(), perm.end(), rng);
    Cloud shuffled;
    for (uint32_t k = 0; k < perm.size(); ++k)
      shuffled.Push(c.x(perm[k]), c.y(perm[k]), c.z(perm[k]), c.intensity(perm[k]));
    const Frame b = Coarse(shuffled, s);
    EXPECT_EQ(a.cell_seed_mode, b.cell_seed_mode);
    EXPECT_EQ(a.cell_plane, b.cell_plane);
    for (uint32_t k = 0; k < perm.size(); ++k)
      ASSERT_EQ(b.coarse[k], a.coarse[perm[k]]) << "shuffled point " << k;
  }
  // The scene exercised both seed modes and both labels.
  uint32_t modes[3] = {0, 0, 0}, ground = 0;
  for (uint32_t cell = 0; cell < a.cell_count.size(); ++cell)
    if (a.cell_count[cell]) ++modes[a.cell_seed_mode[cell]];
  for (uint32_t l : a.coarse) ground += l;
  EXPECT_GT(modes[1], 0u);
  EXPECT_GT(modes[2], 0u);
  EXPECT_GT(ground, 0u);
  EXPECT_LT(ground, a.n);
}

// Points exactly on the thresholds of eq. 5 (tests/coarse_segment_inputs.h; the kernel runs on them
// in coarse_segment_vk_test.cpp): each comparison includes its bound. A cell whose spread equals
// h_athr is whole, seeds exactly lambda above the lowest point are seeds, and a cell raised
// exactly lambda + rise_margin above its neighbours keeps its seeds.
TEST(CoarseSegment, PointsExactlyOnTheSeedThresholdsCountAsInside) {
  Small s;
  const Cloud c = test::SeedThresholdCloud(&s.p);
  const Frame f = Coarse(c, s);
  const uint32_t whole = f.point_cell[0], lowest = f.point_cell[60];
  for (uint32_t i = 0; i < 60; ++i) ASSERT_EQ(f.point_cell[i], whole) << "point " << i;
  for (uint32_t i = 60; i < 120; ++i) ASSERT_EQ(f.point_cell[i], lowest) << "point " << i;
  EXPECT_EQ(f.cell_seed_mode[whole], 2u);
  EXPECT_EQ(f.cell_seed_mode[lowest], 1u);
  EXPECT_EQ(Plane(f, lowest)[7], 40);  // the points at the lowest and exactly lambda above it
  size_t raised = 0;
  for (uint32_t i = 120; i < f.n; ++i) {
    const float r = std::hypot(c.x(i), c.y(i));
    if (r < 8.0f || r >= 10.0f) continue;
    ++raised;
    EXPECT_NE(f.cell_seed_mode[f.point_cell[i]], 0u) << "raised point " << i;
  }
  EXPECT_GT(raised, 50u);
}

}  // namespace
}  // namespace lpir
