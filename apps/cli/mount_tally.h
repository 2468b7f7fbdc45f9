// segment's account of the mounts its frames were segmented with, for a profile whose mount is
// estimated from every cloud (mount per_frame): the summary's clause and the --verbose lines'.
#pragma once
#include <cstddef>
#include <string>
#include <vector>

#include "host/api/mount_estimate.h"

namespace lpir {

class MountTally {
 public:
  void Add(const MountEstimate& mount);
  // "sensor height estimated on 8 of 8 frames: median 1.23 m (1.22 to 1.26)", then, when some
  // frames showed too little ground, "; 2 took the profile's 1.50 m (too little ground)"; "" when
  // no frame was added.
  std::string Summary(float profile_height) const;
  // One frame's ", sensor height 1.23 m, k_xz 0.0120, k_yz -0.0340 (estimated)", or
  // ", sensor height 1.50 m (the profile's: too little ground)".
  static std::string FrameClause(const MountEstimate& mount);

 private:
  std::vector<float> heights_;  // of the frames whose estimate held
  size_t fallbacks_ = 0;
};

}  // namespace lpir
