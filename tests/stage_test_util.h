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

}  // namespace lpir::test
