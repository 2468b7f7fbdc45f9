// Where in range the errors lie: per band of horizontal range sqrt(x^2 + y^2) (metres, sensor
// frame), summed over any number of frames, the points and their outcomes under each protocol.
// Summed over the bands, a protocol's counts are its CountFrame counts summed over the frames.
#pragma once
#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "host/eval/metrics.h"

namespace lpir {

// Band b holds ranges in [edge[b-1], edge[b]): 0-5, 5-10, 10-20, 20-30, 30-40, 40-60, 60+ m.
constexpr std::array<float, 6> kRangeBandEdges = {5, 10, 20, 30, 40, 60};
constexpr size_t kRangeBands = kRangeBandEdges.size() + 1;

// The band of horizontal range `r` in metres; r >= 60, +Inf and NaN fall in the last band.
size_t RangeBand(float r);
// "0-5", "5-10", ..., "60+".
std::string RangeBandName(size_t band);

struct RangeTally {
  uint64_t points = 0;
  std::vector<Counts> counts;  // one per protocol, in RangeBreakdown::protocols() order
};

class RangeBreakdown {
 public:
  explicit RangeBreakdown(std::vector<Protocol> protocols);
  // Adds one frame: `cloud` gives each point's x, y (its band) and z (for kPW). Other inputs as
  // CountFrame; std::invalid_argument when the cloud's size differs from the labels'.
  void Add(const Cloud& cloud, const Labels& pred, const std::vector<uint32_t>& gt);
  const std::array<RangeTally, kRangeBands>& bands() const { return bands_; }
  const std::vector<Protocol>& protocols() const { return protocols_; }

 private:
  std::vector<Protocol> protocols_;
  std::array<RangeTally, kRangeBands> bands_;
};

}  // namespace lpir
