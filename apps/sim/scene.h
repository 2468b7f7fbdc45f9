// A deterministic synthetic street seen by a virtual LiDAR: the scene (road with a ramp, curbs,
// sidewalks, terrain, buildings, parked cars, poles, vegetation, reflection noise) is drawn from a
// seed, then every ray of a SensorProfile (a spinning sensor's beam x azimuth rays, a
// non-repetitive sensor's firing pattern) is cast into it and the nearest hit becomes a point
// with its SemanticKITTI class. Used by `lpir-gseg simulate`, the demo and
// the tests (ground truth with known geometry, tilt read-back for calibration).
#pragma once
#include <cstdint>
#include <vector>

#include "reference_cpu/cloud.h"
#include "reference_cpu/sensor.h"

namespace lpir {

enum SceneKind {
  kUrban,            // the street described above, dimensions drawn from the seed
  kFlat,             // one horizontal plane (class 40 road) and nothing else
  kFlatWithObjects,  // the plane, a car ahead on +x and a 2.5 m wall to the left (+y) along x
};

// The SemanticKITTI classes the simulator writes.
struct SkClass {
  static constexpr uint32_t kOutlier = 1;  // reflection noise under the road
  static constexpr uint32_t kCar = 10;
  static constexpr uint32_t kRoad = 40;
  static constexpr uint32_t kSidewalk = 48;  // sidewalk tops and curb faces
  static constexpr uint32_t kBuilding = 50;
  static constexpr uint32_t kFence = 51;  // low walls
  static constexpr uint32_t kLaneMarking = 60;
  static constexpr uint32_t kVegetation = 70;  // bushes, tree crowns
  static constexpr uint32_t kTrunk = 71;
  static constexpr uint32_t kTerrain = 72;
  static constexpr uint32_t kPole = 80;
  static constexpr uint32_t kTrafficSign = 81;
};

// Ground as every SemanticKITTI protocol counts it: 40 road, 44 parking, 48 sidewalk,
// 49 other-ground, 60 lane marking, 72 terrain (vegetation 70 is not ground).
bool IsSimGroundClass(uint32_t label);

// TILT SIGN CONVENTION (the one `calibrate` reads back as itself, paper eq. 2-3).
// The world frame is level: x along the road (ahead), y to the left, z up, the road surface at
// z = 0 under the sensor. The sensor frame is rotated so that a flat ground plane, expressed in
// the sensor frame, is exactly
//     z = k_xz * x + k_yz * y - sensor_height,  k_xz = tan(pitch_deg), k_yz = tan(roll_deg).
// So positive pitch makes the ground appear to rise ahead (+x: the sensor is tipped nose-down),
// positive roll makes it rise to the left (+y: tipped down to the left). The sensor's x axis stays
// in the world's vertical x-z plane (no yaw), and `sensor_height` is the paper's b_x = b_y: where
// the ground crosses the sensor's own z axis. The sensor origin therefore sits
// sensor_height / sqrt(1 + k_xz^2 + k_yz^2) above the road (the perpendicular distance).
struct SimOptions {
  uint32_t seed = 0;
  float pitch_deg = 0.0f;       // atan(k_xz), see above; |value| <= 30
  float roll_deg = 0.0f;        // atan(k_yz), see above; |value| <= 30
  float range_noise_m = 0.02f;  // sigma of the Gaussian range noise along each ray
  SceneKind kind = kUrban;
  bool emit_rings = false;       // fill cloud.ring (laser index as the profile numbers rings;
                                 // spinning profiles only)
  bool reflection_noise = true;  // a few class-1 points 0.5-2 m under the road (multipath)
};

// One piece of scene geometry in the world frame. Plain data so tests and pictures can read it.
enum class SimShape : uint8_t {
  kHeightPatch,  // surface z = z0 + slope * (x - lo[0]) over the rectangle lo..hi in x and y
  kCurbFace,     // vertical face y = lo[1], x in lo[0]..hi[0], z from z0 + slope * (x - lo[0])
                 // up by `height`
  kBox,          // axis-aligned box lo..hi
  kCylinderY,    // cylinder with its axis along y, inscribed in the box lo..hi (wheels)
  kCylinderZ,    // cylinder with its axis along z, inscribed in the box lo..hi (poles, trunks)
  kEllipsoid,    // axis-aligned ellipsoid inscribed in the box lo..hi, with a bumpy surface
};

struct SimPrimitive {
  SimShape shape = SimShape::kBox;
  uint32_t label = 0;             // SemanticKITTI class of its surface
  float reflectivity = 0.0f;      // intensity in [0, 1] before per-point jitter
  float reflectivity_jitter = 0;  // +- uniform per point
  double lo[3] = {0, 0, 0};       // bounds, metres, world frame
  double hi[3] = {0, 0, 0};
  double z0 = 0, slope = 0;  // kHeightPatch, kCurbFace
  double height = 0;         // kCurbFace
  double roughness = 0;      // m: height patches, +- uniform jitter of the surface height
  double bump = 0;           // m: ellipsoids, amplitude of the deterministic surface bumps
  double bump_phase[3] = {0, 0, 0};
  bool lane_markings = false;  // kHeightPatch of the road: paint the markings (class 60)
};

// The street's layout (world frame, see the tilt convention) and the sensor's pose in it.
struct SimScene {
  SceneKind kind = kUrban;
  double road_center_y = 0;           // the road runs along x between center -+ half width
  double road_half_width = 0;         // m, half the road width (7-9 m wide)
  double curb_height[2] = {0, 0};     // m, right (-y) and left (+y) curbs, 0.10-0.15
  double sidewalk_width[2] = {0, 0};  // m, right and left
  double ramp_start_x = 0, ramp_length = 0, ramp_grade = 0;  // the road rises by grade * length
  double parking_line_offset = 0;  // m from the road centre: solid lines of the parking lanes
  std::vector<SimPrimitive> primitives;

  // Sensor pose: the world's unit axes expressed in the sensor frame, and the sensor origin's
  // height above the road at the world origin (x = y = 0).
  double world_x[3] = {1, 0, 0}, world_y[3] = {0, 1, 0}, world_z[3] = {0, 0, 1};
  double sensor_z = 0;

  // Height of the road surface (no curb) at x.
  double RoadHeight(double x) const;
  // Height of the walkable ground (road, sidewalk top, terrain) under (x, y).
  double GroundHeight(double x, double y) const;
  // Whether a road point at (x, y) is painted (dashed centre line, solid parking-lane lines).
  bool IsLaneMarking(double x, double y) const;
  // Sensor-frame point -> world frame, and world direction <- sensor direction.
  void SensorToWorld(const double p[3], double out[3]) const;
  void DirectionToWorld(const double d[3], double out[3]) const;
};

// The scene for `options` (seed, kind) with the sensor pose for `sensor_height` and the tilt.
SimScene BuildScene(const SimOptions& options, double sensor_height);

struct SimScan {
  Cloud cloud;                   // sensor frame, intensity the surface's reflectivity in [0, 1]
  std::vector<uint32_t> labels;  // SemanticKITTI class per point
  SimScene scene;                // what was scanned, for tests and pictures
};

// Casts the sensor's rays and keeps the nearest hit when its planar range lies in [min_range,
// max_range]; rays without a hit (sky) give no point.
//   spinning: beams x width rays (azimuth = pi - 2 pi (col + 0.5) / width: column 0 looks back
//     along -x and the sweep turns clockwise, paper eq. 1; elevations from the profile, row 0 =
//     top), beam by beam from the top beam, columns in order, like a KITTI scan.
//   rosette, band: the frame_points rays of frame `seed` of the pattern (scan_pattern.h), in
//     firing order, from the sensor frame's origin; no rings.
// std::invalid_argument for an inconsistent profile (a non-repetitive one without frame_points),
// options out of range, or rings asked of a non-repetitive profile.
// Deterministic: the same profile and options give byte-identical output.
SimScan Simulate(const SensorProfile& sensor, const SimOptions& options);

}  // namespace lpir
