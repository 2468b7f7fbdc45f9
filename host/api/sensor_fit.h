// Whether a cloud fits the sensor profile it is segmented with, measured on the host: ring values
// past the profile's beams and elevations outside its beam table, the two signs of a wrong
// --sensor (or a mount tilted beyond what the profile says). The one source of the messages the
// library (an error), the CLI and Python (warnings) give; docs/usage.md, Misfit input.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "reference_cpu/cloud.h"
#include "reference_cpu/sensor.h"

namespace lpir {

struct SensorFit {
  size_t points = 0;
  // Rings (when the cloud has them): points with a ring outside [0, beams), and the range seen.
  size_t rings_outside = 0;
  int32_t ring_min = 0, ring_max = 0;
  // Elevations: points whose planar range lies within the profile's range limits, sampled (every
  // k-th point, k = max(1, points / kElevationSamples)), and those more than kElevationMarginDeg
  // above the top beam or below the bottom one (the angle of z - k_xz x - k_yz y - the mean beam
  // origin over the planar range).
  size_t sampled = 0, above = 0, below = 0;
  // A rosette pattern (Mid-70) sees a circle about its x axis: of the sampled points, those more
  // than kElevationMarginDeg outside it (its radius the table's top bin edge).
  size_t outside_circle = 0;
};

constexpr size_t kElevationSamples = 4096;
constexpr double kElevationMarginDeg = 2.0;
// Rings outside the beams on more than this share of the points make the cloud unusable with the
// profile (a wrong profile puts a third to a half of them there); fewer are invalid points.
constexpr double kRingErrorShare = 0.01;
// Elevations outside the table, or points outside a rosette's circle, on more than this share of
// the sampled points are warned about.
constexpr double kElevationWarnShare = 0.05;

// The rings only (cheap: one pass over the ring field; nothing when the cloud has none or the
// profile's pattern is not spinning, which ignores them).
SensorFit MeasureRings(const Cloud& cloud, const SensorProfile& sensor);
// Rings, elevations and a rosette's circle.
SensorFit MeasureSensorFit(const Cloud& cloud, const SensorProfile& sensor);

// The message of a cloud that cannot be segmented with the profile ("" when it can): rings past
// the beams on more than kRingErrorShare of its points, e.g. "ring values up to 63 (35,012 of
// 70,000 points at 32 or above); profile 'vlp32c' has 32 beams, rings 0..31: wrong --sensor?".
std::string SensorFitError(const SensorFit& fit, const SensorProfile& sensor);
// Warnings for a cloud that can be segmented but does not look like the profile's sensor: a few
// rings past the beams (those points are invalid), elevations outside the table, points outside a
// rosette's circle (a spinning sensor's full turn read as a Mid-70's).
std::vector<std::string> SensorFitWarnings(const SensorFit& fit, const SensorProfile& sensor);

}  // namespace lpir
