// Stage 1, prepare (paper III-B.1, eq. 3).
// In: cloud xyzi (+ ring). Out per point: flags (kPointValid, kPointNoise), zt, r2, inten.
// Valid: x, y, z, intensity finite; not exactly (0, 0, 0); min_range2 <= r2 <= max_range2; z^2 <= max_range2; ring
// (when present) inside [0, beams). Everything of an invalid point is written as 0.
// Operations, in this order: r2 = x*x + y*y; zt = z - (k_xz*x + k_yz*y) (eq. 3: two products, one
// sum, one difference); inten = intensity * intensity_scale; noise = zt < h_noise && inten < i_noise.
#include <cmath>

#include "reference_cpu/stages.h"

namespace lpir {

void Prepare(const Cloud& cloud, const Params& p, Frame& f) {
  const uint32_t n = uint32_t(cloud.size());
  f.n = n;
  f.flags.resize(n);
  f.zt.resize(n);
  f.r2.resize(n);
  f.inten.resize(n);
  const bool has_ring = !cloud.ring.empty();
  for (uint32_t i = 0; i < n; ++i) {
    f.flags[i] = 0u, f.zt[i] = 0.0f, f.r2[i] = 0.0f, f.inten[i] = 0.0f;  // until proven valid
    const float x = cloud.xyzi[4 * i], y = cloud.xyzi[4 * i + 1], z = cloud.xyzi[4 * i + 2];
    const float in = cloud.xyzi[4 * i + 3];
    if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(z) || !std::isfinite(in)) continue;
    if (x == 0.0f && y == 0.0f && z == 0.0f) continue;
    if (has_ring && (cloud.ring[i] < 0 || uint32_t(cloud.ring[i]) >= p.beams)) continue;
    const float xx = x * x, yy = y * y;
    const float r2 = xx + yy;
    if (!(r2 >= p.min_range2) || !(r2 <= p.max_range2)) continue;
    const float zz = z * z;
    if (!(zz <= p.max_range2)) continue;  // |z| beyond the sensor's range: garbage
    const float tx = p.k_xz * x, ty = p.k_yz * y;
    const float tilt = tx + ty;
    const float zt = z - tilt;  // eq. 3
    const float inten = in * p.intensity_scale;
    uint32_t flags = kPointValid;
    if (zt < p.h_noise && inten < p.i_noise) flags |= kPointNoise;
    f.flags[i] = flags;
    f.zt[i] = zt;
    f.r2[i] = r2;
    f.inten[i] = inten;
  }
}

}  // namespace lpir
