// The firing pattern of a non-repetitive (Livox) sensor: the ray directions of one 100 ms frame,
// in firing order, for the simulator to cast (apps/sim/raycast.cpp). The rates and how they
// approximate the real sensors: docs/decisions/livox.md, "Simulation".
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include "reference_cpu/sensor.h"

namespace lpir {

// Frame period of the non-repetitive patterns, s (both datasheets: 10 Hz).
constexpr double kPatternFramePeriod = 0.1;

// Unit ray directions in the sensor frame (x ahead, y left, z up) of frame `seed` of `sensor`:
// sensor.frame_points rays at equal time steps from t0 = seed x kPatternFramePeriod, so seeds
// are consecutive frames of one recording and no two frames fire the same rays.
//   kRosette: two Risley prisms. The deflection from +x, as a 2-vector (y, z) in radians, is
//     (R/2) (cos w1 t, sin w1 t) + (R/2) (cos w2 t, -sin w2 t): the prisms turn in opposite
//     directions at w2 = w1 / golden ratio; R = the elevation table's top bin centre plus half
//     a bin, so every ray lies within R of +x.
//   kBand: the azimuth turns at kBandTurnsPerFrame turns a frame (counter-clockwise seen from
//     above) while the elevation runs a triangle wave over the table's extent (top bin centre
//     plus half a bin down to the bottom one minus half a bin), 36 + 1 / golden ratio periods a
//     turn, so its phase drifts by 0.618 of a period each turn.
// std::invalid_argument for a spinning profile, frame_points 0 or an elevation table of fewer
// than two bins.
std::vector<std::array<double, 3>> PatternRays(const SensorProfile& sensor, uint32_t seed);

}  // namespace lpir
