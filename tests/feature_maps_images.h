// Hand-made images for the feature maps tests (tests/feature_maps_test.cpp checks the reference
// on them, tests/feature_maps_vk_test.cpp the kernel's bytes against the reference's): random
// winners and holes, holes at the column wrap, equal ranges down a column, and holes whose
// neighbours' ranges differ by exactly hole_gap or a few ulps of r2 either side.
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <random>
#include <vector>

#include "reference_cpu/exact.h"
#include "reference_cpu/frame.h"
#include "reference_cpu/params.h"

namespace lpir::test {

// A hand-made image of `p.width` x `p.beams` pixels: one point per measured pixel (numbered in a
// shuffled order), empty pixels with probability `empty`.
struct HandOptions {
  float empty = 0.3f;
  float base_range = 10.0f;   // ranges base_range + small steps, so that holes get filled
  float range_step = 0.02f;   // per column
  float height_scale = 1.0f;  // heights in +-height_scale
  bool equal_down = false;    // a pixel's range equals the one below (undefined slope)
  bool wrap_holes = true;     // holes at columns 0 and width - 1 with measured neighbours
};

inline Frame HandMadeImage(const Params& p, uint32_t seed, const HandOptions& o) {
  const uint32_t w = p.width, h = p.beams, pixels = w * h;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  Frame f;
  f.pixel_point.assign(pixels, kNone);
  std::vector<uint8_t> is_measured(pixels, 0);
  for (uint32_t pix = 0; pix < pixels; ++pix) is_measured[pix] = unit(rng) >= o.empty;
  // Wrap holes: column 0 empty with columns w-1 and 1 measured on even rows, column w-1 empty
  // with columns w-2 and 0 measured on odd rows.
  if (o.wrap_holes && w >= 3) {
    for (uint32_t v = 0; v < h; ++v) {
      const uint32_t row = v * w;
      if (v % 2 == 0) {
        is_measured[row] = 0, is_measured[row + w - 1] = 1, is_measured[row + 1] = 1;
      } else {
        is_measured[row + w - 1] = 0, is_measured[row + w - 2] = 1, is_measured[row] = 1;
      }
    }
  }
  std::vector<uint32_t> measured;
  for (uint32_t pix = 0; pix < pixels; ++pix)
    if (is_measured[pix]) measured.push_back(pix);
  // Points in a shuffled order (the winner's index carries no meaning here), one extra point that
  // no pixel names.
  std::vector<uint32_t> order(measured.size());
  std::iota(order.begin(), order.end(), 0u);
  std::shuffle(order.begin(), order.end(), rng);
  f.n = uint32_t(measured.size() + 1);
  f.r2.assign(f.n, 25.0f);
  f.zt.assign(f.n, 7.0f);
  for (size_t k = 0; k < measured.size(); ++k) {
    const uint32_t pix = measured[k], i = order[k];
    const uint32_t v = pix / w, u = pix % w;
    f.pixel_point[pix] = i;
    float r = o.base_range + o.range_step * float(u % 7) + 0.5f * float(v) + 0.01f * unit(rng);
    if (o.equal_down) r = o.base_range + o.range_step * float(u);  // same down every column
    f.r2[i] = r * r;
    f.zt[i] = o.height_scale * (2.0f * unit(rng) - 1.0f);
    if (rng() % 16 == 0) f.zt[i] = (rng() % 2 ? 1.0f : -1.0f) * o.height_scale;  // extremes
    if (rng() % 32 == 0) f.zt[i] = 0.0f;
  }
  return f;
}

inline Params SmallImage(uint32_t width, uint32_t beams) {
  Params p = DefaultParams();
  p.width = width;
  p.beams = beams;
  return p;
}

// A 1024 x 16 image with holes at every fourth column (u = 1, 5, ...) between measured
// neighbours, the right one's r2 placed so that the ranges (Sqrt(r2)) differ by hole_gap, give
// or take up to 3 ulps of r2. *holes gets those holes' pixels.
inline Frame HoleGapImage(const Params& p, std::vector<uint32_t>* holes) {
  HandOptions o;
  o.empty = 0.0f;  // only the holes punched here (and the wrap holes)
  Frame f = HandMadeImage(p, 2, o);
  for (uint32_t v = 0; v < p.beams; ++v)
    for (uint32_t u = 1; u + 1 < p.width; u += 4) f.pixel_point[v * p.width + u] = kNone;
  std::mt19937 rng(5);
  for (uint32_t v = 0; v < p.beams; ++v)
    for (uint32_t u = 1; u + 1 < p.width; u += 4) {
      const uint32_t pix = v * p.width + u;
      const uint32_t il = f.pixel_point[pix - 1], ir = f.pixel_point[pix + 1];
      if (il == kNone || ir == kNone) continue;
      holes->push_back(pix);
      const float target = exact::Sqrt(f.r2[il]) + p.hole_gap;
      float r2 = target * target;
      const int nudge = int(rng() % 7) - 3;
      for (int k = 0; k < nudge; ++k) r2 = std::nextafter(r2, 1e30f);
      for (int k = 0; k > nudge; --k) r2 = std::nextafter(r2, 0.0f);
      f.r2[ir] = r2;
    }
  return f;
}

}  // namespace lpir::test
