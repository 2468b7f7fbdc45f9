#include "reference_cpu/params.h"

#include <cmath>
#include <cstddef>
#include <cstdio>
#include <limits>
#include <stdexcept>

namespace lpir {
namespace {

struct Field {
  const char* name;
  size_t offset;
  bool is_uint;
};

#define LPIR_F(name) \
  { #name, offsetof(Params, name), false }
#define LPIR_U(name) \
  { #name, offsetof(Params, name), true }
// Fields a profile may override (the image geometry comes from the profile itself).
const Field kFields[] = {
    LPIR_F(h_noise),          LPIR_U(rings_near),     LPIR_U(rings_far),
    LPIR_U(sectors_near),     LPIR_U(sectors_far),    LPIR_F(ring_res_near),
    LPIR_F(ring_res_far),     LPIR_F(slope_max),      LPIR_F(seed_margin),
    LPIR_F(h_athr),           LPIR_F(rise_margin),    LPIR_F(plane_dist_floor),
    LPIR_F(plane_dist_scale), LPIR_F(normal_min_z2),  LPIR_F(ground_max_above),
    LPIR_F(hole_gap),         LPIR_F(t_edge),         LPIR_F(t_slope_low),
    LPIR_F(t_slope_high),     LPIR_F(t_stdz_low),     LPIR_F(t_stdz_high),
    LPIR_F(bank_slope),       LPIR_F(bank_rough),     LPIR_F(grow_dz),
    LPIR_F(grow_grade),       LPIR_U(min_component),  LPIR_F(bp_range_gate),
    LPIR_F(bp_height_gate),   LPIR_U(occ_rows),       LPIR_F(occ_margin),
    LPIR_F(occ_rise),         LPIR_F(occ_grade),      LPIR_F(occ_front),
    LPIR_F(occ_pass),         LPIR_U(occ_step_rows),  LPIR_F(occ_step),
    LPIR_F(occ_step_grade),   LPIR_F(occ_step_reach), LPIR_U(comp_seed_min),
    LPIR_F(comp_seed_share),
};
#undef LPIR_F
#undef LPIR_U

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
  Params p{};
  p.width = 2048;
  p.beams = 64;
  p.ring_zero_is_top = 0;
  p.has_ring = 0;
  p.min_range2 = 2.5f * 2.5f;
  p.max_range2 = 120.0f * 120.0f;
  p.k_xz = 0.0f;
  p.k_yz = 0.0f;
  p.h_noise = -3.73f;  // 2 m under the road for a 1.73 m mount (see ParamsForSensor)
  p.sensor_height = 1.73f;
  p.rings_near = 10;     // 10 x 2 m = 20 m near zone
  p.rings_far = 25;      // 25 x 4 m beyond: to 120 m
  p.sectors_near = 128;  // 2.8 degrees
  p.sectors_far = 64;
  p.ring_res_near = 2.0f;
  p.ring_res_far = 4.0f;
  // Stages 4-9: the measurements behind each default are in docs/decisions/params.md and the
  // stages' pages beside it.
  p.slope_max = 0.10f;
  p.seed_margin = 0.06f;
  p.h_athr = 0.12f;
  p.rise_margin = 0.3f;
  p.plane_dist_floor = 0.1f;  // docs/decisions/coarse_segment.md, The plane band (issue 28)
  p.plane_dist_scale = 2.5f;
  p.normal_min_z2 = 0.7f;  // normal within ~33 degrees of vertical
  // 0.3 keeps the roof of a car parked beside the sensor out of the seeds
  // (docs/decisions/coarse_segment.md).
  p.ground_max_above = 0.3f;
  p.hole_gap = 0.25f;
  p.t_edge = 0.12f;
  p.t_slope_low = 0.09f;
  p.t_slope_high = 0.25f;
  p.t_stdz_low = 0.000025f;   // (5 mm)^2
  p.t_stdz_high = 0.000144f;  // (12 mm)^2
  p.bank_slope = 0.8f;        // 39 degrees
  p.bank_rough = 0.01f;       // (10 cm)^2: grass on a bank
  p.grow_dz = 0.03f;
  p.grow_grade = 0.0f;
  p.column_arc = float(2.0 * 3.14159265358979323846 / 2048.0);
  p.min_component = 300;
  p.bp_range_gate = 0.15f;
  p.bp_height_gate = 0.2f;
  p.occ_rows = 2;
  p.occ_margin = 0.3f;
  p.occ_rise = 0.045f;
  p.occ_grade = 0.0002f;
  p.occ_front = 0.1f;
  p.occ_pass = 0.15f;
  p.occ_step_rows = 10;
  p.occ_step = 0.15f;
  p.occ_step_grade = 0.1f;
  p.occ_step_reach = 3.0f;
  p.comp_seed_min = 10;
  p.comp_seed_share = 0.8f;
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
  // Bounds that keep every index and fixed-point value of stages 3-5 inside its integer type (the
  // profile reader enforces the same for k and max_range; these hold for profiles built in code).
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
