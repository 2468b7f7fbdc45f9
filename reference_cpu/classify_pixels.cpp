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
  f.pixel_class.assign(pixels, kPixEmpty);
  for (uint32_t pix = 0; pix < pixels; ++pix) {
    if (!f.pixel_filled[pix]) continue;
    const bool edge = f.f_edge_l[pix] >= p.t_edge || f.f_edge_r[pix] >= p.t_edge;  // eq. 8
    const float slope = f.f_slope[pix];
    const int s = (slope < 0.0f ? 0 : Vote(slope, p.t_slope_low, p.t_slope_high)) +  // eq. 9
                  Vote(f.f_varz[pix], p.t_stdz_low, p.t_stdz_high) +                 // eq. 10
                  Vote(f.f_vari[pix], p.t_stdi_low, p.t_stdi_high);                  // eq. 11
    uint32_t c;  // eq. 12
    if (s > 0) c = kPixNonGround;
    else if (!edge && s < 0) c = kPixGround;
    else c = kPixUnknown;
    f.pixel_class[pix] = c;
  }
}

}  // namespace lpir
