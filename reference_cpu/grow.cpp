// grow (paper Alg. 1 and the ground connectivity constraint of IV-A).
// In: pixel_fused, f_height, f_range. Out: pixel_grown, pixel_comp, pixel_label.
// Growing: ground pixels are the seeds; an unknown pixel becomes ground when one of its 8
// neighbours (columns wrap around) is ground and the step between them is allowed: height
// changes by at most grow_dz + grow_grade * step, where step = |dr|
// (+ min(r_a, r_b) * column_arc when the column changes) approximates the planar distance
// between the two points (a wall's vertically adjacent pixels are close in height but not in
// distance). A bank's step (our addition) is allowed too: between a pixel and the one above it in
// its column, either of them kPixUnknownOff (its coarse label not ground), when the upper one lies
// farther and no lower and rises at most grow_dz + bank_slope * (its range - the lower one's): a
// grassed embankment climbs away from the sensor, while an object's face comes nearer or keeps
// its range, and ground seen past an object's top lies lower (BankStep; docs/decisions/grow.md,
// Banks). Unknown pixels are kPixUnknown and kPixUnknownOff alike otherwise.
// The test is symmetric in the two pixels, so the grown set is exactly the unknown
// pixels whose component of the allowed-step graph (ground and unknown pixels, allowed steps
// between 8-neighbours) holds a seed: what the shader computes with union-find in a fixed number
// of passes, and what the depth-first search below reaches from the unknown pixels (on threads,
// bands of rows searched side by side, then their edges again until nothing grows: GrowAll).
// Unknown pixels left over are non-ground. Decision and measurements: docs/decisions/grow.md.
// Connectivity: 8-connected components of ground pixels, each labelled by its lowest pixel index
// (pixel_comp, kNone elsewhere); components of fewer than min_component pixels become non-ground
// in pixel_label and keep their component label in pixel_comp (it records the components found),
// except one of at least comp_seed_min pixels whose seeds (pixels fused ground) number at least
// comp_seed_share * its size (one rounded float product; counts are exact in float below 2^24):
// ground that the coarse segmentation vouches for, cut off from the rest (a sidewalk between
// parked cars), not an object's flat top grown from a few seeds (docs/decisions/grow.md).
// Lifting the veto (our addition), after the component test, each vetoed pixel (kPixVetoed, kept
// so in pixel_grown) judged on the labels before any lift: it is ground when its two row
// neighbours (columns wrap) are ground and the step from each to it is allowed, or when the pixel
// above it is ground and its ray did not pass under that pixel (not: d = Ftz0(range above - r) <
// 0 and Ftz0(z * d) >= Ftz0(occ_pass * r)); else non-ground. Why: ground goes on around it, so
// what the veto saw above it was ground rising (a curb's top, a bank) or a thing one pixel wide
// (a pole, a post), not an object's foot; the pass test keeps reflection noise, seen under the
// road, vetoed (docs/decisions/grow.md).
// pixel_label: kPixGround / kPixNonGround, kPixEmpty where no pixel was measured or filled.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>

#include "reference_cpu/exact.h"
#include "reference_cpu/stages.h"

namespace lpir {
namespace {

// Growing works on one byte per pixel: kGround, kUnknown, or 0 for every other class.
constexpr uint8_t kGround = 1, kUnknown = 2;
constexpr uint64_t kBytes = 0x0101010101010101u;  // one bit in each byte of a word

// A pixel and its row (so that neighbours are enumerated without dividing by the width).
struct Pixel {
  uint32_t pix, v;
};

// A run of ground pixels on one row: columns u0..u1 (inclusive; runs do not wrap, the union
// step joins the runs at the two ends of a row).
struct Run {
  uint32_t start, u0, u1;
};

// Scratch reused from frame to frame, each thread's own. A frame split over threads keeps its
// buffers in the calling thread's, the pieces writing disjoint parts of them; each piece's search
// uses its own thread's stack.
struct Scratch {
  std::vector<uint8_t> state;  // per pixel: kGround, kUnknown or 0
  std::vector<uint8_t> edges;  // per band: its first and last rows' states, w each
  std::vector<Pixel> stack;
  std::vector<Run> runs;
  std::vector<uint32_t> row_runs;  // beams + 1 offsets into runs
  std::vector<uint32_t> parent, comp_size, run_seeds, comp_seeds;
  std::vector<uint8_t> band_grew;  // per band: grown from its edges in the last round
  std::vector<std::vector<Run>> band_runs;
  std::vector<std::vector<uint32_t>> lifted, kept;  // per band: vetoed pixels lifted, kept vetoed
};
thread_local Scratch scratch;

// Eight bytes of the state (any alignment).
inline uint64_t Word(const uint8_t* s) {
  uint64_t x;
  std::memcpy(&x, s, sizeof x);
  return x;
}

// The step test of the contract between pixels q and r (features z, r): symmetric in them, each
// result through Ftz0 as the shader does (a device may flush a subnormal one).
inline bool StepAllowed(const Params& p, float zq, float rq, float zr, float rr,
                        bool column_changes) {
  const float dz = exact::Ftz0(std::fabs(zr - zq));
  float step = exact::Ftz0(std::fabs(rr - rq));
  if (column_changes) step = exact::Ftz0(step + exact::Ftz0(std::min(rq, rr) * p.column_arc));
  const float allowed = exact::Ftz0(p.grow_dz + exact::Ftz0(p.grow_grade * step));
  return dz <= allowed;
}

// The bank's step of the contract (our addition) from pixel lo up its column to pixel up, the row
// above: allowed when up lies farther and no lower, rising at most grow_dz + bank_slope * (its
// range - lo's range); each result through Ftz0 as the shader does. Asked only where either pixel
// is kPixUnknownOff (its coarse label not ground): a bank rises beyond the coarse planes.
inline bool BankStep(const Params& p, float z_up, float r_up, float z_lo, float r_lo) {
  const float d = exact::Ftz0(r_up - r_lo);
  const float rise = exact::Ftz0(z_up - z_lo);
  const float allowed = exact::Ftz0(p.grow_dz + exact::Ftz0(p.bank_slope * d));
  return d > 0.0f && rise >= 0.0f && rise <= allowed;
}

uint32_t Find(uint32_t* __restrict up, uint32_t x) {
  while (up[x] != x) x = up[x] = up[up[x]];
  return x;
}

// Joins two runs' sets; the root is the lower run index, i.e. the run with the lowest pixel.
inline void Union(uint32_t* __restrict up, uint32_t a, uint32_t b) {
  a = Find(up, a), b = Find(up, b);
  if (a < b)
    up[b] = a;
  else if (b < a)
    up[a] = b;
}

// The growing state of every pixel (ToState and WriteOutputs take __restrict pointers, so that
// their loops vectorise: a byte store may alias any pointer not marked so).
void ToState(const uint32_t* __restrict fused, uint8_t* __restrict s, uint32_t pixels) {
  for (uint32_t pix = 0; pix < pixels; ++pix) {
    const uint32_t c = fused[pix];
    const bool unknown = (c == kPixUnknown) | (c == kPixUnknownOff);
    s[pix] = uint8_t((c == kPixGround) | unknown << 1);  // kGround, kUnknown
  }
}

// pixel_grown and pixel_label: ground where grown, non-ground where still unknown, else as
// fused; pixel_comp kNone (the runs are filled in after).
void WriteOutputs(const uint32_t* __restrict fused, const uint8_t* __restrict s, uint32_t pixels,
                  uint32_t* __restrict grown, uint32_t* __restrict label,
                  uint32_t* __restrict comp) {
  for (uint32_t pix = 0; pix < pixels; ++pix) {
    const uint32_t t = s[pix], other = t == 0 ? ~0u : 0u;
    const uint32_t c = (fused[pix] & other) | (t & 1u);  // kGround -> kPixGround
    grown[pix] = c;
    label[pix] = c;
    comp[pix] = kNone;
  }
}

// Growing, driven by the (few) unknown pixels rather than the (many) seeds: an unknown pixel
// that a ground neighbour may step to becomes ground, and a depth-first search grows on from it.
// Every pair (ground, unknown neighbour) is tested, when the scan reaches the unknown pixel or
// when the ground pixel is grown, so the search ends at the fixed point. Each neighbour is named
// by hand (columns wrap, rows do not; `moved` when its column differs), without dividing by the
// width. It grows rows v0 .. v1 - 1 (a band; the whole image: 0 .. h) and writes only them; the
// states of the rows just outside it, v0 - 1 and v1, are read from `above` and `below` (copies
// taken while nothing grows; null: the row is not seen), so that bands grow side by side.
class Growing {
 public:
  Growing(const Params& p, const Frame& f, uint8_t* s, std::vector<Pixel>& stack, uint32_t v0,
          uint32_t v1, const uint8_t* above, const uint8_t* below)
      : p_(p),
        w_(p.width),
        v0_(v0),
        v1_(v1),
        height_(f.f_height.data()),
        range_(f.f_range.data()),
        fused_(f.pixel_fused.data()),
        s_(s),
        above_(above),
        below_(below),
        stack_(stack) {}

  // Visits every unknown pixel of the rows in scan order (eight at a time where a word holds none).
  void Scan() {
    stack_.clear();
    for (uint32_t v = v0_; v < v1_; ++v) {
      const uint8_t* row = s_ + v * w_;
      uint32_t u = 0;
      for (; u + 8 <= w_; u += 8)
        if (Word(row + u) & (kBytes * kUnknown))
          for (uint32_t j = u; j < u + 8; ++j)
            if (row[j] == kUnknown) Visit(v, j);
      for (; u < w_; ++u)
        if (row[u] == kUnknown) Visit(v, u);
    }
  }

  // Visits the unknown pixels of the first and last rows again, against the rows outside them:
  // whatever grew there since the last look. Returns whether any pixel grew.
  bool ScanEdges() {
    stack_.clear();
    grew_ = false;
    for (uint32_t v : {v0_, v1_ - 1}) {
      if (v == v0_ ? !above_ : !below_) continue;
      for (uint32_t u = 0; u < w_; ++u)
        if (s_[v * w_ + u] == kUnknown) Visit(v, u);
    }
    return grew_;
  }

 private:
  // The states of row v: the band's own, a copy for the rows just outside it, else null.
  const uint8_t* RowState(uint32_t v) const {
    if (v >= v0_ && v < v1_) return s_ + v * w_;
    if (v + 1 == v0_) return above_;
    return v == v1_ ? below_ : nullptr;
  }

  // Tests the unknown pixel (v, u) against its ground neighbours; grows from it if one passes.
  // The scan reads each pixel's state when it reaches it: pixels grown meanwhile are skipped.
  void Visit(uint32_t v, uint32_t u) {
    const uint32_t w = w_;
    const uint32_t at = v * w, r = at + u;
    const uint32_t ul = u == 0 ? w - 1 : u - 1, ur = u + 1 == w ? 0 : u + 1;
    const bool left = ul != u, right = ur != u;
    const float zr = height_[r], rr = range_[r];
    // Whether the pixel of column c of the row starting at pixel `row`, states `st`, is ground
    // and may step to r.
    auto from = [&](const uint8_t* st, uint32_t row, uint32_t c, bool moved) {
      if (st[c] != kGround) return false;
      return StepAllowed(p_, height_[row + c], range_[row + c], zr, rr, moved);
    };
    const uint8_t* here = s_ + at;
    bool grows = from(here, at, ul, left) || from(here, at, ur, right);
    const uint8_t* up = RowState(v - 1);  // v - 1 wraps past every row when v is 0
    if (!grows && up) {
      const uint32_t above = at - w;
      grows = from(up, above, ul, left) || from(up, above, u, false) ||
              from(up, above, ur, right) || (up[u] == kGround && Climbs(above + u, r));
    }
    const uint8_t* down = RowState(v + 1);
    if (!grows && down) {
      const uint32_t below = at + w;
      grows = from(down, below, ul, left) || from(down, below, u, false) ||
              from(down, below, ur, right) || (down[u] == kGround && Climbs(r, below + u));
    }
    if (grows) {
      s_[r] = kGround;
      grew_ = true;
      stack_.push_back({r, v});
      Drain();
    }
  }

  // Grows on from the pixels on the stack until it is empty, within the band's rows.
  void Drain() {
    const uint32_t w = w_;
    uint8_t* s = s_;
    while (!stack_.empty()) {
      const Pixel q = stack_.back();
      stack_.pop_back();
      const uint32_t v = q.v, at = v * w, u = q.pix - at;
      const uint32_t ul = u == 0 ? w - 1 : u - 1, ur = u + 1 == w ? 0 : u + 1;
      const bool left = ul != u, right = ur != u;
      const float zq = height_[q.pix], rq = range_[q.pix];
      // vertical: 0 beside or diagonal, 1 r the row above q, -1 r the row below.
      auto to = [&](uint32_t r, uint32_t rv, bool moved, int vertical = 0) {
        if (s[r] != kUnknown) return;
        if (StepAllowed(p_, zq, rq, height_[r], range_[r], moved) ||
            (vertical > 0 && Climbs(r, q.pix)) || (vertical < 0 && Climbs(q.pix, r))) {
          s[r] = kGround;
          stack_.push_back({r, rv});
        }
      };
      if (v > v0_) {
        const uint32_t above = at - w;
        to(above + ul, v - 1, left), to(above + u, v - 1, false, 1), to(above + ur, v - 1, right);
      }
      to(at + ul, v, left), to(at + ur, v, right);
      if (v + 1 < v1_) {
        const uint32_t below = at + w;
        to(below + ul, v + 1, left), to(below + u, v + 1, false, -1), to(below + ur, v + 1, right);
      }
    }
  }

  // The bank's step between pixel up and pixel lo, the one below it in its column, where either
  // is kPixUnknownOff (BankStep).
  bool Climbs(uint32_t up, uint32_t lo) const {
    if (fused_[up] != kPixUnknownOff && fused_[lo] != kPixUnknownOff) return false;
    return BankStep(p_, height_[up], range_[up], height_[lo], range_[lo]);
  }

  const Params& p_;
  const uint32_t w_, v0_, v1_;
  const float* const height_;
  const float* const range_;
  const uint32_t* const fused_;
  uint8_t* const s_;
  const uint8_t* const above_;
  const uint8_t* const below_;
  std::vector<Pixel>& stack_;
  bool grew_ = false;
};

// Grows the whole image: one band on one thread, else bands of rows side by side, each growing
// within its rows (the states of the rows just outside it as they were before), then rounds in
// which every band visits its first and last rows' unknown pixels against copies of the
// neighbouring bands' edge rows, until a round grows nothing. The step test is symmetric and the
// growth only adds, so this ends at the same fixed point as one search over the image: the unknown
// pixels whose allowed-step component holds a seed.
void GrowAll(const Params& p, const Frame& f, Scratch& s, Threads threads) {
  const uint32_t w = p.width, h = p.beams;
  uint8_t* state = s.state.data();
  const uint32_t bands = PiecesFor(threads, h, 8);
  if (bands == 1) {
    Growing(p, f, state, s.stack, 0, h, nullptr, nullptr).Scan();
    return;
  }
  // Band b's first row's states at edges[2 b w], its last row's at edges[(2 b + 1) w].
  s.edges.resize(size_t(2) * bands * w);
  s.band_grew.assign(bands, 0);
  auto copy_edges = [&] {
    for (uint32_t b = 0; b < bands; ++b) {
      const Range rows = PieceOf(h, bands, b);
      std::memcpy(&s.edges[size_t(2 * b) * w], state + size_t(rows.begin) * w, w);
      std::memcpy(&s.edges[size_t(2 * b + 1) * w], state + size_t(rows.end - 1) * w, w);
    }
  };
  auto band = [&](uint32_t b, Range rows) {
    const uint8_t* above = b > 0 ? &s.edges[size_t(2 * b - 1) * w] : nullptr;
    const uint8_t* below = b + 1 < bands ? &s.edges[size_t(2 * b + 2) * w] : nullptr;
    return Growing(p, f, state, scratch.stack, rows.begin, rows.end, above, below);
  };
  copy_edges();
  ForPieces(threads, bands, h, [&](uint32_t b, Range rows) { band(b, rows).Scan(); });
  for (bool grew = true; grew;) {
    copy_edges();
    ForPieces(threads, bands, h,
              [&](uint32_t b, Range rows) { s.band_grew[b] = band(b, rows).ScanEdges(); });
    grew = false;
    for (uint8_t g : s.band_grew) grew = grew || g;
  }
}

// The runs of ground pixels of rows `rows`, row by row, into `runs` (row_runs[v] .. row_runs[v +
// 1] - 1 are row v's), skipping eight pixels at a time where a word is all in or all out of the
// current run.
void FindRuns(const uint8_t* s, uint32_t w, Range rows, std::vector<Run>& runs,
              uint32_t* row_runs) {
  runs.clear();
  for (uint32_t v = rows.begin; v < rows.end; ++v) {
    row_runs[v] = uint32_t(runs.size());
    const uint32_t row = v * w;
    const uint8_t* g = s + row;
    bool in_run = false;
    uint32_t u0 = 0;
    for (uint32_t u = 0; u < w; ++u) {
      if ((u & 7) == 0 && u + 8 <= w && (Word(g + u) & kBytes) == (in_run ? kBytes : 0)) {
        u += 7;
        continue;
      }
      const bool ground = g[u] == kGround;
      if (ground == in_run) continue;
      if (ground)
        u0 = u;
      else
        runs.push_back({row + u0, u0, u - 1});
      in_run = ground;
    }
    if (in_run) runs.push_back({row + u0, u0, w - 1});
  }
}

// Joins the runs of row v that touch across the wrap.
void JoinWrap(uint32_t* __restrict up, const Scratch& s, uint32_t w, uint32_t v) {
  const Run* __restrict run = s.runs.data();
  const uint32_t b = s.row_runs[v], e = s.row_runs[v + 1];
  if (b != e && run[b].u0 == 0 && run[e - 1].u1 == w - 1) Union(up, b, e - 1);
}

// Joins the runs of row v (v > 0) that touch runs of row v - 1 (8-connected, across the wrap too).
void JoinAbove(uint32_t* __restrict up, const Scratch& s, uint32_t w, uint32_t v) {
  const Run* __restrict run = s.runs.data();
  const uint32_t b = s.row_runs[v], e = s.row_runs[v + 1];
  const uint32_t pb = s.row_runs[v - 1], pe = s.row_runs[v];
  if (b == e || pb == pe) return;
  // The diagonals across the wrap.
  if (run[pe - 1].u1 == w - 1 && run[b].u0 == 0) Union(up, pe - 1, b);
  if (run[pb].u0 == 0 && run[e - 1].u1 == w - 1) Union(up, pb, e - 1);
  for (uint32_t i = pb, j = b; i < pe && j < e;) {
    if (run[i].u1 + 1 < run[j].u0) {
      ++i;
    } else if (run[j].u1 + 1 < run[i].u0) {
      ++j;
    } else {
      Union(up, i, j);
      if (run[i].u1 < run[j].u1)
        ++i;
      else
        ++j;
    }
  }
}

// The runs of every row (FindRuns, in bands of rows, then laid end to end), and the runs that
// touch joined (in bands of rows, then across the bands' edges). A union keeps the lower root, so
// a set's root is its lowest run, the one with the lowest pixel, whatever the order of the unions.
// Leaves every run's root in parent and each root's pixel count in comp_size.
void FindComponents(uint32_t w, uint32_t h, Scratch& s, Threads threads) {
  const uint8_t* state = s.state.data();
  s.row_runs.resize(h + 1);
  const uint32_t bands = PiecesFor(threads, h, 8);
  if (bands == 1) {
    FindRuns(state, w, {0, h}, s.runs, s.row_runs.data());
  } else {
    s.band_runs.resize(bands);
    ForPieces(threads, bands, h, [&](uint32_t b, Range rows) {
      FindRuns(state, w, rows, s.band_runs[b], s.row_runs.data());
    });
    s.runs.clear();
    for (uint32_t b = 0; b < bands; ++b) {
      const Range rows = PieceOf(h, bands, b);
      for (uint32_t v = rows.begin; v < rows.end; ++v) s.row_runs[v] += uint32_t(s.runs.size());
      s.runs.insert(s.runs.end(), s.band_runs[b].begin(), s.band_runs[b].end());
    }
  }
  s.row_runs[h] = uint32_t(s.runs.size());
  const uint32_t n = uint32_t(s.runs.size());
  s.parent.resize(n);
  s.comp_size.assign(n, 0);
  uint32_t* __restrict up = s.parent.data();
  for (uint32_t k = 0; k < n; ++k) up[k] = k;
  // A band's unions touch only its own runs.
  ForPieces(threads, bands, h, [&](uint32_t, Range rows) {
    for (uint32_t v = rows.begin; v < rows.end; ++v) {
      JoinWrap(up, s, w, v);
      if (v > rows.begin) JoinAbove(up, s, w, v);
    }
  });
  for (uint32_t b = 1; b < bands; ++b) JoinAbove(up, s, w, PieceOf(h, bands, b).begin);
  const Run* __restrict run = s.runs.data();
  for (uint32_t k = 0; k < n; ++k) {
    up[k] = Find(up, k);  // roots come first, so one pass flattens every set
    s.comp_size[up[k]] += run[k].u1 - run[k].u0 + 1;
  }
}

// Whether a component of `size` pixels, `seeds` of them seeds, is removed.
inline bool Removed(const Params& p, uint32_t size, uint32_t seeds) {
  const bool kept = size >= p.comp_seed_min && float(seeds) >= p.comp_seed_share * float(size);
  return size < p.min_component && !kept;
}

// Each run's pixels get their component's label (the start of its root run) in pixel_comp, and
// non-ground in pixel_label when the component is removed (Removed: its size and seed count).
// Pieces of runs count their seeds, added up per component in run order, then write their runs.
void LabelComponents(const Params& p, Frame& f, Scratch& s, Threads threads) {
  uint32_t* __restrict comp = f.pixel_comp.data();
  uint32_t* __restrict label = f.pixel_label.data();
  const uint32_t* __restrict fused = f.pixel_fused.data();
  const uint32_t* __restrict up = s.parent.data();
  const Run* __restrict run = s.runs.data();
  const uint32_t n = uint32_t(s.runs.size());
  const uint32_t pieces = PiecesFor(threads, n, 256);
  s.run_seeds.resize(n);
  ForPieces(threads, pieces, n, [&](uint32_t, Range runs) {
    for (uint32_t k = runs.begin; k < runs.end; ++k) {
      uint32_t seeds = 0;
      for (uint32_t x = run[k].start; x <= run[k].start + (run[k].u1 - run[k].u0); ++x)
        seeds += fused[x] == kPixGround;
      s.run_seeds[k] = seeds;
    }
  });
  s.comp_seeds.assign(n, 0);
  for (uint32_t k = 0; k < n; ++k) s.comp_seeds[up[k]] += s.run_seeds[k];
  ForPieces(threads, pieces, n, [&](uint32_t, Range runs) {
    for (uint32_t k = runs.begin; k < runs.end; ++k) {
      const uint32_t root = up[k], len = run[k].u1 - run[k].u0 + 1;
      std::fill(comp + run[k].start, comp + run[k].start + len, run[root].start);
      if (Removed(p, s.comp_size[root], s.comp_seeds[root]))
        std::fill(label + run[k].start, label + run[k].start + len, kPixNonGround);
    }
  });
}

// The veto's lift over labels after the component test, for the vetoed pixels of rows `rows`:
// each decided on the labels before any lift, into `lifted` or `kept`, written by the caller once
// every pixel has been decided.
void DecideVetoed(const Params& p, const float* __restrict range, const float* __restrict height,
                  const uint32_t* __restrict label, Range rows, std::vector<uint32_t>& lifted,
                  std::vector<uint32_t>& kept) {
  const uint32_t w = p.width;
  lifted.clear();
  kept.clear();
  for (uint32_t v = rows.begin; v < rows.end; ++v) {
    const uint32_t* const row = label + size_t(v) * w;
    // The row's vetoed pixels in order, found by std::find (few pixels are vetoed).
    for (const uint32_t* at = std::find(row, row + w, kPixVetoed); at != row + w;
         at = std::find(at + 1, row + w, kPixVetoed)) {
      const uint32_t u = uint32_t(at - row), x = v * w + u;
      const uint32_t left = u == 0 ? x + w - 1 : x - 1, right = u + 1 == w ? x + 1 - w : x + 1;
      auto joins = [&](uint32_t q) {
        return label[q] == kPixGround &&
               StepAllowed(p, height[q], range[q], height[x], range[x], true);
      };
      bool lift = joins(left) && joins(right);
      if (!lift && v > 0 && label[x - w] == kPixGround) {
        const float r = range[x], d = exact::Ftz0(range[x - w] - r);
        lift = !(d < 0.0f && exact::Ftz0(height[x] * d) >= exact::Ftz0(p.occ_pass * r));
      }
      (lift ? lifted : kept).push_back(x);
    }
  }
}

}  // namespace

void Grow(const Params& p, Frame& f, Threads threads) {
  const uint32_t w = p.width, h = p.beams, pixels = w * h;
  Scratch& s = scratch;
  s.state.resize(pixels);
  uint8_t* state = s.state.data();
  const uint32_t pieces = PiecesFor(threads, pixels, 8192);
  ForPieces(threads, pieces, pixels, [&](uint32_t, Range r) {
    ToState(f.pixel_fused.data() + r.begin, state + r.begin, r.end - r.begin);
  });
  GrowAll(p, f, s, threads);
  FindComponents(w, h, s, threads);
  f.pixel_grown.resize(pixels);
  f.pixel_comp.resize(pixels);
  f.pixel_label.resize(pixels);
  ForPieces(threads, pieces, pixels, [&](uint32_t, Range r) {
    WriteOutputs(f.pixel_fused.data() + r.begin, state + r.begin, r.end - r.begin,
                 f.pixel_grown.data() + r.begin, f.pixel_label.data() + r.begin,
                 f.pixel_comp.data() + r.begin);
  });
  LabelComponents(p, f, s, threads);
  // A vetoed pixel kept is written non-ground (its neighbours read it as not ground either way).
  const uint32_t bands = PiecesFor(threads, h, 8);
  s.lifted.resize(bands), s.kept.resize(bands);
  ForPieces(threads, bands, h, [&](uint32_t b, Range rows) {
    DecideVetoed(p, f.f_range.data(), f.f_height.data(), f.pixel_label.data(), rows, s.lifted[b],
                 s.kept[b]);
  });
  ForPieces(threads, bands, h, [&](uint32_t b, Range) {
    for (uint32_t x : s.lifted[b]) f.pixel_label[x] = kPixGround;
    for (uint32_t x : s.kept[b]) f.pixel_label[x] = kPixNonGround;
  });
}

}  // namespace lpir
