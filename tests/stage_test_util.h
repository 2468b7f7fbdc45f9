// Small profiles and clouds for the stage tests.
#pragma once
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

}  // namespace lpir::test
