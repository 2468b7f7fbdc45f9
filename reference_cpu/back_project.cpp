// back_project (paper III-D.2, last step).
// In: flags, point_pixel, pixel_point, pixel_label, f_range, f_height, r2, zt, coarse.
// Out per point: label (1 ground, 0 non-ground), why (kWhy*), label_why (both in one byte,
// PackLabelWhy).
// Invalid and noise points are non-ground. The point that won its pixel takes the pixel's label; a
// point that lost it takes the pixel's label when it lies within bp_range_gate (planar range,
// Sqrt) and bp_height_gate (z_t) of the winner; otherwise it is ground only when both its own
// coarse label and the pixel's label say so (a lost point alone would leak coarse errors; the
// paper reads "otherwise its coarse label": docs/decisions/back_project.md).
#include <cmath>

#include "reference_cpu/exact.h"
#include "reference_cpu/stages.h"

namespace lpir {

namespace {

// Points [r.begin, r.end).
void BackProjectRange(const Params& p, Frame& f, Range r) {
  const uint32_t* __restrict flags = f.flags.data();
  const uint32_t* __restrict point_pixel = f.point_pixel.data();
  const uint32_t* __restrict pixel_point = f.pixel_point.data();
  const uint32_t* __restrict pixel_label = f.pixel_label.data();
  const float* __restrict f_range = f.f_range.data();
  const float* __restrict f_height = f.f_height.data();
  const float* __restrict r2 = f.r2.data();
  const float* __restrict zt = f.zt.data();
  const uint32_t* __restrict coarse = f.coarse.data();
  uint8_t* __restrict label = f.label.data();
  uint8_t* __restrict why = f.why.data();
  uint8_t* __restrict label_why = f.label_why.data();
  const float range_gate = p.bp_range_gate, height_gate = p.bp_height_gate;
  for (uint32_t i = r.begin; i < r.end; ++i) {
    const uint32_t flag = flags[i];
    if ((flag & (kPointValid | kPointNoise)) != kPointValid) {  // invalid, or noise
      label[i] = 0;
      why[i] = (flag & kPointValid) ? kWhyNoise : kWhyInvalid;
      label_why[i] = PackLabelWhy(0, why[i]);
      continue;
    }
    const uint32_t pix = point_pixel[i];
    // Winner: the pixel's label. Lost: the pixel's label when within the gates, else the pixel's
    // and its own coarse label together; both ways ground needs a ground pixel, so the gates
    // (and their Sqrt) are only evaluated for a lost non-coarse-ground point on a ground pixel.
    bool ground = pixel_label[pix] == kPixGround;
    if (ground && pixel_point[pix] != i && coarse[i] == 0) {
      const float dr = std::fabs(exact::Sqrt(r2[i]) - f_range[pix]);
      const float dz = exact::Ftz0(std::fabs(zt[i] - f_height[pix]));  // a device may flush
      ground = dr <= range_gate && dz <= height_gate;
    }
    label[i] = ground ? 1 : 0;
    why[i] = ground ? kWhyGround : kWhyNonGround;
    label_why[i] = PackLabelWhy(label[i], why[i]);
  }
}

}  // namespace

void BackProject(const Params& p, Frame& f, Threads threads) {
  const uint32_t n = f.n;
  f.label.resize(n);
  f.why.resize(n);
  f.label_why.resize(n);
  ForPieces(threads, PiecesFor(threads, n, 8192), n,
            [&](uint32_t, Range r) { BackProjectRange(p, f, r); });
}

}  // namespace lpir
