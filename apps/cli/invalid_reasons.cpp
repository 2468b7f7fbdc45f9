// prepare's validity test, reason by reason (see invalid_reasons.h): the same flushed inputs and
// the same float operations as reference_cpu/prepare.cpp, so that a point is invalid here exactly
// when it is invalid there.
#include "apps/cli/invalid_reasons.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <utility>

#include "reference_cpu/exact.h"
#include "reference_cpu/frame.h"

namespace lpir {

namespace {

// Adds point i's reason, if it has one, to r.
void CountPoint(const Cloud& cloud, const Params& p, bool has_ring, size_t i, InvalidReasons& r) {
  const float x = exact::Ftz0(cloud.x(i)), y = exact::Ftz0(cloud.y(i));
  const float z = exact::Ftz0(cloud.z(i));
  if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(z)) {
    ++r.not_finite;
    return;
  }
  if (x == 0.0f && y == 0.0f && z == 0.0f) {
    ++r.at_origin;
    return;
  }
  const float r2 = exact::Ftz0(x * x) + exact::Ftz0(y * y);
  const float zz = exact::Ftz0(z * z);
  if (!(r2 >= p.min_range2 && r2 <= p.max_range2 && zz <= p.max_range2)) {
    ++r.out_of_range;
    return;
  }
  if (has_ring && !(cloud.ring[i] >= 0 && cloud.ring[i] < int32_t(p.beams))) ++r.bad_ring;
}

}  // namespace

InvalidReasons CountInvalidReasons(const Cloud& cloud, const Params& p, bool rings_read) {
  InvalidReasons r;
  const bool has_ring = rings_read && !cloud.ring.empty();
  for (size_t i = 0; i < cloud.size(); ++i) CountPoint(cloud, p, has_ring, i, r);
  return r;
}

InvalidReasons CountInvalidReasons(const Cloud& cloud, const Params& p, bool rings_read,
                                   const std::vector<uint8_t>& why) {
  InvalidReasons r;
  const bool has_ring = rings_read && !cloud.ring.empty();
  // From one invalid point to the next by memchr (vector code): they are few.
  const uint8_t* const first = why.data();
  const uint8_t* const end = first + std::min(cloud.size(), why.size());
  for (const uint8_t* at = first; at < end; ++at) {
    at = static_cast<const uint8_t*>(std::memchr(at, kWhyInvalid, size_t(end - at)));
    if (!at) break;
    CountPoint(cloud, p, has_ring, size_t(at - first), r);
  }
  return r;
}

std::string DescribeInvalidReasons(const InvalidReasons& r) {
  const std::pair<size_t, const char*> reasons[] = {{r.not_finite, "NaN/Inf"},
                                                    {r.at_origin, "at the origin"},
                                                    {r.out_of_range, "out of range"},
                                                    {r.bad_ring, "ring outside the beams"}};
  std::string text;
  for (const auto& [count, name] : reasons)
    if (count) text += (text.empty() ? "" : ", ") + std::to_string(count) + " " + name;
  return text;
}

}  // namespace lpir
