// What each ground-truth class contributes to the scores, summed over any number of frames: its
// points, how many were predicted ground, and its outcomes under each protocol. Summed over the
// classes, a protocol's counts are its CountFrame counts summed over the frames.
#pragma once
#include <cstdint>
#include <map>
#include <utility>
#include <vector>

#include "host/eval/metrics.h"

namespace lpir {

struct ClassTally {
  uint64_t points = 0;
  uint64_t predicted_ground = 0;
  std::vector<Counts> counts;  // one per protocol, in ClassBreakdown::protocols() order
};

class ClassBreakdown {
 public:
  explicit ClassBreakdown(std::vector<Protocol> protocols) : protocols_(std::move(protocols)) {}
  // Adds one frame; inputs and std::invalid_argument as CountFrame for each protocol.
  void Add(const Labels& pred, const std::vector<uint32_t>& gt, const std::vector<float>* z);
  // The classes seen (label & 0xFFFF), ascending.
  const std::map<uint32_t, ClassTally>& classes() const { return classes_; }
  const std::vector<Protocol>& protocols() const { return protocols_; }

 private:
  std::vector<Protocol> protocols_;
  std::map<uint32_t, ClassTally> classes_;
};

}  // namespace lpir
