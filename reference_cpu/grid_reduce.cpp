// grid_reduce (paper eq. 4, V-C.1): the concentric zone model.
// In: flags, r2, zt, point_pixel; tables.ring_bound2. Out: point_cell; per cell cell_zmin,
// cell_zmax (ordered keys of z_t), cell_count. Invalid and noise points have no cell.
// Ring: the first ring whose squared outer radius exceeds r2 (binary search; points beyond the
// last ring have no cell). Eq. 4 writes the far ring index as floor(r/res_c) + floor((r - r_thr) /
// res_f), which counts the near rings past r_thr twice; we number the far rings after the near
// ones, which is what the zone model means. Sector: from the image column (no angle needed):
// u / (width / sectors) with the zone's sector count. Cell = near rings x near sectors, then far.
// Reductions: integer min/max/add, order-independent.
#include <algorithm>
#include <limits>
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

namespace {

// Per cell: the ordered keys of min and max z_t, and the count.
struct CellSums {
  uint32_t* zmin;
  uint32_t* zmax;
  uint32_t* count;
};

// pix / width for every pixel index pix < 2^28 (beams <= 4096, width <= 65536), as a multiply and a
// shift: with l = ceil(log2(width)) and m = ceil(2^(28 + l) / width), 2^(28 + l) <= m width <=
// 2^(28 + l) + 2^l, so floor(pix m / 2^(28 + l)) = floor(pix / width) (Granlund and Montgomery
// 1994, Theorem 4.2); m < 2^29 + 1, so pix m fits 58 bits.
struct RowOfPixel {
  uint64_t m;
  uint32_t shift;
  explicit RowOfPixel(uint32_t width) {
    uint32_t l = 0;
    while ((uint64_t(1) << l) < width) ++l;
    shift = 28 + l;
    m = ((uint64_t(1) << shift) + width - 1) / width;
  }
  uint32_t operator()(uint32_t pix) const { return uint32_t((uint64_t(pix) * m) >> shift); }
};

// The cell of every point of `points` (point_cell) and the cells' reductions over them into
// `out` (which holds kNone, 0, 0 for a cell no point has reached). A run of consecutive points in
// one cell (scan order keeps a sector's points together) is reduced in registers and merged into
// the cell when the run ends, so that each point does not wait on the last one's store. `edges`
// holds the rings' edges with one before and one after: -inf, ring_bound2[0 .. rings - 1], +inf, so
// that ring k spans edges[k] <= r2 < edges[k + 1] for every k in 0 .. rings (rings: beyond the
// last).
void CellsOf(const Params& p, const Tables& t, Frame& f, const uint32_t* __restrict sn,
             const uint32_t* __restrict sf, const float* __restrict edges, Range points,
             const CellSums& out) {
  const uint32_t rings = p.rings_near + p.rings_far;
  const uint32_t width = p.width, rings_near = p.rings_near;
  const uint32_t sectors_near = p.sectors_near, sectors_far = p.sectors_far;
  const float* bound2 = t.ring_bound2.data();
  const RowOfPixel row_of(width);
  const uint32_t* __restrict flags = f.flags.data();
  const float* __restrict r2s = f.r2.data();
  const float* __restrict zt = f.zt.data();
  const uint32_t* __restrict point_pixel = f.point_pixel.data();
  uint32_t* __restrict point_cell = f.point_cell.data();
  uint32_t* __restrict zmin = out.zmin;
  uint32_t* __restrict zmax = out.zmax;
  uint32_t* __restrict count = out.count;
  const uint32_t far_base = rings_near * sectors_near;
  uint32_t hint =
      0;  // the previous point's ring: the ring is unique, so a right hint is the answer
  uint32_t run_cell = 0, run_min = kNone, run_max = 0, run_count = 0;  // the run so far
  auto merge_run = [&] {
    zmin[run_cell] = std::min(zmin[run_cell], run_min);
    zmax[run_cell] = std::max(zmax[run_cell], run_max);
    count[run_cell] += run_count;
  };
  for (uint32_t i = points.begin; i < points.end; ++i) {
    point_cell[i] = kNone;
    if (flags[i] != kPointValid) continue;  // invalid or noise
    const float r2 = r2s[i];
    const bool hint_right = (r2 >= edges[hint]) & (r2 < edges[hint + 1]);
    const uint32_t ring = hint_right ? hint : RingOf(r2, bound2, rings);
    hint = ring;
    if (ring >= rings) continue;
    const uint32_t pix = point_pixel[i];
    const uint32_t u = pix - row_of(pix) * width;
    const uint32_t cell = ring < rings_near ? ring * sectors_near + sn[u]
                                            : far_base + (ring - rings_near) * sectors_far + sf[u];
    point_cell[i] = cell;
    if (cell != run_cell) {
      if (run_count) merge_run();
      run_cell = cell, run_min = kNone, run_max = 0, run_count = 0;
    }
    const uint32_t key = exact::Key(zt[i]);
    run_min = std::min(run_min, key);
    run_max = std::max(run_max, key);
    run_count += 1;
  }
  if (run_count) merge_run();
}

// Scratch reused from frame to frame: every column's sector in each zone, the rings' edges
// (CellsOf), and the cell reductions of the pieces after the first (which reduces into the frame),
// three cells' arrays a piece.
struct Scratch {
  std::vector<uint32_t> sector_near, sector_far;
  std::vector<float> edges;
  std::vector<uint32_t> pieces;
};
thread_local Scratch scratch;

}  // namespace

// Pieces of points, each reducing into its own cells (the first into the frame's); then the
// pieces' cells are merged (min, max, sum: integers, in any order the same).
void GridReduce(const Params& p, const Tables& t, Frame& f, Threads threads) {
  const uint32_t n = f.n, cells = CellCount(p), width = p.width;
  f.point_cell.resize(n);
  f.cell_zmin.assign(cells, kNone);
  f.cell_zmax.assign(cells, 0u);
  f.cell_count.assign(cells, 0u);
  Scratch& s = scratch;
  // Sector of every column in each zone, so the per-point loop divides nothing.
  const uint32_t cols_near = width / p.sectors_near, cols_far = width / p.sectors_far;
  s.sector_near.resize(width), s.sector_far.resize(width);
  for (uint32_t u = 0; u < width; ++u)
    s.sector_near[u] = u / cols_near, s.sector_far[u] = u / cols_far;
  const uint32_t rings = p.rings_near + p.rings_far;
  s.edges.assign(size_t(rings) + 2, std::numeric_limits<float>::infinity());
  s.edges[0] = -std::numeric_limits<float>::infinity();
  std::copy(t.ring_bound2.begin(), t.ring_bound2.begin() + rings, s.edges.begin() + 1);
  const uint32_t pieces = PiecesFor(threads, n, 4096);
  s.pieces.resize(size_t(pieces - 1) * 3 * cells);
  auto sums = [&](uint32_t k) {
    if (k == 0) return CellSums{f.cell_zmin.data(), f.cell_zmax.data(), f.cell_count.data()};
    uint32_t* c = s.pieces.data() + size_t(k - 1) * 3 * cells;
    return CellSums{c, c + cells, c + 2 * cells};
  };
  ForPieces(threads, pieces, n, [&](uint32_t k, Range points) {
    const CellSums out = sums(k);
    if (k > 0) {  // the frame's were set above
      std::fill(out.zmin, out.zmin + cells, kNone);
      std::fill(out.zmax, out.zmax + cells, 0u);
      std::fill(out.count, out.count + cells, 0u);
    }
    CellsOf(p, t, f, s.sector_near.data(), s.sector_far.data(), s.edges.data(), points, out);
  });
  if (pieces == 1) return;
  ForPieces(threads, PiecesFor(threads, cells, 256), cells, [&](uint32_t, Range r) {
    const CellSums all = sums(0);
    for (uint32_t k = 1; k < pieces; ++k) {
      const CellSums piece = sums(k);
      for (uint32_t c = r.begin; c < r.end; ++c) {
        all.zmin[c] = std::min(all.zmin[c], piece.zmin[c]);
        all.zmax[c] = std::max(all.zmax[c], piece.zmax[c]);
        all.count[c] += piece.count[c];
      }
    }
  });
}

}  // namespace lpir
