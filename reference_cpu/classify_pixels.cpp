// classify_pixels (paper eqs. 8-12).
// In: pixel_filled, f_edge_l/r, f_slope, f_varz. Out: pixel_class (kPix*).
// f_edge = edge_l >= t_edge || edge_r >= t_edge (eq. 8); f_slope, f_stdz in {-1, 0, 1} by their
// low/high thresholds (eqs. 9-10; an undefined slope, -1, votes 0). Eq. 11's intensity vote is
// taken as -1, uniform intensity: it was -1 on nearly every pixel of every labelled scan and bought
// 0.01 F1 points, while its thresholds tied the result to the intensity's unit
// (docs/decisions/intensity.md). Eq. 12 completed as docs/spec.md, Readings of the paper says, with
// s = f_slope + f_stdz - 1:
//   edge 0: s < 0 ground, s > 0 non-ground, s = 0 unknown;  edge 1: s > 0 non-ground, else unknown.
// A non-ground pixel is a bank (kPixBank, our addition) when f_slope < bank_slope and f_varz <
// bank_rough: a smooth surface rising at up to ~39 degrees (a grassed embankment) that eq. 9's
// slope vote calls an object; fuse decides it with the coarse label (docs/decisions/grow.md,
// Banks). Empty pixels are kPixEmpty. Comparisons only.
#include "reference_cpu/stages.h"

namespace lpir {
namespace {

// Eq. 11's vote for every pixel: uniform intensity.
constexpr int kIntensityVote = -1;

// -1 at or below low, else 1 at or above high, else 0 (a NaN votes 0). Without branches, as are
// the selects below: the loop over the pixels has no data-dependent jump.
inline int32_t Vote(float value, float low, float high) {
  const int32_t below = value <= low, above = value >= high;
  return (above & (below ^ 1)) - below;
}

// c ? a : b, by a mask.
inline uint32_t Pick(bool c, uint32_t a, uint32_t b) {
  const uint32_t mask = 0u - uint32_t(c);
  return (a & mask) | (b & ~mask);
}

// Pixels [r.begin, r.end).
void ClassifyRange(const Params& p, Frame& f, Range r) {
  // Raw pointers: the outputs never alias the inputs, so the loop keeps nothing in memory.
  const uint32_t* __restrict filled = f.pixel_filled.data();
  const float* __restrict edge_l = f.f_edge_l.data();
  const float* __restrict edge_r = f.f_edge_r.data();
  const float* __restrict slope_map = f.f_slope.data();
  const float* __restrict varz = f.f_varz.data();
  uint32_t* __restrict out = f.pixel_class.data();
  const Params q = p;  // thresholds in registers
  for (uint32_t pix = r.begin; pix < r.end; ++pix) {
    const bool edge = (edge_l[pix] >= q.t_edge) | (edge_r[pix] >= q.t_edge);  // eq. 8
    const float slope = slope_map[pix], z = varz[pix];
    // Eq. 9 (an undefined slope, -1, votes 0), eq. 10, eq. 11.
    const int32_t f_slope = Vote(slope, q.t_slope_low, q.t_slope_high) * int32_t(!(slope < 0.0f));
    const int32_t s = f_slope + Vote(z, q.t_stdz_low, q.t_stdz_high) + kIntensityVote;
    // Eq. 12: s > 0 non-ground (a bank where smooth), s < 0 off an edge ground, else unknown.
    const bool bank = (slope < q.bank_slope) & (z < q.bank_rough);
    const uint32_t objects = Pick(bank, kPixBank, kPixNonGround);
    const uint32_t c = Pick(s > 0, objects, Pick(!edge & (s < 0), kPixGround, kPixUnknown));
    out[pix] = Pick(filled[pix] != 0u, c, kPixEmpty);
  }
}

}  // namespace

void ClassifyPixels(const Params& p, Frame& f, Threads threads) {
  const uint32_t pixels = p.width * p.beams;
  f.pixel_class.resize(pixels);
  ForPieces(threads, PiecesFor(threads, pixels, 8192), pixels,
            [&](uint32_t, Range r) { ClassifyRange(p, f, r); });
}

}  // namespace lpir
