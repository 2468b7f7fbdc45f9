// Per-range-band tallies (see by_range.h).
#include "host/eval/by_range.h"

#include <cmath>
#include <stdexcept>

namespace lpir {

size_t RangeBand(float r) {
  size_t b = 0;
  while (b < kRangeBandEdges.size() && r >= kRangeBandEdges[b]) ++b;
  return std::isnan(r) ? kRangeBands - 1 : b;
}

std::string RangeBandName(size_t band) {
  auto edge = [](size_t i) { return std::to_string(int(kRangeBandEdges[i])); };
  if (band == 0) return "0-" + edge(0);
  if (band + 1 >= kRangeBands) return edge(kRangeBandEdges.size() - 1) + "+";
  return edge(band - 1) + "-" + edge(band);
}

RangeBreakdown::RangeBreakdown(std::vector<Protocol> protocols) : protocols_(std::move(protocols)) {
  for (RangeTally& t : bands_) t.counts.resize(protocols_.size());
}

void RangeBreakdown::Add(const Cloud& cloud, const Labels& pred, const std::vector<uint32_t>& gt) {
  if (cloud.size() != gt.size())
    throw std::invalid_argument("scan has " + std::to_string(cloud.size()) +
                                " points but the ground truth " + std::to_string(gt.size()));
  std::vector<float> z(cloud.size());
  for (size_t i = 0; i < z.size(); ++i) z[i] = cloud.z(i);
  for (Protocol p : protocols_) CheckFrame(p, pred, gt, &z);
  for (size_t i = 0; i < gt.size(); ++i) {
    const float r = std::sqrt(cloud.x(i) * cloud.x(i) + cloud.y(i) * cloud.y(i));
    RangeTally& t = bands_[RangeBand(r)];
    ++t.points;
    for (size_t k = 0; k < protocols_.size(); ++k)
      t.counts[k].Add(ScorePoint(protocols_[k], gt[i], pred[i] != 0, z[i]));
  }
}

}  // namespace lpir
