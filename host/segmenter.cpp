#include "host/segmenter.h"

#include <stdexcept>

namespace lpir {

Segmenter::Segmenter(const SensorProfile& sensor, size_t max_points)
    : sensor_(sensor),
      params_(ParamsForSensor(sensor)),
      tables_(MakeTables(sensor, params_)),
      max_points_(max_points) {}

const Frame& Segmenter::Segment(const Cloud& cloud, StageTimes* times) {
  if (cloud.size() > max_points_)
    throw std::length_error("cloud has " + std::to_string(cloud.size()) +
                            " points, more than the configured maximum of " +
                            std::to_string(max_points_) + " (raise it with --max-points)");
  if (!cloud.ring.empty() && cloud.ring.size() != cloud.size())
    throw std::invalid_argument("cloud has " + std::to_string(cloud.ring.size()) +
                                " ring entries for " + std::to_string(cloud.size()) + " points");
  RunReference(cloud, params_, tables_, frame_, times);
  return frame_;
}

}  // namespace lpir
