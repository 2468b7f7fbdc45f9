// Stage 7, fuse (paper III-D.2, first step of the fine segmentation).
// In: pixel_class, pixel_point, coarse. Out: pixel_fused.
// Where the coarse label of the pixel's winning point and the pixel class disagree (ground vs
// non-ground), the pixel becomes unknown. Where the pixel class is unknown (an edge, or no vote),
// the coarse label decides ground ("the ground-classified points from both the rough and the
// regional segmentation are seeds"); a coarse non-ground there stays unknown for growing. A hole-filled pixel has no point, hence no coarse
// opinion: it is unknown (it may still be grown through). Comparisons only.
#include "reference_cpu/stages.h"

namespace lpir {

void Fuse(const Params& p, Frame& f) {
  const uint32_t pixels = p.width * p.beams;
  f.pixel_fused.assign(pixels, kPixEmpty);
  for (uint32_t pix = 0; pix < pixels; ++pix) {
    const uint32_t c = f.pixel_class[pix];
    if (c == kPixEmpty) continue;
    const uint32_t i = f.pixel_point[pix];
    if (i == kNone) {
      f.pixel_fused[pix] = kPixUnknown;
      continue;
    }
    const uint32_t coarse = f.coarse[i] ? kPixGround : kPixNonGround;
    if (c == kPixUnknown) {
      f.pixel_fused[pix] = coarse == kPixGround ? kPixGround : kPixUnknown;
    } else {
      f.pixel_fused[pix] = c == coarse ? c : kPixUnknown;
    }
  }
}

}  // namespace lpir
