// prepare (paper III-B.1, eq. 3).
// In: cloud xyz (+ ring); the intensity is not read (docs/decisions/intensity.md). Out per point:
// flags (kPointValid, kPointNoise), zt, r2.
// Valid: x, y, z finite; not exactly (0, 0, 0); min_range2 <= r2 <= max_range2; z^2 <=
// max_range2; ring (when present) inside [0, beams). Everything of an invalid point is written as
// 0.
// Inputs (x, y, z) and every result that can be subnormal (xx, yy, zz, tx, ty, tilt, zt) go
// through exact::Ftz0 (subnormals and -0 to +0), so that a device that flushes gives the same
// bytes (docs/decisions/denormals.md).
// Operations, in this order: r2 = x*x + y*y; zt = z - (k_xz*x + k_yz*y) (eq. 3: two products, one
// sum, one difference); noise = zt < h_noise (reflection noise, III-B.1: deeper under the road
// than any ground the profile's height puts there).

#include "reference_cpu/exact.h"
#include "reference_cpu/stages.h"

namespace lpir {
namespace {

// std::isfinite as one float operation (f - f is 0 exactly when f is finite): fewer vector
// instructions.
inline uint32_t Finite(float f) { return uint32_t(f - f == 0.0f); }

// Points [r.begin, r.end). Every test of every point is computed and the outputs selected by the
// validity, without a branch, so the compiler turns the loop into vector code. Ftz is the identity
// on all but subnormals and -0, so flushing every input and result is the rule above.
template <bool kRing>
void PrepareRange(const Cloud& cloud, const Params& p, Frame& f, Range r) {
  const float* __restrict xyzi = cloud.xyzi.data();
  const int32_t* __restrict ring = cloud.ring.data();
  uint32_t* __restrict flags_out = f.flags.data();
  float* __restrict zt_out = f.zt.data();
  float* __restrict r2_out = f.r2.data();
  const int32_t beams = int32_t(p.beams);
  const float min_range2 = p.min_range2, max_range2 = p.max_range2, k_xz = p.k_xz, k_yz = p.k_yz;
  const float h_noise = p.h_noise;
  for (size_t i = r.begin; i < r.end; ++i) {  // size_t: 4 * i must not wrap, or no vectors
    const float x = exact::Ftz0(xyzi[4 * i]), y = exact::Ftz0(xyzi[4 * i + 1]);
    const float z = exact::Ftz0(xyzi[4 * i + 2]);
    const float xx = exact::Ftz0(x * x), yy = exact::Ftz0(y * y);
    const float r2 = xx + yy;  // 0 or at least 2^-126: never subnormal
    const float zz = exact::Ftz0(z * z);
    const float tx = exact::Ftz0(k_xz * x), ty = exact::Ftz0(k_yz * y);
    const float tilt = exact::Ftz0(tx + ty);
    const float zt = exact::Ftz0(z - tilt);  // eq. 3
    // 0 or 1 each, combined with & so that every test is evaluated (no branch); |z| beyond the
    // sensor's range is garbage; NaN fails every comparison.
    const uint32_t finite = Finite(x) & Finite(y) & Finite(z);
    const uint32_t origin = uint32_t(x == 0.0f) & uint32_t(y == 0.0f) & uint32_t(z == 0.0f);
    uint32_t valid = finite & (origin ^ 1u) & uint32_t(r2 >= min_range2) &
                     uint32_t(r2 <= max_range2) & uint32_t(zz <= max_range2);
    if constexpr (kRing) valid &= uint32_t(ring[i] >= 0) & uint32_t(ring[i] < beams);
    const uint32_t noise = uint32_t(zt < h_noise);
    flags_out[i] = valid ? kPointValid | noise * kPointNoise : 0u;
    zt_out[i] = valid ? zt : 0.0f;
    r2_out[i] = valid ? r2 : 0.0f;
  }
}

}  // namespace

void Prepare(const Cloud& cloud, const Params& p, Frame& f, Threads threads) {
  const uint32_t n = uint32_t(cloud.size());
  f.n = n;
  f.flags.resize(n);
  f.zt.resize(n);
  f.r2.resize(n);
  ForPieces(threads, PiecesFor(threads, n, 4096), n, [&](uint32_t, Range r) {
    if (cloud.ring.empty())
      PrepareRange<false>(cloud, p, f, r);
    else
      PrepareRange<true>(cloud, p, f, r);
  });
}

}  // namespace lpir
