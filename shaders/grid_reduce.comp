// grid_reduce (paper eq. 4, V-C.1): the GPU twin of reference_cpu/grid_reduce.cpp, same
// bytes. Two passes of this one shader, chosen by the specialization constant kPass, with a
// compute -> compute barrier between them (GridReduceStage::Record records both):
//   pass 0, one invocation per cell c < count: cell_zmin = kNone, cell_zmax = 0, cell_count = 0.
//   pass 1, one invocation per kItems consecutive points (of count; the device's shape,
//     specialization constant 2: host/vk/shape.h): point_cell and the per-cell reductions (runs
//     of one cell reduced in registers, then one set of atomics per run; with kItems = 1 a set
//     per point). The atomics are order-independent, so the bytes do not depend on kItems.
// In: binding 0 Params (uniform), 1 flags, 2 r2, 3 zt, 4 point_pixel (per point), 5 ring_bound2
//     (rings_near + rings_far floats, ascending: the host's table, the reference's bytes).
// Out: 6 point_cell (per point), 7 cell_zmin, 8 cell_zmax (ordered keys of z_t), 9 cell_count.
// Only flags == kPointValid (valid, not noise) gets a cell. Ring: the first index whose
// ring_bound2 exceeds r2 (binary search; the CPU's hint is a shortcut to the same unique answer),
// none when r2 is beyond the last ring. Sector: u = point_pixel % width, u / (width / sectors) of
// the ring's zone (integer % and / are exact on unsigned operands). Cell: near rings x near
// sectors, then far rings x far sectors. Reductions: atomicMin / atomicMax of exact_Key(zt) and
// atomicAdd of 1, order-independent. No float arithmetic: the ring comparison is done on ordered
// keys, so it does not depend on how the device treats subnormals.
#version 450
#extension GL_GOOGLE_include_directive : require

#include "common/params.h"
#include "common/frame_codes.h"
#include "common/exact.glsl"
#include "common/compare.glsl"

layout(local_size_x_id = 0) in;

layout(std140, set = 0, binding = 0) uniform ParamsBlock { Params p; };
layout(std430, set = 0, binding = 1) readonly buffer Flags { uint flags[]; };
layout(std430, set = 0, binding = 2) readonly buffer R2 { float r2[]; };
layout(std430, set = 0, binding = 3) readonly buffer Zt { float zt[]; };
layout(std430, set = 0, binding = 4) readonly buffer PointPixel { uint point_pixel[]; };
layout(std430, set = 0, binding = 5) readonly buffer RingBound2 { float ring_bound2[]; };
layout(std430, set = 0, binding = 6) writeonly buffer PointCell { uint point_cell[]; };
layout(std430, set = 0, binding = 7) buffer CellZmin { uint cell_zmin[]; };
layout(std430, set = 0, binding = 8) buffer CellZmax { uint cell_zmax[]; };
layout(std430, set = 0, binding = 9) buffer CellCount { uint cell_count[]; };

layout(constant_id = 1) const uint kPass = 0u;  // a pipeline per pass (host/vk/kernel.h)
layout(constant_id = 2) const uint kItems = 1u;  // points per invocation of pass 1 (the shape)

layout(push_constant) uniform Push {
  uint count;  // cells (pass 0) or points (pass 1)
} pc;


// reference_cpu RingOf: the first index with r2 < bound2[index], rings when none.
// The reference searches by halves; here a guess from the rings' widths (ring_res_near over
// rings_near rings, then ring_res_far: how reference_cpu/params.cpp lays out ring_bound2) walks to
// the same index, as Less(r, ring_bound2[k]) only turns from false to true once along k: two
// tests where the search by halves takes six (docs/decisions/grid_reduce.md).
uint RingOf(float r2, uint rings) {
  float r = sqrt(max(r2, 0.0)), near = p.ring_res_near * float(p.rings_near);
  float guess = r < near ? r / p.ring_res_near : float(p.rings_near) + (r - near) / p.ring_res_far;
  uint k = min(uint(clamp(guess, 0.0, float(rings))), rings);
  while (k > 0u && Less(r2, ring_bound2[k - 1u])) --k;
  while (k < rings && !Less(r2, ring_bound2[k])) ++k;
  return k;
}

// Point i's cell, kNone for invalid and noise points and beyond the last ring.
uint CellOf(uint i) {
  if (flags[i] != kPointValid) return kNone;  // invalid or noise
  uint rings = p.rings_near + p.rings_far;
  uint ring = RingOf(r2[i], rings);
  if (ring >= rings) return kNone;
  uint u = point_pixel[i] % p.width;
  return ring < p.rings_near
             ? ring * p.sectors_near + u / (p.width / p.sectors_near)
             : p.rings_near * p.sectors_near + (ring - p.rings_near) * p.sectors_far +
                   u / (p.width / p.sectors_far);
}

void Flush(uint cell, uint zmin, uint zmax, uint count) {
  atomicMin(cell_zmin[cell], zmin);
  atomicMax(cell_zmax[cell], zmax);
  atomicAdd(cell_count[cell], count);
}

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (kPass == 0u) {
    if (i >= pc.count) return;
    cell_zmin[i] = kNone;
    cell_zmax[i] = 0u;
    cell_count[i] = 0u;
    return;
  }
  // Pass 1: points kItems * i .. kItems * i + kItems - 1, each run of one cell reduced in
  // registers first (scans come ring by ring: consecutive points mostly share a cell).
  uint first = i * kItems;
  if (first >= pc.count) return;
  uint end = min(first + kItems, pc.count);
  uint cur = kNone, zmin = kNone, zmax = 0u, count = 0u;
  for (uint k = first; k < end; ++k) {
    uint cell = CellOf(k);
    point_cell[k] = cell;
    if (cell == kNone) continue;
    if (cell != cur) {
      if (cur != kNone) Flush(cur, zmin, zmax, count);
      cur = cell, zmin = kNone, zmax = 0u, count = 0u;
    }
    uint key = exact_Key(zt[k]);
    zmin = min(zmin, key);
    zmax = max(zmax, key);
    ++count;
  }
  if (cur != kNone) Flush(cur, zmin, zmax, count);
}
