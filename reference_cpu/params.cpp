#include "reference_cpu/params.h"

#include <cmath>
#include <cstddef>
#include <cstdio>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <type_traits>

namespace lpir {
namespace {

struct Field {
  const char* name;
  size_t offset;
  bool is_uint;
};

// The parameters (shaders/common/params.def's LPIR_PARAM rows): what a profile may override (the
// image geometry and the mount come from the profile itself).
const Field kFields[] = {
#define LPIR_PARAM(stage, type, name, default_value, unit, swept, meaning) \
  {#name, offsetof(Params, name), std::is_same_v<type, uint>},
#define LPIR_DERIVED(stage, type, name, default_value, unit, meaning)
#include "shaders/common/params.def"
};

// A subnormal parameter is an operand a device may flush (Vulkan allows it), so the stages' bytes
// would depend on the device (docs/decisions/denormals.md): rejected, naming the parameter.
void RejectSubnormal(const std::string& profile, const std::string& name, float value) {
  if (value == 0.0f || !(std::fabs(value) < std::numeric_limits<float>::min())) return;
  char text[32];
  std::snprintf(text, sizeof text, "%g", double(value));
  throw std::invalid_argument("sensor profile '" + profile + "': parameter " + name + " is " +
                              text + ", a subnormal float (a device may flush it to 0): use 0 " +
                              "or a magnitude of at least 1.18e-38");
}

}  // namespace

Params DefaultParams() {
  Params p;
  std::memset(&p, 0, sizeof p);  // the tail that rounds the block to vec4s is zero, not garbage
#define LPIR_PARAM(stage, type, name, default_value, unit, swept, meaning) p.name = default_value;
#define LPIR_DERIVED(stage, type, name, default_value, unit, meaning) p.name = default_value;
#include "shaders/common/params.def"
  return p;
}

bool ApplyOverride(Params& params, const std::string& name, float value) {
  for (const Field& f : kFields) {
    if (name != f.name) continue;
    char* base = reinterpret_cast<char*>(&params) + f.offset;
    if (f.is_uint) {
      if (!(value >= 0.0f) || value != std::floor(value) || value > 4.0e9f)
        throw std::invalid_argument("parameter " + name + " expects a whole number >= 0");
      *reinterpret_cast<uint32_t*>(base) = static_cast<uint32_t>(value);
    } else {
      if (!std::isfinite(value))
        throw std::invalid_argument("parameter " + name + " expects a finite number");
      *reinterpret_cast<float*>(base) = value;
    }
    return true;
  }
  return false;
}

std::vector<std::string> ParamNames() {
  std::vector<std::string> names;
  for (const Field& f : kFields) names.push_back(f.name);
  return names;
}

Params ParamsForSensor(const SensorProfile& s) {
  Params p = DefaultParams();
  p.width = s.width;
  p.column_arc = float(2.0 * 3.14159265358979323846 / double(s.width));
  p.beams = s.beams;
  p.ring_zero_is_top = s.ring_zero_is_top ? 1u : 0u;
  p.min_range2 = s.min_range * s.min_range;
  p.max_range2 = s.max_range * s.max_range;
  p.k_xz = s.k_xz;
  p.k_yz = s.k_yz;
  p.sensor_height = s.sensor_height;
  // Reflection noise lies under the road: 2 m under the sensor's own ground plane, so that a road
  // falling away is not flagged (docs/decisions/intensity.md).
  p.h_noise = -s.sensor_height - 2.0f;
  for (const auto& [name, value] : s.overrides) {
    if (!ApplyOverride(p, name, value))
      throw std::invalid_argument("sensor profile '" + s.name + "': unknown parameter '" + name +
                                  "'");
  }
  if (p.sectors_near == 0 || p.width % p.sectors_near || p.sectors_far == 0 ||
      p.width % p.sectors_far)
    throw std::invalid_argument("sensor profile '" + s.name +
                                "': sectors_near and sectors_far must divide the image width");
  const uint64_t rings = uint64_t(p.rings_near) + p.rings_far;
  if (rings == 0 || !(p.ring_res_near > 0) || !(p.ring_res_far > 0))
    throw std::invalid_argument("sensor profile '" + s.name + "': the grid needs rings");
  // Bounds that keep every index and fixed-point value of grid_reduce, coarse_segment and
  // feature_maps inside its integer type (the profile reader enforces the same for k and max_range;
  // these hold for profiles built in code).
  const uint64_t cells =
      uint64_t(p.rings_near) * p.sectors_near + uint64_t(p.rings_far) * p.sectors_far;
  if (rings > 4096 || cells > (uint64_t(1) << 22))
    throw std::invalid_argument("sensor profile '" + s.name + "': a grid of " +
                                std::to_string(rings) + " rings and " + std::to_string(cells) +
                                " cells (at most 4096 rings and 4194304 cells)");
  if (!(std::fabs(s.k_xz) <= kMaxProfileTiltSlope) ||
      !(std::fabs(s.k_yz) <= kMaxProfileTiltSlope) || !(s.max_range <= kMaxProfileRange))
    throw std::invalid_argument("sensor profile '" + s.name +
                                "': k_xz and k_yz must lie in -1..1 and max_range be at most "
                                "1000 m");
  for (const Field& f : kFields)
    if (!f.is_uint)
      RejectSubnormal(
          s.name, f.name,
          *reinterpret_cast<const float*>(reinterpret_cast<const char*>(&p) + f.offset));
  RejectSubnormal(s.name, "min_range2 (min_range squared)", p.min_range2);
  RejectSubnormal(s.name, "max_range2 (max_range squared)", p.max_range2);
  RejectSubnormal(s.name, "k_xz", p.k_xz);
  RejectSubnormal(s.name, "k_yz", p.k_yz);
  RejectSubnormal(s.name, "sensor_height", p.sensor_height);
  RejectSubnormal(s.name, "column_arc", p.column_arc);
  return p;
}

Tables MakeTables(const SensorProfile& s, const Params& p) {
  if (s.elevation_deg.size() != s.beams)
    throw std::invalid_argument("sensor profile '" + s.name + "': elevation table has " +
                                std::to_string(s.elevation_deg.size()) + " entries for " +
                                std::to_string(s.beams) + " beams");
  if (!s.beam_origin_z.empty() && s.beam_origin_z.size() != s.beams)
    throw std::invalid_argument("sensor profile '" + s.name + "': beam_origin_z has " +
                                std::to_string(s.beam_origin_z.size()) + " entries for " +
                                std::to_string(s.beams) + " beams");
  Tables t;
  const double kPi = 3.14159265358979323846;
  for (unsigned b = 0; b + 1 < s.beams; ++b) {
    double mid = 0.5 * (double(s.elevation_deg[b]) + double(s.elevation_deg[b + 1])) * kPi / 180;
    double tn = std::tan(mid);
    t.beam_bound.push_back(float(tn * std::fabs(tn)));
    t.beam_origin.push_back(s.beam_origin_z.empty() ? 0.0f
                                                    : float(0.5 * (double(s.beam_origin_z[b]) +
                                                                   s.beam_origin_z[b + 1])));
  }
  t.column_dir.resize(2 * size_t(p.width));
  for (unsigned k = 0; k < p.width; ++k) {
    double phi = kPi - 2.0 * kPi * double(k) / double(p.width);
    t.column_dir[2 * k] = float(std::cos(phi));
    t.column_dir[2 * k + 1] = float(std::sin(phi));
  }
  for (unsigned i = 1; i <= p.rings_near; ++i) {
    double r = double(p.ring_res_near) * i;
    t.ring_inner.push_back(float(r - double(p.ring_res_near)));
    t.ring_bound2.push_back(float(r * r));
  }
  double near = double(p.ring_res_near) * p.rings_near;
  for (unsigned i = 1; i <= p.rings_far; ++i) {
    double r = near + double(p.ring_res_far) * i;
    t.ring_inner.push_back(float(r - double(p.ring_res_far)));
    t.ring_bound2.push_back(float(r * r));
  }
  return t;
}

}  // namespace lpir
