// Per-class tallies (see by_class.h).
#include "host/eval/by_class.h"

namespace lpir {

void ClassBreakdown::Add(const Labels& pred, const std::vector<uint32_t>& gt,
                         const std::vector<float>* z) {
  for (Protocol p : protocols_) CheckFrame(p, pred, gt, z);
  for (size_t i = 0; i < gt.size(); ++i) {
    ClassTally& t = classes_[ClassOf(gt[i])];
    if (t.counts.empty()) t.counts.resize(protocols_.size());
    const bool predicted = pred[i] != 0;
    ++t.points;
    t.predicted_ground += predicted;
    const float zi = z ? (*z)[i] : 0.0f;
    for (size_t k = 0; k < protocols_.size(); ++k)
      t.counts[k].Add(ScorePoint(protocols_[k], gt[i], predicted, zi));
  }
}

}  // namespace lpir
