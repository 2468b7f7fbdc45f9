// Stage 1, prepare (paper III-B.1, eq. 3).
// In: cloud xyzi (+ ring). Out per point: flags (kPointValid, kPointNoise), zt, r2, inten.
// Valid: x, y, z, intensity finite; not exactly (0, 0, 0); min_range2 <= r2 <= max_range2; z^2 <= max_range2; ring
// (when present) inside [0, beams). Everything of an invalid point is written as 0.
// Subnormal inputs (x, y, z, intensity) and outputs (zt, r2, inten) are flushed to zero.
// Operations, in this order: r2 = x*x + y*y; zt = z - (k_xz*x + k_yz*y) (eq. 3: two products, one
// sum, one difference); inten = intensity * intensity_scale; noise = zt < h_noise && inten < i_noise.
#include <cmath>

#include "reference_cpu/exact.h"
#include "reference_cpu/stages.h"

namespace lpir {

void Prepare(const Cloud& cloud, const Params& p, Frame& f) {
  const uint32_t n = uint32_t(cloud.size());
  f.n = n;
  f.flags.resize(n);
  f.zt.resize(n);
  f.r2.resize(n);
  f.inten.resize(n);
  const float* __restrict xyzi = cloud.xyzi.data();
  const int32_t* __restrict ring = cloud.ring.empty() ? nullptr : cloud.ring.data();
  uint32_t* __restrict flags_out = f.flags.data();
  float* __restrict zt_out = f.zt.data();
  float* __restrict r2_out = f.r2.data();
  float* __restrict inten_out = f.inten.data();
  const Params q = p;  // parameters in registers
  for (uint32_t i = 0; i < n; ++i) {
    flags_out[i] = 0u, zt_out[i] = 0.0f, r2_out[i] = 0.0f, inten_out[i] = 0.0f;  // until valid
    // Subnormal inputs and outputs are flushed to zero, so a device that flushes them agrees
    // (Vulkan leaves denormal handling to the device). A valid point has r2 >= min_range2, so no
    // intermediate underflow can reach an output otherwise.
    const float x = exact::Ftz(xyzi[4 * i]), y = exact::Ftz(xyzi[4 * i + 1]);
    const float z = exact::Ftz(xyzi[4 * i + 2]), in = exact::Ftz(xyzi[4 * i + 3]);
    if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(z) || !std::isfinite(in)) continue;
    if (x == 0.0f && y == 0.0f && z == 0.0f) continue;
    if (ring && (ring[i] < 0 || uint32_t(ring[i]) >= q.beams)) continue;
    const float xx = x * x, yy = y * y;
    const float r2 = xx + yy;
    if (!(r2 >= q.min_range2) || !(r2 <= q.max_range2)) continue;
    const float zz = z * z;
    if (!(zz <= q.max_range2)) continue;  // |z| beyond the sensor's range: garbage
    const float tx = q.k_xz * x, ty = q.k_yz * y;
    const float tilt = tx + ty;
    const float zt = z - tilt;  // eq. 3
    const float inten = in * q.intensity_scale;
    uint32_t flags = kPointValid;
    if (exact::Ftz(zt) < q.h_noise && exact::Ftz(inten) < q.i_noise) flags |= kPointNoise;
    flags_out[i] = flags;
    zt_out[i] = exact::Ftz(zt);
    r2_out[i] = exact::Ftz(r2);
    inten_out[i] = exact::Ftz(inten);
  }
}

}  // namespace lpir
