// fuse (paper III-D.2, first step of the fine segmentation).
// In: pixel_class, pixel_point, coarse, pixel_filled, f_range, f_height. Out: pixel_fused.
// Where the coarse label of the pixel's winning point and the pixel class disagree (ground vs
// non-ground), the pixel becomes unknown. Where the pixel class is unknown (an edge, or no vote),
// the coarse label decides ground ("the ground-classified points from
// both the rough and the regional segmentation are seeds"); a coarse non-ground there stays unknown
// for growing. A hole-filled pixel has no point, hence no coarse opinion: it is unknown (it may
// still be grown through). A bank (kPixBank, a smooth slope the class calls non-ground) is
// non-ground as a class, but unknown where the coarse label is non-ground too: terrain rising
// beyond what the coarse planes allow, which growing may climb (our addition, docs/decisions/
// grow.md, Banks). An unknown pixel whose coarse label is not ground (non-ground, or no point) is
// kPixUnknownOff, the others kPixUnknown. Comparisons only.
// Occlusion veto (our addition): a pixel with an occluder among the occ_rows pixels above it in its
// column (nearer than its range + occ_margin and higher by more than occ_rise) is vetoed
// (kPixVetoed) where the rule below would make it ground or unknown: it is the foot of an object
// or lies under an overhang (a hedge, a car body), and never grows; grow lifts it to ground only
// where the ground goes on around it (reference_cpu/grow.cpp). The reach is
// range + occ_margin + occ_grade * range^2 (flat ground's step between beams grows with range^2),
// and at most range + occ_front for a pixel whose own class is ground: an object standing farther
// behind a flat, smooth pixel leaves it ground (it lies in front of the object, not on its face).
// Nor does a pixel of class ground count an occluder nearer than itself whose range its ray passed
// with at least occ_pass of clearance above the pixel's height (the ray from the sensor through
// the pixel is z * range above / r high there, flat ground z): it is ground seen under or past the
// object (a crown, a raised body, a fence's mesh), not the object's foot, which the ray meets
// lower than a car body's underside.
// Why: the false ground left is a band 1-3 rows thick at the foot of vegetation, fences and walls,
// on the continuation of the ground plane; the beam above it hits the object nearer or at about
// the same range, which flat open ground never does. occ_rows 2 by default; unknown pixels take
// the coarse label (docs/decisions/fuse.md).
// A step in the ground is not an occluder (our addition): an occluded pixel is spared when, over
// the rows v - k, k = 1 .. min(occ_step_rows, v), of its column, no filled pixel nearer than
// range + occ_step_reach rises above z + occ_step + occ_step_grade * max(its range - range, 0)
// (not steep), and one of them is of class ground and farther than the pixel (a landing): the
// column climbs a curb or a bank onto ground that goes on, where a wall, a hedge or a car keeps
// rising.
#include <algorithm>

#include "reference_cpu/exact.h"
#include "reference_cpu/stages.h"

namespace lpir {
namespace {

// The coarse opinion of a pixel without a point (a hole-filled one): unknown, which Decide turns
// into unknown whatever the class.
constexpr uint32_t kNoOpinion = kPixUnknown;

// Columns handled at a time.
constexpr uint32_t kPiece = 256;

// The occluder bounds of one row's pixels: reach = (r + occ_margin) + occ_grade * r^2, for a
// pixel of class ground min(that, r + occ_front), and top = Ftz0(z + occ_rise) (computed for every
// pixel, used where the pixel is not empty).
void Bounds(const Params& p, const float* __restrict range, const float* __restrict height,
            const uint32_t* __restrict cls, uint32_t w, float* __restrict reach,
            float* __restrict top) {
  const float margin = p.occ_margin, rise = p.occ_rise, occ_grade = p.occ_grade;
  const float front = p.occ_front;
  for (uint32_t u = 0; u < w; ++u) {
    const float r = range[u];
    const float rr = r * r;
    const float grade = occ_grade * rr;
    const float near = r + margin;
    const float any = near + grade;
    const float ground = std::min(any, r + front);
    reach[u] = cls[u] == kPixGround ? ground : any;
    top[u] = exact::Ftz0(height[u] + rise);  // a device may flush a subnormal sum
  }
}

// Marks the pixels of a row that the row above_* would occlude before the pass rule (filled
// there, nearer than the reach, higher than the top); the three tests have no side effects, so
// they are evaluated together. The first row above sets the marks, the next ones add to them.
void Occlude(const uint32_t* __restrict above_filled, const float* __restrict above_range,
             const float* __restrict above_height, const float* __restrict reach,
             const float* __restrict top, uint32_t w, bool first, uint32_t* __restrict occluded) {
  for (uint32_t u = 0; u < w; ++u) {
    const uint32_t occluder = uint32_t(above_filled[u] != 0) & uint32_t(above_range[u] < reach[u]) &
                              uint32_t(above_height[u] > top[u]);
    occluded[u] = first ? occluder : occluded[u] | occluder;
  }
}

// Whether the marked pixel i of class ground (range r, height z, bounds reach and top) keeps an
// occluder under the pass rule: one of the rows i - k w, k = 1 .. rows, that Occlude counts and
// that its ray did not pass under, i.e. not (d = Ftz0(range above - r) < 0 and Ftz0(z * d) >=
// Ftz0(occ_pass * r)); z * d / r is the ray's clearance at the range above, the pixel's height
// taken for the ground's there. Only marked pixels of class ground ask (the feet of objects and
// the ground seen past them: a minority), so the test runs per pixel.
bool KeepsOccluder(const Params& p, const uint32_t* __restrict filled,
                   const float* __restrict range, const float* __restrict height, uint32_t i,
                   uint32_t w, uint32_t rows, float reach, float top) {
  const float r = range[i], z = height[i];
  const float pass = exact::Ftz0(p.occ_pass * r);
  for (uint32_t k = 1; k <= rows; ++k) {
    const uint32_t a = i - k * w;
    if (!filled[a] || !(range[a] < reach) || !(height[a] > top)) continue;
    const float d = exact::Ftz0(range[a] - r);
    if (!(d < 0.0f && exact::Ftz0(z * d) >= pass)) return true;
  }
  return false;
}

// Whether the occluded pixel i (row v, range r, height z) is spared as a step: over the rows
// above, i - k w for k = 1 .. rows, a pixel counts when it is filled and nearer than far =
// Ftz0(r + occ_step_reach); it is steep when higher than Ftz0(base + Ftz0(occ_step_grade *
// max(d, 0))), base = Ftz0(z + occ_step) and d = Ftz0(its range - r), and a landing when of class
// ground with d > 0. Spared: a landing and nothing steep. Only occluded pixels ask (a minority:
// the feet of objects), so the test runs per pixel.
bool SparedStep(const Params& p, const uint32_t* __restrict filled, const uint32_t* __restrict cls,
                const float* __restrict range, const float* __restrict height, uint32_t i,
                uint32_t w, uint32_t rows) {
  const float r = range[i];
  const float far = exact::Ftz0(r + p.occ_step_reach);
  const float base = exact::Ftz0(height[i] + p.occ_step);
  const float grade = p.occ_step_grade;
  bool landing = false;
  for (uint32_t k = 1; k <= rows; ++k) {  // the first steep pixel decides: not spared
    const uint32_t a = i - k * w;
    if (!filled[a] || !(range[a] < far)) continue;
    const float d = exact::Ftz0(range[a] - r);
    const float beyond = d > 0.0f ? d : 0.0f;
    if (height[a] > exact::Ftz0(base + exact::Ftz0(grade * beyond))) return false;
    landing = landing || (cls[a] == kPixGround && d > 0.0f);
  }
  return landing;
}

// The coarse label of each pixel's winning point, kNoOpinion where the pixel has none.
void Opinions(const uint32_t* __restrict point, const uint32_t* __restrict coarse, uint32_t w,
              uint32_t* __restrict opinion) {
  static_assert(kPixNonGround == 0 && kPixGround == 1, "the opinion is the coarse bit");
  for (uint32_t u = 0; u < w; ++u) {  // without branches: coarse[0] stands in for no point
    const uint32_t i = point[u], has = uint32_t(i != kNone);
    const uint32_t ground = uint32_t(coarse[i & (0u - has)] != 0);
    opinion[u] = (ground & has) | (has ^ 1u) * kNoOpinion;
  }
}

// The rule of the contract for one row, given each pixel's occlusion mark and coarse opinion
// (kPixGround, kPixNonGround or kNoOpinion); selects only, so that the loop vectorises. Where the
// class is unknown the vote is the opinion when ground; elsewhere it is the class when the
// opinion agrees (a bank agrees with no opinion); else unknown (always so without an opinion):
// kPixUnknown when the opinion is ground, else kPixUnknownOff. An occluded pixel whose vote is
// ground or unknown is kPixVetoed; one whose vote is non-ground stays non-ground.
void Decide(const uint32_t* __restrict cls, const uint32_t* __restrict occluded,
            const uint32_t* __restrict opinion, uint32_t w, uint32_t* __restrict fused) {
  for (uint32_t u = 0; u < w; ++u) {
    const uint32_t c = cls[u], o = opinion[u];
    const uint32_t agree =
        uint32_t(c == o) | (uint32_t(c == kPixUnknown) & uint32_t(o == kPixGround));
    const uint32_t unknown = o == kPixGround ? kPixUnknown : kPixUnknownOff;
    const uint32_t vote = agree & uint32_t(o != kNoOpinion) ? o : unknown;
    const uint32_t vetoed = vote == kPixNonGround ? kPixNonGround : kPixVetoed;
    const uint32_t kept = occluded[u] ? vetoed : vote;
    fused[u] = c == kPixEmpty ? kPixEmpty : kept;
  }
}

}  // namespace

namespace {

// Rows `rows` of pixel_fused; each row reads only the stage's inputs, its own and those of the rows
// above it.
void FuseRows(const Params& p, Frame& f, Range rows) {
  const uint32_t w = p.width;
  const uint32_t* __restrict cls = f.pixel_class.data();
  const uint32_t* __restrict point = f.pixel_point.data();
  static const uint32_t kNoPoints[1] = {0};  // read in place of coarse[0] when there are no points
  const uint32_t* __restrict coarse = f.coarse.empty() ? kNoPoints : f.coarse.data();
  const uint32_t* __restrict filled = f.pixel_filled.data();
  const float* __restrict range = f.f_range.data();
  const float* __restrict height = f.f_height.data();
  uint32_t* __restrict fused = f.pixel_fused.data();
  // Pieces of rows, so that the scratch stays in the L1 cache.
  float reach[kPiece], top[kPiece];
  uint32_t occluded[kPiece], opinion[kPiece], asks[kPiece];
  for (uint32_t v = rows.begin; v < rows.end; ++v) {
    // The occlusion veto looks at rows v - k for k = 1 .. min(occ_rows, v).
    const uint32_t rows_above = p.occ_rows < v ? p.occ_rows : v;
    const uint32_t step_rows = p.occ_step_rows < v ? p.occ_step_rows : v;
    for (uint32_t u0 = 0; u0 < w; u0 += kPiece) {
      const uint32_t n = w - u0 < kPiece ? w - u0 : kPiece, at = v * w + u0;
      Opinions(point + at, coarse, n, opinion);
      if (rows_above) {
        Bounds(p, range + at, height + at, cls + at, n, reach, top);
        for (uint32_t k = 1; k <= rows_above; ++k) {
          const uint32_t above = at - k * w;
          Occlude(filled + above, range + above, height + above, reach, top, n, k == 1, occluded);
        }
        // The marked pixels whose mark can change what Decide writes: not empty, and the vote not
        // non-ground (the vote is non-ground exactly where class and opinion both are); the
        // others' marks stay, unread. Listed without a branch, then in turn: a pixel of class
        // ground keeps its mark only with an occluder its ray did not pass under (KeepsOccluder);
        // then a mark is lifted on a step (SparedStep).
        uint32_t count = 0;
        for (uint32_t u = 0; u < n; ++u) {
          const uint32_t c = cls[at + u];
          const uint32_t vote_non_ground =
              uint32_t(c == kPixNonGround) & uint32_t(opinion[u] == kPixNonGround);
          asks[count] = u;
          count += occluded[u] & uint32_t(c != kPixEmpty) & (vote_non_ground ^ 1u);
        }
        for (uint32_t j = 0; j < count; ++j) {
          const uint32_t u = asks[j];
          if (cls[at + u] == kPixGround &&
              !KeepsOccluder(p, filled, range, height, at + u, w, rows_above, reach[u], top[u])) {
            occluded[u] = 0;
            continue;
          }
          if (step_rows && SparedStep(p, filled, cls, range, height, at + u, w, step_rows))
            occluded[u] = 0;
        }
      } else {
        for (uint32_t u = 0; u < n; ++u) occluded[u] = 0;
      }
      Decide(cls + at, occluded, opinion, n, fused + at);
    }
  }
}

}  // namespace

void Fuse(const Params& p, Frame& f, Threads threads) {
  const uint32_t h = p.beams;
  f.pixel_fused.resize(size_t(p.width) * h);
  ForPieces(threads, PiecesFor(threads, h, 4), h,
            [&](uint32_t, Range rows) { FuseRows(p, f, rows); });
}

}  // namespace lpir
