// The whole pipeline (lpir::Segmenter on the CPU reference, HDL-64E profile) on simulated
// scenes with known truth (apps/sim): a flat plane, the plane with a car and a wall, and urban
// streets with a ramp, curbs, sidewalks, cars, buildings and vegetation. Plus determinism of
// every Frame buffer.
#include <gtest/gtest.h>

#include <cstring>
#include <string>
#include <vector>

#include "apps/sim/scene.h"
#include "host/api/segmenter.h"
#include "host/eval/metrics.h"
#include "host/io/sensor_profile.h"

namespace lpir {
namespace {

SensorProfile Hdl64() { return LoadSensorProfile("hdl64e", LPIR_SENSORS_DIR); }

SimScan Scene(SceneKind kind, uint32_t seed) {
  SimOptions o;
  o.seed = seed;
  o.kind = kind;
  return Simulate(Hdl64(), o);
}

// Points of one class (or of a predicate) and how many of them were labelled ground.
struct Tally {
  size_t points = 0, ground = 0;
  double Fraction() const { return points ? double(ground) / double(points) : 0.0; }
};

Tally CountClass(const SimScan& scan, const Frame& f, uint32_t cls) {
  Tally t;
  for (size_t i = 0; i < scan.labels.size(); ++i)
    if ((scan.labels[i] & 0xFFFF) == cls) ++t.points, t.ground += f.label[i];
  return t;
}

Labels Predicted(const Frame& f) { return Labels(f.label.begin(), f.label.end()); }

TEST(PipelineScenes, FlatPlaneIsAllGround) {
  const SimScan scan = Scene(kFlat, 3);
  Segmenter seg(Hdl64(), SegmenterOptions::For(Backend::kCpu));
  const Frame& f = seg.Segment(scan.cloud);
  ASSERT_EQ(f.label.size(), scan.cloud.size());
  const Counts c = CountFrame(Protocol::kDG, Predicted(f), scan.labels, nullptr);
  const Scores s = ScoreCounts(c);
  RecordProperty("recall", std::to_string(s.recall));
  EXPECT_GT(c.tp, 50000u);
  EXPECT_GE(s.recall, 0.99);
  EXPECT_EQ(c.fp, 0u) << "reflection noise (the only non-ground) labelled ground";
}

TEST(PipelineScenes, CarAndWallOnAFlatPlaneAreNotGround) {
  for (uint32_t seed : {1u, 2u}) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    const SimScan scan = Scene(kFlatWithObjects, seed);
    Segmenter seg(Hdl64(), SegmenterOptions::For(Backend::kCpu));
    const Frame& f = seg.Segment(scan.cloud);
    const Tally car = CountClass(scan, f, SkClass::kCar);
    const Tally wall = CountClass(scan, f, SkClass::kBuilding);
    const Tally road = CountClass(scan, f, SkClass::kRoad);
    EXPECT_GT(car.points, 500u);
    EXPECT_GT(wall.points, 2000u);
    EXPECT_EQ(car.ground, 0u);
    EXPECT_EQ(wall.ground, 0u);
    RecordProperty("road_recall_seed" + std::to_string(seed), std::to_string(road.Fraction()));
    EXPECT_GE(road.Fraction(), 0.98);
  }
}

// A car point this high above the walkable ground under it is the body, not a wheel's contact.
constexpr double kAboveContact = 0.1;  // m

// Whether car point i of `scan` lies more than kAboveContact above the ground under it (world
// frame).
bool CarBody(const SimScan& scan, size_t i) {
  const double p[3] = {scan.cloud.x(i), scan.cloud.y(i), scan.cloud.z(i)};
  double w[3];
  scan.scene.SensorToWorld(p, w);
  return w[2] > scan.scene.GroundHeight(w[0], w[1]) + kAboveContact;
}

// What one urban street scored; car_body: the car points off the ground (CarBody).
struct Street {
  Counts dg;
  Tally car, car_body, ramp, sidewalk;
  double grade = 0;
};

Street Score(const SimScan& scan, const Frame& f) {
  Street st;
  st.dg = CountFrame(Protocol::kDG, Predicted(f), scan.labels, nullptr);
  st.car = CountClass(scan, f, SkClass::kCar);
  for (size_t i = 0; i < scan.labels.size(); ++i)
    if ((scan.labels[i] & 0xFFFF) == SkClass::kCar && CarBody(scan, i))
      ++st.car_body.points, st.car_body.ground += f.label[i];
  st.sidewalk = CountClass(scan, f, SkClass::kSidewalk);  // sidewalk tops and curb faces
  // The ramp's road surface: road or paint on the road, along the climbing stretch (world frame).
  const SimScene& sc = scan.scene;
  st.grade = sc.ramp_grade;
  for (size_t i = 0; i < scan.labels.size(); ++i) {
    const uint32_t cls = scan.labels[i] & 0xFFFF;
    if (cls != SkClass::kRoad && cls != SkClass::kLaneMarking) continue;
    const double p[3] = {scan.cloud.x(i), scan.cloud.y(i), scan.cloud.z(i)};
    double w[3];
    sc.SensorToWorld(p, w);
    if (w[0] < sc.ramp_start_x || w[0] > sc.ramp_start_x + sc.ramp_length) continue;
    if (std::abs(w[1] - sc.road_center_y) > sc.road_half_width) continue;
    ++st.ramp.points, st.ramp.ground += f.label[i];
  }
  return st;
}

// Floors a little under what seeds 1, 2, 4 measure pooled (the test prints them; the measured
// values per sensor profile are in docs/decisions/sensors.md).
constexpr double kUrbanF1Floor = 0.97;  // the target: DG F1 >= 97 %
constexpr double kUrbanPrecisionFloor = 0.99;
constexpr double kRampGroundFloor = 0.94;      // road points on the 8-10 % ramp labelled ground
constexpr double kSidewalkGroundFloor = 0.97;  // sidewalk and curb points labelled ground

// Streets without a car parked right beside the sensor (see the disabled test below for those).
TEST(PipelineScenes, UrbanStreets) {
  Segmenter seg(Hdl64(), SegmenterOptions::For(Backend::kCpu));
  Counts summed;
  Tally ramp, sidewalk;
  for (uint32_t seed : {1u, 2u, 4u}) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    const SimScan scan = Scene(kUrban, seed);
    const Street st = Score(scan, seg.Segment(scan.cloud));
    summed += st.dg;
    ramp.points += st.ramp.points, ramp.ground += st.ramp.ground;
    sidewalk.points += st.sidewalk.points, sidewalk.ground += st.sidewalk.ground;
    std::printf(
        "seed %u: DG F1 %.4f, car %zu / %zu, ramp %zu / %zu = %.4f (grade %.3f), "
        "sidewalk %zu / %zu = %.4f\n",
        seed, ScoreCounts(st.dg).f1, st.car.ground, st.car.points, st.ramp.ground, st.ramp.points,
        st.ramp.Fraction(), st.grade, st.sidewalk.ground, st.sidewalk.points,
        st.sidewalk.Fraction());
    EXPECT_GT(st.car.points, 1000u);
    // A wheel's lowest hit, at the road's height, seen under the body may pass as ground (the
    // veto's occ_pass); no point of a body may.
    EXPECT_EQ(st.car_body.ground, 0u) << "car body points labelled ground";
    EXPECT_LE(st.car.ground * 1000, st.car.points) << "car points labelled ground";
    ASSERT_GE(st.grade, 0.08);
    EXPECT_GT(st.ramp.points, 300u);
    EXPECT_GT(st.sidewalk.points, 1000u);
  }
  // DG sums the counts over the sequence.
  const Scores s = ScoreCounts(summed);
  std::printf(
      "summed: DG P %.4f R %.4f F1 %.4f, ramp %zu / %zu = %.4f, sidewalk %zu / %zu = "
      "%.4f\n",
      s.precision, s.recall, s.f1, ramp.ground, ramp.points, ramp.Fraction(), sidewalk.ground,
      sidewalk.points, sidewalk.Fraction());
  RecordProperty("dg_f1", std::to_string(s.f1));
  RecordProperty("ramp_ground", std::to_string(ramp.Fraction()));
  RecordProperty("sidewalk_ground", std::to_string(sidewalk.Fraction()));
  EXPECT_GE(s.f1, kUrbanF1Floor);
  EXPECT_GE(s.precision, kUrbanPrecisionFloor);
  EXPECT_GE(ramp.Fraction(), kRampGroundFloor);
  EXPECT_GE(sidewalk.Fraction(), kSidewalkGroundFloor);
}

// A car parked right beside the sensor (2-6 m away, seed 3): its roof cells have only roof cells
// around them (no rise over the 3x3 neighbourhood), so only the slope prior of coarse_segment keeps
// the roof out of the seeds (ground_max_above; 5727 of 29240 car points were ground at 0.6).
TEST(PipelineScenes, CarParkedBesideTheSensorIsNotGround) {
  Segmenter seg(Hdl64(), SegmenterOptions::For(Backend::kCpu));
  const SimScan scan = Scene(kUrban, 3);
  const Frame& f = seg.Segment(scan.cloud);
  const Street st = Score(scan, f);
  size_t beside = 0, beside_ground = 0;  // the parked car's points, within 10 m
  for (size_t i = 0; i < scan.labels.size(); ++i) {
    const float x = scan.cloud.x(i), y = scan.cloud.y(i);
    if ((scan.labels[i] & 0xFFFF) != SkClass::kCar || x * x + y * y > 100.0f) continue;
    ++beside, beside_ground += f.label[i];
  }
  EXPECT_GT(beside, 10000u);
  EXPECT_EQ(beside_ground, 0u) << "points of the car beside the sensor labelled ground";
  EXPECT_LE(st.car.ground, 10u) << "car points labelled ground, the far cars included";
  EXPECT_GE(ScoreCounts(st.dg).precision, kUrbanPrecisionFloor);
}

// Streets where a car is parked right beside the sensor (seeds 13 and 18): a plane fitted to the
// few seeds under its body may tilt by 25 degrees (seed 13) and must not put the roof, 0.29 m from
// it, on the ground. Near the sensor no car body point may be ground (a wheel's contact with the
// road may: CarBody); far away a lone body point in a 4 m cell can still pass (seed 13: one point
// at 68 m, 0.5 m above the road), so overall the bound is 0.1 %.
TEST(PipelineScenes, CarRoofIsNotGroundNextToATiltedCellPlane) {
  Segmenter seg(Hdl64(), SegmenterOptions::For(Backend::kCpu));
  for (uint32_t seed : {13u, 18u}) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    const SimScan scan = Scene(kUrban, seed);
    const Frame& f = seg.Segment(scan.cloud);
    const Street st = Score(scan, f);
    EXPECT_GT(st.car.points, 10000u);
    EXPECT_LE(st.car.ground * 1000, st.car.points) << "car points labelled ground";
    size_t near_car_ground = 0;
    for (size_t i = 0; i < scan.labels.size(); ++i) {
      const float x = scan.cloud.x(i), y = scan.cloud.y(i);
      if ((scan.labels[i] & 0xFFFF) == SkClass::kCar && f.label[i] && x * x + y * y < 1600.0f &&
          CarBody(scan, i))
        ++near_car_ground;
    }
    EXPECT_EQ(near_car_ground, 0u) << "car body points within 40 m labelled ground";
  }
}

// Every buffer of a Frame, by name, as bytes.
struct Buffer {
  const char* name;
  const void* data;
  size_t bytes;
};
template <typename T>
Buffer Of(const char* name, const std::vector<T>& v) {
  return {name, v.data(), v.size() * sizeof(T)};
}
std::vector<Buffer> Buffers(const Frame& f) {
  return {Of("flags", f.flags),
          Of("zt", f.zt),
          Of("r2", f.r2),
          Of("point_pixel", f.point_pixel),
          Of("pixel_key", f.pixel_key),
          Of("pixel_point", f.pixel_point),
          Of("point_cell", f.point_cell),
          Of("cell_zmin", f.cell_zmin),
          Of("cell_zmax", f.cell_zmax),
          Of("cell_count", f.cell_count),
          Of("cell_seed_mode", f.cell_seed_mode),
          Of("cell_plane", f.cell_plane),
          Of("coarse", f.coarse),
          Of("pixel_filled", f.pixel_filled),
          Of("f_range", f.f_range),
          Of("f_height", f.f_height),
          Of("f_slope", f.f_slope),
          Of("f_edge_l", f.f_edge_l),
          Of("f_edge_r", f.f_edge_r),
          Of("f_varz", f.f_varz),
          Of("pixel_class", f.pixel_class),
          Of("pixel_fused", f.pixel_fused),
          Of("pixel_grown", f.pixel_grown),
          Of("pixel_comp", f.pixel_comp),
          Of("pixel_label", f.pixel_label),
          Of("label", f.label),
          Of("why", f.why),
          Of("label_why", f.label_why)};
}

TEST(PipelineScenes, SegmentingTwiceGivesIdenticalBytes) {
  const SimScan scan = Scene(kUrban, 4);
  const SimScan other = Scene(kUrban, 5);
  Segmenter a(Hdl64(), SegmenterOptions::For(Backend::kCpu));
  Segmenter b(Hdl64(), SegmenterOptions::For(Backend::kCpu));
  const Frame first = a.Segment(scan.cloud);  // a copy
  a.Segment(other.cloud);                     // the reused buffers hold another frame meanwhile
  const Frame& again = a.Segment(scan.cloud);
  const Frame& fresh = b.Segment(scan.cloud);
  const std::vector<Buffer> x = Buffers(first), y = Buffers(again), z = Buffers(fresh);
  ASSERT_EQ(x.size(), 28u);
  for (size_t k = 0; k < x.size(); ++k) {
    SCOPED_TRACE(x[k].name);
    EXPECT_GT(x[k].bytes, 0u);
    ASSERT_EQ(x[k].bytes, y[k].bytes);
    ASSERT_EQ(x[k].bytes, z[k].bytes);
    EXPECT_EQ(0, std::memcmp(x[k].data, y[k].data, x[k].bytes));
    EXPECT_EQ(0, std::memcmp(x[k].data, z[k].data, x[k].bytes));
  }
  EXPECT_EQ(first.n, scan.cloud.size());
}

}  // namespace
}  // namespace lpir
