// Why the points of a cloud are invalid, counted on the host by prepare's rule
// (reference_cpu/prepare.cpp), so that the reasons of a frame sum to its points labelled
// kWhyInvalid. Each invalid point counts once, under the first reason it meets in this order.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "reference_cpu/cloud.h"
#include "reference_cpu/params.h"

namespace lpir {

struct InvalidReasons {
  size_t not_finite = 0;    // x, y or z NaN or infinite
  size_t at_origin = 0;     // x, y and z all zero (subnormals flushed, as prepare does)
  size_t out_of_range = 0;  // planar r2 outside [min_range2, max_range2], or z^2 > max_range2
  size_t bad_ring = 0;      // a ring outside [0, beams)
  size_t total() const { return not_finite + at_origin + out_of_range + bad_ring; }
};

// The invalid points of `cloud` under `p`, by reason; `rings_read`: the profile reads the ring
// field (pattern spinning), else a ring is never a reason.
InvalidReasons CountInvalidReasons(const Cloud& cloud, const Params& p, bool rings_read);
// The same from a segmented frame's `why` (one a point): only the points it labels kWhyInvalid
// are looked at, so a frame of a few invalid points costs a few tests, not one a point.
InvalidReasons CountInvalidReasons(const Cloud& cloud, const Params& p, bool rings_read,
                                   const std::vector<uint8_t>& why);

// "3 NaN/Inf, 2 at the origin, 1 out of range, 4 ring outside the beams", naming the reasons with
// a count (in that order; "" when there are none).
std::string DescribeInvalidReasons(const InvalidReasons& r);

}  // namespace lpir
