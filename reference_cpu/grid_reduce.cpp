// Stage 3, grid reduce (paper eq. 4, V-C.1): the concentric zone model.
// In: flags, r2, zt, point_pixel; tables.ring_bound2. Out: point_cell; per cell cell_zmin,
// cell_zmax (ordered keys of z_t), cell_count. Invalid and noise points have no cell.
// Ring: the first ring whose squared outer radius exceeds r2 (binary search; points beyond the
// last ring have no cell). Eq. 4 writes the far ring index as floor(r/res_c) + floor((r - r_thr) /
// res_f), which counts the near rings past r_thr twice; we number the far rings after the near
// ones, which is what the zone model means. Sector: from the image column (no angle needed):
// u / (width / sectors) with the zone's sector count. Cell = near rings x near sectors, then far.
// Reductions: integer min/max/add, order-independent.
#include <algorithm>
#include <vector>

#include "reference_cpu/exact.h"
#include "reference_cpu/stages.h"

namespace lpir {

uint32_t RingOf(float r2, const float* bound2, uint32_t rings) {
  uint32_t lo = 0, hi = rings;  // first index with r2 < bound2[index], rings when none
  while (lo < hi) {
    const uint32_t mid = (lo + hi) >> 1;
    if (r2 < bound2[mid])
      hi = mid;
    else
      lo = mid + 1;
  }
  return lo;
}

void GridReduce(const Params& p, const Tables& t, Frame& f) {
  const uint32_t n = f.n, cells = CellCount(p), rings = p.rings_near + p.rings_far;
  const uint32_t width = p.width, rings_near = p.rings_near;
  const uint32_t sectors_near = p.sectors_near, sectors_far = p.sectors_far;
  f.point_cell.resize(n);
  f.cell_zmin.assign(cells, kNone);
  f.cell_zmax.assign(cells, 0u);
  f.cell_count.assign(cells, 0u);
  const uint32_t cols_near = width / sectors_near, cols_far = width / sectors_far;
  const float* bound2 = t.ring_bound2.data();
  // Sector of every column in each zone, so the per-point loop divides nothing.
  thread_local std::vector<uint32_t> sector_near, sector_far;
  sector_near.resize(width), sector_far.resize(width);
  for (uint32_t u = 0; u < width; ++u) sector_near[u] = u / cols_near, sector_far[u] = u / cols_far;
  const float inv_width = exact::Div(1.0f, float(width));
  const uint32_t* __restrict flags = f.flags.data();
  const float* __restrict r2s = f.r2.data();
  const float* __restrict zt = f.zt.data();
  const uint32_t* __restrict point_pixel = f.point_pixel.data();
  uint32_t* __restrict point_cell = f.point_cell.data();
  uint32_t* __restrict zmin = f.cell_zmin.data();
  uint32_t* __restrict zmax = f.cell_zmax.data();
  uint32_t* __restrict count = f.cell_count.data();
  const uint32_t* __restrict sn = sector_near.data();
  const uint32_t* __restrict sf = sector_far.data();
  const uint32_t far_base = rings_near * sectors_near;
  uint32_t hint =
      0;  // the previous point's ring: the ring is unique, so a right hint is the answer
  for (uint32_t i = 0; i < n; ++i) {
    point_cell[i] = kNone;
    if (flags[i] != kPointValid) continue;  // invalid or noise
    const float r2 = r2s[i];
    const bool hint_right =
        (hint == 0 || r2 >= bound2[hint - 1]) && (hint == rings || r2 < bound2[hint]);
    const uint32_t ring = hint_right ? hint : RingOf(r2, bound2, rings);
    hint = ring;
    if (ring >= rings) continue;
    const uint32_t pix = point_pixel[i];
    uint32_t v = uint32_t(float(pix) * inv_width);  // pix / width, then made exact
    while (v * width > pix) --v;
    while ((v + 1) * width <= pix) ++v;
    const uint32_t u = pix - v * width;
    const uint32_t cell = ring < rings_near ? ring * sectors_near + sn[u]
                                            : far_base + (ring - rings_near) * sectors_far + sf[u];
    point_cell[i] = cell;
    const uint32_t key = exact::Key(zt[i]);
    zmin[cell] = std::min(zmin[cell], key);
    zmax[cell] = std::max(zmax[cell], key);
    count[cell] += 1;
  }
}

}  // namespace lpir
