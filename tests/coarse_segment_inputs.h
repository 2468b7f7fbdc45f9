// coarse_segment's inputs made by hand for the coarse segment tests (tests/coarse_segment_test.cpp
// and tests/coarse_segment_vk_test.cpp): a point's cell as grid_reduce defines it, the prepare,
// project and grid_reduce buffers of a cloud without prepare's tilt and noise, and planes of
// points.
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>

#include "reference_cpu/cloud.h"
#include "reference_cpu/exact.h"
#include "reference_cpu/frame.h"
#include "reference_cpu/params.h"
#include "reference_cpu/stages.h"

namespace lpir::test {

// The cell of a planar position as grid_reduce defines it (eq. 4 rings, sector from the column).
inline uint32_t CellOf(const Params& p, const Tables& t, float x, float y) {
  const uint32_t rings = p.rings_near + p.rings_far;
  const uint32_t ring = RingOf(x * x + y * y, t.ring_bound2.data(), rings);
  if (ring >= rings) return kNone;
  const uint32_t u = ColumnOf(x, y, t.column_dir.data(), p.width);
  return ring < p.rings_near
             ? ring * p.sectors_near + u / (p.width / p.sectors_near)
             : p.rings_near * p.sectors_near + (ring - p.rings_near) * p.sectors_far +
                   u / (p.width / p.sectors_far);
}

// coarse_segment's inputs by hand: every point valid, z_t = z (no tilt), r^2, its cell, and per
// cell the ordered keys of min / max z_t and the count.
inline Frame CoarseInputs(const Cloud& c, const Params& p, const Tables& t) {
  Frame f;
  f.n = uint32_t(c.size());
  f.flags.assign(f.n, kPointValid);
  f.zt.resize(f.n);
  f.r2.resize(f.n);
  f.point_cell.resize(f.n);
  const uint32_t cells = CellCount(p);
  f.cell_zmin.assign(cells, kNone);
  f.cell_zmax.assign(cells, 0u);
  f.cell_count.assign(cells, 0u);
  for (uint32_t i = 0; i < f.n; ++i) {
    f.zt[i] = c.z(i);
    f.r2[i] = c.x(i) * c.x(i) + c.y(i) * c.y(i);
    const uint32_t cell = CellOf(p, t, c.x(i), c.y(i));
    f.point_cell[i] = cell;
    if (cell == kNone) continue;
    f.cell_zmin[cell] = std::min(f.cell_zmin[cell], exact::Key(f.zt[i]));
    f.cell_zmax[cell] = std::max(f.cell_zmax[cell], exact::Key(f.zt[i]));
    f.cell_count[cell] += 1;
  }
  return f;
}

// A grid of points on z = z0 + gx * x + gy * y (+ uniform noise of +- amp) over x0..x1, y0..y1.
inline void AddPlane(Cloud* c, float x0, float x1, float y0, float y1, float step, float z0,
                     float gx, float gy, float amp, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> noise(-amp, amp);
  for (float x = x0; x <= x1; x += step)
    for (float y = y0; y <= y1; y += step)
      c->Push(x, y, z0 + gx * x + gy * y + (amp > 0 ? noise(rng) : 0.0f), 0.3f);
}

// A height near `base` from which `delta` above is exactly `delta` in float: (h + delta) - h ==
// delta, so a point there lies exactly on a threshold of eq. 5.
inline float ExactBase(float base, float delta) {
  float h = base;
  for (int k = 0; k < 100000; ++k, h = std::nextafter(h, -1e9f))
    if ((h + delta) - h == delta) return h;
  return base;
}

// Points exactly on the thresholds of eq. 5, in cells too far apart to be neighbours, with *p's
// thresholds set on a coarse binary grid so that heights near the road reach them exactly:
// h_max - h_nmin == h_athr (points 0-59 around x = 5 m: a whole cell), z_t - h_min == lambda
// (points 60-119 around x = -5 m: the lower two thirds are seeds), and h_min - h_nmin == lambda
// + rise_margin (the rest: ring 3, 8-10 m, raised exactly to the limit above rings 2 and 4).
inline Cloud SeedThresholdCloud(Params* p) {
  p->h_athr = 0.125f;
  p->seed_margin = 0.25f;
  p->slope_max = 0.0625f;
  p->rise_margin = 0.25f;
  const float road = -p->sensor_height;
  const float lambda = p->ring_res_near * p->slope_max + p->seed_margin;
  const float rise = lambda + p->rise_margin;
  Cloud c;
  const float a = ExactBase(road, p->h_athr);
  for (int k = 0; k < 20; ++k) {
    c.Push(5.0f + 0.05f * k, 0.1f + 0.01f * (k % 5), a, 0.3f);
    c.Push(5.02f + 0.05f * k, 0.12f + 0.01f * (k % 3), a + p->h_athr, 0.3f);
    c.Push(5.03f + 0.05f * k, 0.14f, a + 0.5f * p->h_athr, 0.3f);
  }
  const float b = ExactBase(road, lambda);
  for (int k = 0; k < 20; ++k) {
    c.Push(-5.0f - 0.05f * k, 0.1f + 0.01f * (k % 5), b, 0.3f);
    c.Push(-5.02f - 0.05f * k, 0.12f + 0.01f * (k % 3), b + lambda, 0.3f);
    c.Push(-5.03f - 0.05f * k, 0.14f, b + lambda + p->h_athr + 0.2f, 0.3f);
  }
  const float d = ExactBase(road, rise);
  for (float x = 4.1f; x <= 9.9f; x += 0.1f)
    for (float y = 5.0f; y <= 5.6f; y += 0.1f) {
      const float r = std::hypot(x, y);
      c.Push(x, y, r >= 8.0f && r < 10.0f ? d + rise : d, 0.3f);
    }
  return c;
}

}  // namespace lpir::test
