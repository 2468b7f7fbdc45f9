// Small profiles and clouds for the stage tests.
#pragma once
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <random>

#include "reference_cpu/cloud.h"
#include "reference_cpu/frame.h"
#include "reference_cpu/params.h"
#include "reference_cpu/sensor.h"

namespace lpir::test {

// A 16-beam sensor, 256 columns, beams 1 degree apart from +2 to -13 degrees, 1.7 m high.
inline SensorProfile SmallSensor() {
  SensorProfile s;
  s.name = "small";
  s.beams = 16;
  s.width = 256;
  for (unsigned b = 0; b < s.beams; ++b) s.elevation_deg.push_back(2.0f - float(b));
  s.sensor_height = 1.7f;
  s.min_range = 1.0f;
  s.max_range = 100.0f;
  s.overrides = {{"sectors_near", 64}, {"sectors_far", 32}};
  return s;
}

// A street-like random cloud: ground with bumps, boxes, poles, scattered clutter, and invalid and
// noise points.
inline Cloud StreetLikeCloud(size_t n, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f), angle(0.0f, 6.2831853f);
  Cloud cloud;
  cloud.xyzi.reserve(4 * n);
  for (size_t i = 0; i < n; ++i) {
    const float r = 2.0f + 60.0f * unit(rng) * unit(rng), a = angle(rng);
    float x = r * std::cos(a), y = r * std::sin(a), z = -1.73f + 0.02f * unit(rng);
    float in = 40.0f + 20.0f * unit(rng);
    switch (rng() % 12) {
      case 0:
        z += 2.0f * unit(rng);
        in = 255.0f * unit(rng);
        break;  // objects
      case 1:
        z = -1.73f + 0.3f * std::sin(x);
        break;  // a slope
      case 2:
        x = std::numeric_limits<float>::quiet_NaN();
        break;
      case 3:
        z = -3.0f, in = 0.0f;
        break;  // reflection noise
      case 4:
        z += 0.2f * unit(rng);
        break;  // rough ground
      default:
        break;
    }
    cloud.Push(x, y, z, in);
  }
  return cloud;
}

// A random street-like cloud around a sensor `sensor_height` above the ground: objects standing
// on it, slopes, invalid and noise points, and second returns beside the point before, so that
// many points share a pixel with a winner near them (fuse's occluders, back_project's lost points).
inline Cloud StreetWithSecondReturns(size_t n, float sensor_height, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  Cloud cloud;
  for (size_t i = 0; i < n; ++i) {
    const float az = unit(rng) * 6.2831853f, r = 3.0f + 50.0f * unit(rng) * unit(rng);
    float x = r * std::cos(az), y = r * std::sin(az), z = -sensor_height + 0.05f * unit(rng);
    float in = unit(rng) * 0.9f;
    switch (rng() % 12) {
      case 0:
      case 1:
      case 2:
        z = -sensor_height + 3.0f * unit(rng);
        break;
      case 3:
        z += 0.1f * r * unit(rng);
        break;
      case 4:
        if (rng() % 4 == 0) x = 0.0f, y = 0.0f, z = 0.0f;  // invalid
        break;
      case 5:
        if (rng() % 4 == 0) z = -sensor_height - 1.0f, in = 0.0f;  // reflection noise
        break;
      case 6:
        if (i > 0) {  // a second return next to the previous point: a lost point, near its winner
          x = cloud.x(i - 1) * (1.0f + 0.002f * unit(rng));
          y = cloud.y(i - 1) * (1.0f + 0.002f * unit(rng));
          z = cloud.z(i - 1) + 0.3f * (unit(rng) - 0.5f);
        }
        break;
      default:
        break;
    }
    cloud.Push(x, y, z, in);
  }
  return cloud;
}

}  // namespace lpir::test
