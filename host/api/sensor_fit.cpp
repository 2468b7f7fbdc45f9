// Whether a cloud fits its sensor profile (see sensor_fit.h). Outside the bit-exact contract: host
// statistics in double, for messages only.
#include "host/api/sensor_fit.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace lpir {
namespace {

// "35,012": thousands separated, as the messages count points.
std::string Count(size_t n) {
  std::string digits = std::to_string(n), out;
  for (size_t i = 0; i < digits.size(); ++i) {
    if (i > 0 && (digits.size() - i) % 3 == 0) out += ',';
    out += digits[i];
  }
  return out;
}

std::string Percent(size_t part, size_t whole) {
  char text[16];
  std::snprintf(text, sizeof text, "%.0f %%", whole ? 100.0 * double(part) / double(whole) : 0.0);
  return text;
}

std::string Degrees(double d) {
  char text[16];
  std::snprintf(text, sizeof text, "%+.1f deg", d);
  return text;
}

// A rosette's circle about its x axis, degrees: the table's top bin centre plus half a bin (its
// bins are even), as `simulate` casts it.
double CircleDeg(const SensorProfile& sensor) {
  const std::vector<float>& e = sensor.elevation_deg;
  return e.empty() ? 0.0 : e.front() + (e.size() > 1 ? 0.5 * (e[0] - e[1]) : 0.0);
}

}  // namespace

SensorFit MeasureRings(const Cloud& cloud, const SensorProfile& sensor) {
  SensorFit fit;
  fit.points = cloud.size();
  if (cloud.ring.empty() || sensor.pattern != ScanPattern::kSpinning) return fit;  // not read
  fit.ring_min = fit.ring_max = cloud.ring[0];
  const int32_t beams = int32_t(sensor.beams);
  for (int32_t r : cloud.ring) {
    fit.ring_min = std::min(fit.ring_min, r);
    fit.ring_max = std::max(fit.ring_max, r);
    fit.rings_outside += r < 0 || r >= beams;
  }
  return fit;
}

SensorFit MeasureSensorFit(const Cloud& cloud, const SensorProfile& sensor) {
  SensorFit fit = MeasureRings(cloud, sensor);
  if (sensor.elevation_deg.empty() || cloud.size() == 0) return fit;
  double origin = 0;
  for (float z : sensor.beam_origin_z) origin += z;
  if (!sensor.beam_origin_z.empty()) origin /= double(sensor.beam_origin_z.size());
  const double top = sensor.elevation_deg.front() + kElevationMarginDeg;
  const double bottom = sensor.elevation_deg.back() - kElevationMarginDeg;
  const size_t stride = std::max<size_t>(1, cloud.size() / kElevationSamples);
  const double kDeg = 180.0 / 3.14159265358979323846;
  const double circle = CircleDeg(sensor) + kElevationMarginDeg;
  const bool rosette = sensor.pattern == ScanPattern::kRosette;
  for (size_t i = 0; i < cloud.size(); i += stride) {
    const double x = cloud.x(i), y = cloud.y(i);
    const double z = cloud.z(i) - sensor.k_xz * x - sensor.k_yz * y - origin;
    const double r = std::hypot(x, y);
    if (!std::isfinite(r) || !std::isfinite(z)) continue;
    if (r < sensor.min_range || r > sensor.max_range) continue;  // invalid points, the origin's
    // no-returns and the vehicle's own among them
    const double elevation = std::atan2(z, r) * kDeg;
    ++fit.sampled;
    fit.above += elevation > top;
    fit.below += elevation < bottom;
    if (rosette) {  // the angle off the sensor's x axis, in its own frame
      const double off = std::atan2(std::hypot(double(cloud.y(i)), double(cloud.z(i))), x) * kDeg;
      fit.outside_circle += off > circle;
    }
  }
  return fit;
}

std::string SensorFitError(const SensorFit& fit, const SensorProfile& sensor) {
  if (fit.rings_outside == 0 || double(fit.rings_outside) <= kRingErrorShare * double(fit.points))
    return "";
  const int32_t last = int32_t(sensor.beams) - 1;
  std::string seen = fit.ring_max > last ? "ring values up to " + std::to_string(fit.ring_max)
                                         : "ring values down to " + std::to_string(fit.ring_min);
  return seen + " (" + Count(fit.rings_outside) + " of " + Count(fit.points) +
         " points outside 0.." + std::to_string(last) + "); profile '" + sensor.name + "' has " +
         std::to_string(sensor.beams) + " beams: wrong --sensor?";
}

std::vector<std::string> SensorFitWarnings(const SensorFit& fit, const SensorProfile& sensor) {
  std::vector<std::string> warnings;
  if (fit.rings_outside > 0 && SensorFitError(fit, sensor).empty())
    warnings.push_back(Count(fit.rings_outside) + " of " + Count(fit.points) +
                       " points have a ring outside 0.." + std::to_string(sensor.beams - 1) +
                       " (seen " + std::to_string(fit.ring_min) + ".." +
                       std::to_string(fit.ring_max) + "): they are invalid (non-ground)");
  const size_t outside = fit.above + fit.below;
  if (fit.sampled > 0 && double(outside) > kElevationWarnShare * double(fit.sampled)) {
    std::string where;
    if (fit.above)
      where = Percent(fit.above, fit.sampled) + " of the points lie more than " +
              Degrees(kElevationMarginDeg).substr(1) + " above the top beam (" +
              Degrees(sensor.elevation_deg.front()) + ")";
    if (fit.below)
      where += (where.empty() ? Percent(fit.below, fit.sampled) + " of the points lie more than " +
                                    Degrees(kElevationMarginDeg).substr(1) + " below"
                              : " and " + Percent(fit.below, fit.sampled) + " below") +
               " the bottom beam (" + Degrees(sensor.elevation_deg.back()) + ")";
    warnings.push_back(where + " of profile '" + sensor.name +
                       "': wrong --sensor, or a mount tilt the profile does not hold "
                       "(lpir-gseg calibrate)?");
  }
  if (fit.sampled > 0 && double(fit.outside_circle) > kElevationWarnShare * double(fit.sampled)) {
    warnings.push_back(Percent(fit.outside_circle, fit.sampled) + " of the points lie more than " +
                       Degrees(kElevationMarginDeg).substr(1) + " outside the " +
                       Degrees(CircleDeg(sensor)).substr(1) +
                       " circle about the x axis that profile '" + sensor.name +
                       "' sees (a rosette looks ahead only; a full turn is a spinning "
                       "sensor's): wrong --sensor?");
  }
  return warnings;
}

}  // namespace lpir
