// Builds the simulator's scenes from a seed: the street layout (road, ramp, curbs, sidewalks,
// terrain, buildings, parked cars, poles, vegetation) or the flat calibration scenes, plus the
// sensor pose that realises the tilt sign convention documented in scene.h.
#include "apps/sim/scene.h"

#include <algorithm>
#include <cmath>

#include "apps/sim/sim_random.h"

namespace lpir {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kHalfLength = 100.0;    // m, the street runs over x in [-100, 100]
constexpr double kTerrainDepth = 50.0;   // m of terrain beyond each sidewalk
constexpr double kFlatHalfSize = 150.0;  // m, half the side of the flat scenes' plane

SimPrimitive MakeBox(uint32_t label, double x0, double x1, double y0, double y1, double z0,
                     double z1, float reflectivity, float jitter) {
  SimPrimitive p;
  p.shape = SimShape::kBox;
  p.label = label;
  p.reflectivity = reflectivity;
  p.reflectivity_jitter = jitter;
  p.lo[0] = std::min(x0, x1), p.hi[0] = std::max(x0, x1);
  p.lo[1] = std::min(y0, y1), p.hi[1] = std::max(y0, y1);
  p.lo[2] = std::min(z0, z1), p.hi[2] = std::max(z0, z1);
  return p;
}

// A ground piece over x in [x0, x1], y in [y0, y1] whose height starts at z_start at x0 and rises
// by `slope` per metre of x.
SimPrimitive MakePatch(uint32_t label, double x0, double x1, double y0, double y1, double z_start,
                       double slope, float reflectivity, float jitter, double roughness) {
  SimPrimitive p;
  p.shape = SimShape::kHeightPatch;
  p.label = label;
  p.reflectivity = reflectivity;
  p.reflectivity_jitter = jitter;
  p.lo[0] = x0, p.hi[0] = x1;
  p.lo[1] = std::min(y0, y1), p.hi[1] = std::max(y0, y1);
  const double z_end = z_start + slope * (x1 - x0);
  p.lo[2] = std::min(z_start, z_end), p.hi[2] = std::max(z_start, z_end);
  p.z0 = z_start;
  p.slope = slope;
  p.roughness = roughness;
  return p;
}

// A car standing on ground of height g, centred at (cx, cy), along x: a body box from ~0.3 m to
// ~1 m, a cabin box up to ~1.5 m and four wheels (cylinders along y) touching the ground, so the
// car's lowest surfaces meet the road as in real scans.
void AddCar(SimRandom& rng, double cx, double cy, double g, std::vector<SimPrimitive>* out) {
  const double length = rng.Uniform(3.9, 4.8);
  const double width = rng.Uniform(1.7, 1.9);
  const double height = rng.Uniform(1.4, 1.6);
  const double clearance = rng.Uniform(0.28, 0.34);
  const double body_top = rng.Uniform(0.9, 1.05);
  const double facing = rng.Chance(0.5) ? 1.0 : -1.0;
  const double wheel_r = rng.Uniform(0.31, 0.35);
  const double wheel_x = length / 2 - rng.Uniform(0.7, 0.9);
  const float paint = static_cast<float>(rng.Uniform(0.03, 0.35));
  const float rubber = static_cast<float>(rng.Uniform(0.01, 0.06));
  const double hl = length / 2, hw = width / 2;
  out->push_back(MakeBox(SkClass::kCar, cx - hl, cx + hl, cy - hw, cy + hw, g + clearance,
                         g + body_top, paint, 0.04f));
  out->push_back(MakeBox(SkClass::kCar, cx - facing * 0.35 * length, cx + facing * 0.2 * length,
                         cy - hw + 0.1, cy + hw - 0.1, g + body_top - 0.01, g + height,
                         paint * 0.7f, 0.04f));
  for (double sx : {-1.0, 1.0}) {
    for (double sy : {-1.0, 1.0}) {
      SimPrimitive w =
          MakeBox(SkClass::kCar, cx + sx * wheel_x - wheel_r, cx + sx * wheel_x + wheel_r,
                  cy + sy * (hw - 0.02), cy + sy * (hw - 0.25), g, g + 2 * wheel_r, rubber, 0.02f);
      w.shape = SimShape::kCylinderY;
      out->push_back(w);
    }
  }
}

// A bumpy ellipsoid (bush or crown) with radii rx, ry, rz centred at (cx, cy, cz).
void AddBlob(SimRandom& rng, uint32_t label, double cx, double cy, double cz, double rx, double ry,
             double rz, std::vector<SimPrimitive>* out) {
  SimPrimitive p = MakeBox(label, cx - rx, cx + rx, cy - ry, cy + ry, cz - rz, cz + rz,
                           static_cast<float>(rng.Uniform(0.25, 0.45)), 0.12f);
  p.shape = SimShape::kEllipsoid;
  p.bump = std::min(0.12, 0.1 * std::min(rx, std::min(ry, rz)) + 0.04);
  for (double& phase : p.bump_phase) phase = rng.Uniform(0.0, 2 * kPi);
  out->push_back(p);
}

void AddTree(SimRandom& rng, double x, double y, double g, std::vector<SimPrimitive>* out) {
  const double r = rng.Uniform(0.1, 0.2);
  const double trunk = rng.Uniform(1.8, 3.0);
  SimPrimitive t = MakeBox(SkClass::kTrunk, x - r, x + r, y - r, y + r, g - 0.3, g + trunk + 0.3,
                           static_cast<float>(rng.Uniform(0.2, 0.35)), 0.05f);
  t.shape = SimShape::kCylinderZ;
  out->push_back(t);
  const double crown = rng.Uniform(1.5, 2.8);
  AddBlob(rng, SkClass::kVegetation, x, y, g + trunk + 0.7 * crown, crown, crown,
          crown * rng.Uniform(0.7, 1.0), out);
}

void AddPole(SimRandom& rng, double x, double y, double g, double toward_road,
             std::vector<SimPrimitive>* out) {
  const double r = rng.Uniform(0.05, 0.12);
  const double h = rng.Uniform(4.0, 8.0);
  SimPrimitive p = MakeBox(SkClass::kPole, x - r, x + r, y - r, y + r, g - 0.3, g + h,
                           static_cast<float>(rng.Uniform(0.1, 0.4)), 0.05f);
  p.shape = SimShape::kCylinderZ;
  out->push_back(p);
  if (rng.Chance(0.3)) {  // a sign plate facing along the road, hanging over the sidewalk edge
    const double yc = y + toward_road * 0.4;
    out->push_back(MakeBox(SkClass::kTrafficSign, x + r + 0.01, x + r + 0.05, yc - 0.35, yc + 0.35,
                           g + 2.1, g + 2.8, 0.85f, 0.05f));
  }
}

void BuildUrban(SimRandom& rng, SimScene* s) {
  const double yc = s->road_center_y = rng.Uniform(-0.3, 0.3);
  const double hw = s->road_half_width = rng.Uniform(3.5, 4.5);
  for (int side = 0; side < 2; ++side) {
    s->curb_height[side] = rng.Uniform(0.10, 0.15);
    s->sidewalk_width[side] = rng.Uniform(2.0, 4.0);
  }
  s->ramp_start_x = rng.Uniform(20.0, 25.0);
  s->ramp_length = rng.Uniform(15.0, 20.0);
  s->ramp_grade = rng.Uniform(0.08, 0.10);
  s->parking_line_offset = hw - rng.Uniform(2.1, 2.4);
  const double ramp_end = s->ramp_start_x + s->ramp_length;
  std::vector<SimPrimitive>& prims = s->primitives;

  // Ground: three stretches along x (flat, ramp, flat) x five bands across (terrain, sidewalk,
  // road, sidewalk, terrain), and the vertical curb faces between road and sidewalks.
  const float asphalt = static_cast<float>(rng.Uniform(0.12, 0.26));
  const float paving = static_cast<float>(rng.Uniform(0.26, 0.33));
  const float grass = static_cast<float>(rng.Uniform(0.3, 0.4));
  const double xs[4] = {-kHalfLength, s->ramp_start_x, ramp_end, kHalfLength};
  for (int k = 0; k < 3; ++k) {
    const double x0 = xs[k], x1 = xs[k + 1];
    const double z = s->RoadHeight(x0);
    const double slope = k == 1 ? s->ramp_grade : 0.0;
    SimPrimitive road =
        MakePatch(SkClass::kRoad, x0, x1, yc - hw, yc + hw, z, slope, asphalt, 0.05f, 0.004);
    road.lane_markings = true;
    prims.push_back(road);
    for (int side = 0; side < 2; ++side) {
      const double dir = side == 0 ? -1.0 : 1.0;
      const double edge = yc + dir * hw;
      const double outer = edge + dir * s->sidewalk_width[side];
      const double top = z + s->curb_height[side];
      prims.push_back(
          MakePatch(SkClass::kSidewalk, x0, x1, edge, outer, top, slope, paving, 0.04f, 0.003));
      SimPrimitive curb =
          MakePatch(SkClass::kSidewalk, x0, x1, edge, edge, z, slope, paving, 0.04f, 0.0);
      curb.shape = SimShape::kCurbFace;
      curb.height = s->curb_height[side];
      curb.hi[2] += curb.height;
      prims.push_back(curb);
      prims.push_back(MakePatch(SkClass::kTerrain, x0, x1, outer, outer + dir * kTerrainDepth, top,
                                slope, grass, 0.08f, 0.03));
    }
  }

  // Beyond each sidewalk: buildings, and gaps of terrain with bushes, trees and low walls.
  for (int side = 0; side < 2; ++side) {
    const double dir = side == 0 ? -1.0 : 1.0;
    const double outer = yc + dir * (hw + s->sidewalk_width[side]);
    double x = -kHalfLength;
    while (x < kHalfLength) {
      if (rng.Chance(0.65)) {
        const double len = rng.Uniform(10.0, 30.0);
        const double setback = rng.Chance(0.3) ? 0.0 : rng.Uniform(0.3, 3.0);
        const double depth = rng.Uniform(8.0, 16.0);
        const double height = rng.Uniform(3.0, 10.0);
        const double x1 = std::min(x + len, kHalfLength);
        const double front = outer + dir * setback;
        const double base = std::min(s->GroundHeight(x, outer), s->GroundHeight(x1, outer));
        const double top = s->GroundHeight(0.5 * (x + x1), outer) + height;
        prims.push_back(MakeBox(SkClass::kBuilding, x, x1, front, front + dir * depth, base - 1.0,
                                top, static_cast<float>(rng.Uniform(0.15, 0.5)), 0.06f));
        if (setback > 1.5 && rng.Chance(0.5)) {  // a bush in the front yard
          const double bx = rng.Uniform(x + 1.0, x1 - 1.0);
          const double by = outer + dir * 0.5 * setback;
          const double r = 0.45 * setback;
          // One draw per statement: the order of a call's arguments is unspecified (GCC took
          // the last first, clang the first); this is GCC's order, so its scenes are unchanged.
          const double rz = r * rng.Uniform(0.8, 1.5);
          const double rx = rng.Uniform(0.8, 2.0);
          AddBlob(rng, SkClass::kVegetation, bx, by, s->GroundHeight(bx, by) + 0.4 * r, rx, r, rz,
                  &prims);
        }
        x += len;
      } else {
        const double len = rng.Uniform(5.0, 15.0);
        const int bushes = 1 + static_cast<int>(rng.Uniform() * 3.0);
        for (int b = 0; b < bushes; ++b) {
          const double rx = rng.Uniform(0.5, 1.5), ry = rng.Uniform(0.5, 1.2);
          const double rz = rng.Uniform(0.4, 0.9);
          const double bx = rng.Uniform(x, x + len);
          const double by = outer + dir * rng.Uniform(ry + 0.3, ry + 8.0);
          AddBlob(rng, SkClass::kVegetation, bx, by, s->GroundHeight(bx, by) + 0.6 * rz, rx, ry, rz,
                  &prims);
        }
        if (rng.Chance(0.5)) {
          const double tx = rng.Uniform(x + 1.0, x + len - 1.0);
          const double ty = outer + dir * rng.Uniform(3.0, 10.0);
          AddTree(rng, tx, ty, s->GroundHeight(tx, ty), &prims);
        }
        if (rng.Chance(0.35)) {  // a low wall along the sidewalk
          const double wy = outer + dir * rng.Uniform(0.3, 1.0);
          const double wx0 = x + 0.5, wx1 = std::min(x + len - 0.5, kHalfLength);
          const double base = std::min(s->GroundHeight(wx0, wy), s->GroundHeight(wx1, wy));
          const float reflectivity = static_cast<float>(rng.Uniform(0.2, 0.4));  // GCC's order
          const double top = s->GroundHeight(0.5 * (wx0 + wx1), wy) + rng.Uniform(0.5, 1.0);
          prims.push_back(MakeBox(SkClass::kFence, wx0, wx1, wy, wy + dir * 0.25, base - 0.3, top,
                                  reflectivity, 0.05f));
        }
        x += len;
      }
    }
  }

  // Poles on the sidewalks near the curbs.
  for (int side = 0; side < 2; ++side) {
    const double dir = side == 0 ? -1.0 : 1.0;
    const double edge = yc + dir * hw;
    for (double x = -kHalfLength + rng.Uniform(0.0, 20.0); x < kHalfLength;
         x += rng.Uniform(15.0, 30.0)) {
      const double y = edge + dir * rng.Uniform(0.3, 0.7);
      AddPole(rng, x, y, s->GroundHeight(x, y), -dir, &prims);
    }
  }

  // Parked cars along both curbs (not on the ramp), and one car on the road ahead.
  for (int side = 0; side < 2; ++side) {
    const double dir = side == 0 ? -1.0 : 1.0;
    double x = -70.0 + rng.Uniform(0.0, 5.0);
    while (x < 70.0) {
      const double slot = rng.Uniform(4.2, 5.2);
      const bool parked = rng.Chance(0.6);
      const double cx = x + slot / 2;
      const bool on_ramp = x + slot > s->ramp_start_x - 2.0 && x < ramp_end + 2.0;
      if (parked && !on_ramp) {
        const double cy = yc + dir * (hw - 0.25 - 0.95);
        AddCar(rng, cx, cy, s->RoadHeight(cx), &prims);
      }
      x += slot + rng.Uniform(0.8, 6.0);
    }
  }
  const double ahead = rng.Uniform(10.0, 15.0);
  AddCar(rng, ahead, yc + rng.Uniform(-0.3, 0.3), s->RoadHeight(ahead), &prims);
}

void BuildFlat(SimRandom& rng, bool with_objects, SimScene* s) {
  s->road_half_width = kFlatHalfSize;
  s->primitives.push_back(MakePatch(SkClass::kRoad, -kFlatHalfSize, kFlatHalfSize, -kFlatHalfSize,
                                    kFlatHalfSize, 0.0, 0.0, 0.2f, 0.03f, 0.0));
  if (!with_objects) return;
  const double car_y = rng.Uniform(-0.3, 0.3);  // GCC's order of the call's arguments
  const double car_x = rng.Uniform(9.0, 11.0);
  AddCar(rng, car_x, car_y, 0.0, &s->primitives);
  const double wall_y = rng.Uniform(5.0, 6.0);
  s->primitives.push_back(
      MakeBox(SkClass::kBuilding, -15.0, 15.0, wall_y, wall_y + 0.3, -0.5, 2.5, 0.35f, 0.05f));
}

double Dot(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

}  // namespace

bool IsSimGroundClass(uint32_t label) {
  const uint32_t c = label & 0xFFFFu;
  return c == 40 || c == 44 || c == 48 || c == 49 || c == 60 || c == 72;
}

double SimScene::RoadHeight(double x) const {
  if (x <= ramp_start_x) return 0.0;
  return ramp_grade * (std::min(x, ramp_start_x + ramp_length) - ramp_start_x);
}

double SimScene::GroundHeight(double x, double y) const {
  const double dy = y - road_center_y;
  if (std::abs(dy) <= road_half_width) return RoadHeight(x);
  return RoadHeight(x) + curb_height[dy < 0 ? 0 : 1];
}

bool SimScene::IsLaneMarking(double x, double y) const {
  if (kind != kUrban) return false;
  constexpr double kHalfLine = 0.075;  // 15 cm wide paint
  const double dy = std::abs(y - road_center_y);
  if (std::abs(dy - parking_line_offset) < kHalfLine) return true;  // solid
  if (dy >= kHalfLine) return false;
  const double phase = std::fmod(x + 1000.0, 9.0);  // 3 m dashes, 6 m gaps
  return phase < 3.0;
}

void SimScene::SensorToWorld(const double p[3], double out[3]) const {
  DirectionToWorld(p, out);
  out[2] += sensor_z;
}

void SimScene::DirectionToWorld(const double d[3], double out[3]) const {
  out[0] = Dot(world_x, d);
  out[1] = Dot(world_y, d);
  out[2] = Dot(world_z, d);
}

SimScene BuildScene(const SimOptions& options, double sensor_height) {
  SimScene s;
  s.kind = options.kind;

  // Pose (scene.h): world up in the sensor frame is n = (-k_xz, -k_yz, 1) / norm, so the plane
  // n . p = -sensor_z reads z = k_xz x + k_yz y - sensor_z * norm = ... - sensor_height exactly.
  const double k_xz = std::tan(options.pitch_deg * (kPi / 180.0));
  const double k_yz = std::tan(options.roll_deg * (kPi / 180.0));
  const double norm = std::sqrt(1.0 + k_xz * k_xz + k_yz * k_yz);
  const double n[3] = {-k_xz / norm, -k_yz / norm, 1.0 / norm};
  // World x: the sensor's x axis made horizontal (no yaw); world y = z cross x.
  double u[3] = {1.0 - n[0] * n[0], -n[0] * n[1], -n[0] * n[2]};
  const double un = std::sqrt(Dot(u, u));
  for (double& c : u) c /= un;
  const double v[3] = {n[1] * u[2] - n[2] * u[1], n[2] * u[0] - n[0] * u[2],
                       n[0] * u[1] - n[1] * u[0]};
  for (int i = 0; i < 3; ++i) s.world_x[i] = u[i], s.world_y[i] = v[i], s.world_z[i] = n[i];
  s.sensor_z = sensor_height / norm;

  // The scene stream depends on the seed only (not on the sensor), so every sensor sees the same
  // street for a given seed.
  SimRandom rng(options.seed ^ 0x5CE4E5EEu);
  if (options.kind == kUrban) {
    BuildUrban(rng, &s);
  } else {
    BuildFlat(rng, options.kind == kFlatWithObjects, &s);
  }
  return s;
}

}  // namespace lpir
