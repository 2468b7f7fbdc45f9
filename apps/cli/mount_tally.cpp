#include "apps/cli/mount_tally.h"

#include <algorithm>
#include <cstdio>

namespace lpir {

void MountTally::Add(const MountEstimate& mount) {
  if (mount.estimated)
    heights_.push_back(mount.mount.sensor_height);
  else
    ++fallbacks_;
}

std::string MountTally::Summary(float profile_height) const {
  const size_t frames = heights_.size() + fallbacks_;
  if (frames == 0) return "";
  char buf[200];
  std::string text;
  if (!heights_.empty()) {
    std::vector<float> sorted = heights_;
    std::sort(sorted.begin(), sorted.end());
    std::snprintf(buf, sizeof(buf),
                  "sensor height estimated on %zu of %zu frames: median %.2f m (%.2f to %.2f)",
                  sorted.size(), frames, double(sorted[(sorted.size() - 1) / 2]),
                  double(sorted.front()), double(sorted.back()));
    text = buf;
  }
  if (fallbacks_) {
    std::snprintf(buf, sizeof(buf), "%s%zu took the profile's %.2f m (too little ground)",
                  text.empty() ? "sensor height: " : "; ", fallbacks_, double(profile_height));
    text += buf;
  }
  return text;
}

std::string MountTally::FrameClause(const MountEstimate& mount) {
  char buf[128];
  if (mount.estimated)
    std::snprintf(buf, sizeof(buf), ", sensor height %.2f m, k_xz %.4f, k_yz %.4f (estimated)",
                  double(mount.mount.sensor_height), double(mount.mount.k_xz),
                  double(mount.mount.k_yz));
  else
    std::snprintf(buf, sizeof(buf), ", sensor height %.2f m (the profile's: too little ground)",
                  double(mount.mount.sensor_height));
  return buf;
}

}  // namespace lpir
