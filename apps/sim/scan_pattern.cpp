// The firing patterns of the non-repetitive sensors (scan_pattern.h). Rates and their sources:
// docs/decisions/livox.md, "Simulation".
#include "apps/sim/scan_pattern.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace lpir {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kGolden = 1.6180339887498949;  // (1 + sqrt 5) / 2

// Rosette: passes through the centre a second, w1 + w2 over 2 pi. The labelled Livox recordings
// pass through it every ~487 points (4.9 ms at 100,000 points/s).
constexpr double kRosettePetalRate = 205.0;  // Hz
// The two prisms' turns a second: f1 + f2 = kRosettePetalRate and f1 / f2 = golden ratio, so
// each petal is (f1 - f2) / (f1 + f2) x 180 = 42.5 degrees wide (40 measured) and the pattern
// never closes.
constexpr double kPrismRate1 = kRosettePetalRate / kGolden;              // 126.7 Hz
constexpr double kPrismRate2 = kRosettePetalRate / (kGolden * kGolden);  // 78.3 Hz

// Band: turns of azimuth a frame, and triangle periods of the elevation a turn (a whole number
// plus 1 / golden ratio: each turn's wave falls between the earlier turns' waves).
constexpr double kBandTurnsPerFrame = 5.0;
constexpr double kBandPeriodsPerTurn = 36.0 + 1.0 / kGolden;

// The fraction of `cycles` (cycles at time 0 of frame `seed` plus `per_ray` for each of `ray`
// rays), in [0, 1): the seed's whole part is taken away first so that late frames keep their
// precision.
double CyclePhase(double per_frame, uint32_t seed, double per_ray, size_t ray) {
  const double start = std::fmod(per_frame * static_cast<double>(seed), 1.0);
  const double phase = std::fmod(start + per_ray * static_cast<double>(ray), 1.0);
  return phase < 0 ? phase + 1.0 : phase;
}

}  // namespace

std::vector<std::array<double, 3>> PatternRays(const SensorProfile& sensor, uint32_t seed) {
  auto fail = [&](const std::string& what) {
    throw std::invalid_argument("simulate: the " + std::string(sensor.name) + " profile " + what);
  };
  if (sensor.pattern == ScanPattern::kSpinning) fail("is spinning: it has no firing pattern");
  if (sensor.frame_points == 0) fail("needs frame_points (the returns of a 100 ms frame)");
  if (sensor.elevation_deg.size() < 2) fail("needs at least two elevation bins");
  const size_t n = sensor.frame_points;
  const double half_bin = 0.5 * (sensor.elevation_deg[0] - sensor.elevation_deg[1]);
  const double top = (sensor.elevation_deg.front() + half_bin) * (kPi / 180.0);
  const double bottom = (sensor.elevation_deg.back() - half_bin) * (kPi / 180.0);
  std::vector<std::array<double, 3>> rays(n);

  if (sensor.pattern == ScanPattern::kRosette) {
    const double half_radius = 0.5 * top;
    const double c1 = kPrismRate1 * kPatternFramePeriod, c2 = kPrismRate2 * kPatternFramePeriod;
    for (size_t k = 0; k < n; ++k) {
      const double a1 = 2.0 * kPi * CyclePhase(c1, seed, c1 / n, k);
      const double a2 = -2.0 * kPi * CyclePhase(c2, seed, c2 / n, k);
      const double dy = half_radius * (std::cos(a1) + std::cos(a2));
      const double dz = half_radius * (std::sin(a1) + std::sin(a2));
      const double rho = std::hypot(dy, dz);  // angle from +x, radians
      const double s = rho > 0 ? std::sin(rho) / rho : 1.0;
      rays[k] = {std::cos(rho), s * dy, s * dz};
    }
    return rays;
  }

  const double turns = kBandTurnsPerFrame, waves = kBandTurnsPerFrame * kBandPeriodsPerTurn;
  for (size_t k = 0; k < n; ++k) {
    const double az = 2.0 * kPi * CyclePhase(turns, seed, turns / n, k);
    const double w = CyclePhase(waves, seed, waves / n, k);
    const double el = top - (top - bottom) * (w < 0.5 ? 2.0 * w : 2.0 - 2.0 * w);
    rays[k] = {std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el)};
  }
  return rays;
}

}  // namespace lpir
