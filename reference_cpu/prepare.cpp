// Stage 1, prepare (paper III-B.1, eq. 3).
// In: cloud xyzi (+ ring). Out per point: flags (kPointValid, kPointNoise), zt, r2, inten.
// Valid: x, y, z, intensity finite; not exactly (0, 0, 0); min_range2 <= r2 <= max_range2; z^2 <= max_range2; ring
// (when present) inside [0, beams). Everything of an invalid point is written as 0.
// inten is clamped to [-kMaxIntensity, kMaxIntensity] (1e4, far beyond any sensor's [0, 1]): stage
// 5 quantises it to 1e-4 steps and squares it in int64, which a raw intensity of 1e30 overflowed.
// Subnormal inputs (x, y, z, intensity) and outputs (zt, r2, inten) are flushed to zero.
// Operations, in this order: r2 = x*x + y*y; zt = z - (k_xz*x + k_yz*y) (eq. 3: two products, one
// sum, one difference); inten = intensity * intensity_scale; noise = zt < h_noise && inten < i_noise.
#include <algorithm>
#include <cmath>

#include "reference_cpu/exact.h"
#include "reference_cpu/stages.h"

namespace lpir {
namespace {

constexpr float kMaxIntensity = 10000.0f;  // shaders/prepare.comp: the same bound

// |bits| - 1 is below 0x7FFFFF exactly for subnormals (zero wraps to the largest value), so the
// minimum over several values tells whether any is subnormal, with one branch that real scans
// never take.
inline uint32_t SubKey(float f) { return (exact::Bits(f) & 0x7FFFFFFFu) - 1u; }
inline bool AnySubnormal(uint32_t a, uint32_t b, uint32_t c, uint32_t d = ~0u) {
  return std::min(std::min(a, b), std::min(c, d)) < 0x007FFFFFu;
}

}  // namespace

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
    float x = cloud.xyzi[4 * i], y = cloud.xyzi[4 * i + 1], z = cloud.xyzi[4 * i + 2];
    float in = cloud.xyzi[4 * i + 3];
    // Subnormal inputs and outputs are flushed to zero, so a device that flushes them agrees
    // (Vulkan leaves denormal handling to the device). A valid point has r2 >= min_range2, so no
    // intermediate underflow can reach an output otherwise.
    if (AnySubnormal(SubKey(x), SubKey(y), SubKey(z), SubKey(in)))
      x = exact::Ftz(x), y = exact::Ftz(y), z = exact::Ftz(z), in = exact::Ftz(in);
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
    float zt = z - tilt;  // eq. 3
    float inten = in * p.intensity_scale;
    inten = std::min(std::max(inten, -kMaxIntensity), kMaxIntensity);
    float r2_out = r2;
    if (AnySubnormal(SubKey(zt), SubKey(r2), SubKey(inten)))
      zt = exact::Ftz(zt), r2_out = exact::Ftz(r2), inten = exact::Ftz(inten);
    uint32_t flags = kPointValid;
    if (zt < p.h_noise && inten < p.i_noise) flags |= kPointNoise;
    f.flags[i] = flags;
    f.zt[i] = zt;
    f.r2[i] = r2_out;
    f.inten[i] = inten;
  }
}

}  // namespace lpir
