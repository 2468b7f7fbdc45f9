// The library's entry point: a Segmenter is made once per sensor and labels clouds one by one.
// It owns the parameters, the host-derived tables and the frame buffers, allocated once and
// reused (a frame allocates nothing once the buffers have grown to the cloud size).
#pragma once
#include <cstddef>
#include <string>

#include "reference_cpu/cloud.h"
#include "reference_cpu/frame.h"
#include "reference_cpu/params.h"
#include "reference_cpu/pipeline.h"
#include "reference_cpu/sensor.h"

namespace lpir {

constexpr size_t kDefaultMaxPoints = size_t(1) << 20;

class Segmenter {
 public:
  // Throws std::invalid_argument for an inconsistent profile (see ParamsForSensor, MakeTables).
  explicit Segmenter(const SensorProfile& sensor, size_t max_points = kDefaultMaxPoints);

  // Runs stages 1-9. Throws std::length_error when the cloud holds more than max_points points,
  // and std::invalid_argument when its ring field does not match its size. The frame stays valid
  // until the next call.
  const Frame& Segment(const Cloud& cloud, StageTimes* times = nullptr);

  const Params& params() const { return params_; }
  const Tables& tables() const { return tables_; }
  const SensorProfile& sensor() const { return sensor_; }
  size_t max_points() const { return max_points_; }

 private:
  SensorProfile sensor_;
  Params params_;
  Tables tables_;
  size_t max_points_;
  Frame frame_;
};

}  // namespace lpir
