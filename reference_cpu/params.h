// Parameters and the tables the host derives from them. Both are handed to every backend as the
// same bytes (docs/spec.md, The bit-exact contract): the reference and the shaders never compute a
// trigonometric value.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "reference_cpu/sensor.h"
#include "shaders/common/params.h"

namespace lpir {

// Defaults tuned for the HDL-64E in SemanticKITTI.
Params DefaultParams();

// Defaults, then the profile's geometry, then its overrides. Throws std::invalid_argument naming
// the profile and the key when an override names no parameter or a value is out of range.
Params ParamsForSensor(const SensorProfile& sensor);

// Sets one parameter by its field name; false when no field has that name.
bool ApplyOverride(Params& params, const std::string& name, float value);

// Names of every parameter (for help texts and profile checking).
std::vector<std::string> ParamNames();

// The sensor's mount (eq. 2-3): flat ground in the sensor frame is
// z = k_xz * x + k_yz * y - sensor_height.
struct Mount {
  float k_xz = 0.0f, k_yz = 0.0f;
  float sensor_height = 1.73f;  // m
};

inline Mount MountOf(const Params& p) { return Mount{p.k_xz, p.k_yz, p.sensor_height}; }

// Params for a frame seen from `mount`: k_xz, k_yz and sensor_height replaced, and the noise
// floor h_noise moved with the ground (by the change of height, so that it keeps its depth under
// the ground, a profile's override included). MountOf(p) leaves p's bytes as they are.
inline Params WithMount(Params p, const Mount& mount) {
  p.h_noise = p.h_noise - (mount.sensor_height - p.sensor_height);
  p.k_xz = mount.k_xz;
  p.k_yz = mount.k_yz;
  p.sensor_height = mount.sensor_height;
  return p;
}

struct Tables {
  // Row boundaries: beams - 1 entries, descending. Boundary b lies between row b and row b + 1 at
  // elevation e_b; stored as t*|t| with t = tan(e_b), compared with z*|z| / r^2 without dividing.
  std::vector<float> beam_bound;
  // Height of boundary b's laser origin (the mean of rows b and b + 1), m: the elevation compared
  // with beam_bound[b] is that of z - beam_origin[b].
  std::vector<float> beam_origin;
  // Column boundaries: width entries of (cos, sin) of phi_k = pi - 2*pi*k/width (entry 0 unused).
  std::vector<float> column_dir;
  // Ring boundaries: squared outer radius of every ring, ascending, rings_near + rings_far entries.
  std::vector<float> ring_bound2;
  // Inner radius of every ring, m (the slope prior of coarse_segment reads it).
  std::vector<float> ring_inner;
};

// Cells of the concentric grid: near rings x near sectors, then far rings x far sectors.
inline uint32_t CellCount(const Params& p) {
  return p.rings_near * p.sectors_near + p.rings_far * p.sectors_far;
}

Tables MakeTables(const SensorProfile& sensor, const Params& params);

}  // namespace lpir
