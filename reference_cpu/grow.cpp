// Stage 8, grow (paper Alg. 1 and the ground connectivity constraint of IV-A).
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
// of passes, and what the depth-first search below reaches from the unknown pixels. Unknown
// pixels left over are non-ground. Decision and measurements: docs/decisions/grow.md.
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

// Scratch reused from frame to frame (the reference is single-threaded).
thread_local std::vector<uint8_t> state;
thread_local std::vector<Pixel> stack;
thread_local std::vector<Run> runs;
thread_local std::vector<uint32_t> row_runs;  // beams + 1 offsets into runs
thread_local std::vector<uint32_t> parent, comp_size, comp_seeds, lifted;

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
// width.
class Growing {
 public:
  Growing(const Params& p, const Frame& f, uint8_t* s)
      : p_(p),
        w_(p.width),
        h_(p.beams),
        height_(f.f_height.data()),
        range_(f.f_range.data()),
        fused_(f.pixel_fused.data()),
        s_(s) {}

  // Visits every unknown pixel in scan order (eight at a time where a word holds none).
  void Scan() {
    stack.clear();
    for (uint32_t v = 0; v < h_; ++v) {
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

 private:
  // Tests the unknown pixel (v, u) against its ground neighbours; grows from it if one passes.
  // The scan reads each pixel's state when it reaches it: pixels grown meanwhile are skipped.
  void Visit(uint32_t v, uint32_t u) {
    const uint32_t w = w_, h = h_;
    const uint8_t* s = s_;
    const uint32_t at = v * w, r = at + u;
    const uint32_t ul = u == 0 ? w - 1 : u - 1, ur = u + 1 == w ? 0 : u + 1;
    const bool left = ul != u, right = ur != u;
    const float zr = height_[r], rr = range_[r];
    auto from = [&](uint32_t q, bool moved) {
      if (s[q] != kGround) return false;
      return StepAllowed(p_, height_[q], range_[q], zr, rr, moved);
    };
    bool grows = from(at + ul, left) || from(at + ur, right);
    if (!grows && v > 0) {
      const uint32_t above = at - w;
      grows = from(above + ul, left) || from(above + u, false) || from(above + ur, right) ||
              (s[above + u] == kGround && Climbs(above + u, r));
    }
    if (!grows && v + 1 < h) {
      const uint32_t below = at + w;
      grows = from(below + ul, left) || from(below + u, false) || from(below + ur, right) ||
              (s[below + u] == kGround && Climbs(r, below + u));
    }
    if (grows) {
      s_[r] = kGround;
      stack.push_back({r, v});
      Drain();
    }
  }

  // Grows on from the pixels on the stack until it is empty.
  void Drain() {
    const uint32_t w = w_, h = h_;
    uint8_t* s = s_;
    while (!stack.empty()) {
      const Pixel q = stack.back();
      stack.pop_back();
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
          stack.push_back({r, rv});
        }
      };
      if (v > 0) {
        const uint32_t above = at - w;
        to(above + ul, v - 1, left), to(above + u, v - 1, false, 1), to(above + ur, v - 1, right);
      }
      to(at + ul, v, left), to(at + ur, v, right);
      if (v + 1 < h) {
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
  const uint32_t w_, h_;
  const float* const height_;
  const float* const range_;
  const uint32_t* const fused_;
  uint8_t* const s_;
};

// The runs of ground pixels of every row, row by row (row_runs[v] .. row_runs[v + 1] - 1 are row
// v's), skipping eight pixels at a time where a word is all in or all out of the current run.
void FindRuns(const uint8_t* s, uint32_t w, uint32_t h) {
  runs.clear();
  row_runs.resize(h + 1);
  for (uint32_t v = 0; v < h; ++v) {
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
  row_runs[h] = uint32_t(runs.size());
}

// Joins the runs that touch: on the same row across the wrap, on adjacent rows (8-connected,
// across the wrap too). Leaves every run's root in parent (the component's lowest run) and each
// root's pixel count in comp_size.
void JoinRuns(uint32_t w, uint32_t h) {
  const uint32_t n = uint32_t(runs.size());
  parent.resize(n);
  comp_size.assign(n, 0);
  uint32_t* __restrict up = parent.data();
  for (uint32_t k = 0; k < n; ++k) up[k] = k;
  const Run* __restrict run = runs.data();
  for (uint32_t v = 0; v < h; ++v) {
    const uint32_t b = row_runs[v], e = row_runs[v + 1];
    if (b == e) continue;
    if (run[b].u0 == 0 && run[e - 1].u1 == w - 1) Union(up, b, e - 1);  // the wrap on the row
    if (v == 0) continue;
    const uint32_t pb = row_runs[v - 1], pe = row_runs[v];
    if (pb == pe) continue;
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
  for (uint32_t k = 0; k < n; ++k) {
    up[k] = Find(up, k);  // roots come first, so one pass flattens every set
    comp_size[up[k]] += run[k].u1 - run[k].u0 + 1;
  }
}

// Whether a component of `size` pixels, `seeds` of them seeds, is removed.
inline bool Removed(const Params& p, uint32_t size, uint32_t seeds) {
  const bool kept = size >= p.comp_seed_min && float(seeds) >= p.comp_seed_share * float(size);
  return size < p.min_component && !kept;
}

// Each run's pixels get their component's label (the start of its root run) in pixel_comp, and
// non-ground in pixel_label when the component is removed (Removed: its size and seed count).
void LabelComponents(const Params& p, Frame& f) {
  uint32_t* __restrict comp = f.pixel_comp.data();
  uint32_t* __restrict label = f.pixel_label.data();
  const uint32_t* __restrict fused = f.pixel_fused.data();
  const uint32_t* __restrict up = parent.data();
  const Run* __restrict run = runs.data();
  const uint32_t n = uint32_t(runs.size());
  comp_seeds.assign(n, 0);
  for (uint32_t k = 0; k < n; ++k) {
    uint32_t seeds = 0;
    for (uint32_t x = run[k].start; x <= run[k].start + (run[k].u1 - run[k].u0); ++x)
      seeds += fused[x] == kPixGround;
    comp_seeds[up[k]] += seeds;
  }
  for (uint32_t k = 0; k < n; ++k) {
    const uint32_t root = up[k], len = run[k].u1 - run[k].u0 + 1;
    std::fill(comp + run[k].start, comp + run[k].start + len, run[root].start);
    if (Removed(p, comp_size[root], comp_seeds[root]))
      std::fill(label + run[k].start, label + run[k].start + len, kPixNonGround);
  }
}

// The veto's lift over labels after the component test, every vetoed pixel decided on the labels
// before any lift: one that stays is written non-ground at once (its neighbours read it as not
// ground either way), the lifted ones are collected and written ground after the scan.
void LiftVetoed(const Params& p, const float* __restrict range, const float* __restrict height,
                uint32_t* __restrict label) {
  const uint32_t w = p.width, h = p.beams;
  lifted.clear();
  for (uint32_t v = 0; v < h; ++v) {
    for (uint32_t u = 0; u < w; ++u) {
      const uint32_t x = v * w + u;
      if (label[x] != kPixVetoed) continue;
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
      if (lift)
        lifted.push_back(x);
      else
        label[x] = kPixNonGround;
    }
  }
  for (uint32_t x : lifted) label[x] = kPixGround;
}

}  // namespace

void Grow(const Params& p, Frame& f) {
  const uint32_t w = p.width, h = p.beams, pixels = w * h;
  state.resize(pixels);
  uint8_t* s = state.data();
  ToState(f.pixel_fused.data(), s, pixels);
  Growing(p, f, s).Scan();
  FindRuns(s, w, h);
  JoinRuns(w, h);
  f.pixel_grown.resize(pixels);
  f.pixel_comp.resize(pixels);
  f.pixel_label.resize(pixels);
  WriteOutputs(f.pixel_fused.data(), s, pixels, f.pixel_grown.data(), f.pixel_label.data(),
               f.pixel_comp.data());
  LabelComponents(p, f);
  LiftVetoed(p, f.f_range.data(), f.f_height.data(), f.pixel_label.data());
}

}  // namespace lpir
