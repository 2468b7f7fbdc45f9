// Stage 6, classify pixels (paper eqs. 8-12).
// In: pixel_filled, f_edge_l/r, f_slope, f_varz, f_vari. Out: pixel_class (kPix*).
// f_edge = edge_l >= t_edge || edge_r >= t_edge (eq. 8); f_slope, f_stdz, f_stdi in {-1, 0, 1}
// by their low/high thresholds (eqs. 9-11; an undefined slope, -1, votes 0). Eq. 12 completed as
// SPEC section 2 says, with s = f_slope + f_stdz + f_stdi:
//   edge 0: s < 0 ground, s > 0 non-ground, s = 0 unknown;  edge 1: s > 0 non-ground, else unknown.
// Empty pixels are kPixEmpty. Comparisons only.
#include "reference_cpu/stages.h"

namespace lpir {
namespace {

inline int Vote(float value, float low, float high) {
  if (value <= low) return -1;
  if (value >= high) return 1;
  return 0;
}

}  // namespace

void ClassifyPixels(const Params& p, Frame& f) {
  const uint32_t pixels = p.width * p.beams;
  f.pixel_class.resize(pixels);
  // Raw pointers: the outputs never alias the inputs, so the loop keeps nothing in memory.
  const uint32_t* __restrict filled = f.pixel_filled.data();
  const float* __restrict edge_l = f.f_edge_l.data();
  const float* __restrict edge_r = f.f_edge_r.data();
  const float* __restrict slope_map = f.f_slope.data();
  const float* __restrict varz = f.f_varz.data();
  const float* __restrict vari = f.f_vari.data();
  uint32_t* __restrict out = f.pixel_class.data();
  const Params q = p;  // thresholds in registers
  for (uint32_t pix = 0; pix < pixels; ++pix) {
    const bool edge = (edge_l[pix] >= q.t_edge) | (edge_r[pix] >= q.t_edge);  // eq. 8
    const float slope = slope_map[pix];
    const int s = (slope < 0.0f ? 0 : Vote(slope, q.t_slope_low, q.t_slope_high)) +  // eq. 9
                  Vote(varz[pix], q.t_stdz_low, q.t_stdz_high) +                     // eq. 10
                  Vote(vari[pix], q.t_stdi_low, q.t_stdi_high);                      // eq. 11
    uint32_t c;                                                                      // eq. 12
    if (s > 0)
      c = kPixNonGround;
    else if (!edge && s < 0)
      c = kPixGround;
    else
      c = kPixUnknown;
    out[pix] = filled[pix] ? c : kPixEmpty;
  }
}

}  // namespace lpir
