// Stage 8, grow (Alg. 1, IV-A): the GPU twin of reference_cpu/grow.cpp, same bytes.
// One shader, seven passes chosen by the push constant `mode` (host/stages/grow.cpp records them
// in this order, a compute-to-compute barrier after each dispatch):
//   0 init     per pixel: pixel_grown = pixel_fused; the flags buffer to its starting state.
//   1 grow     per tile, sweep k = 0 .. budget - 1, dispatched indirectly from the flags buffer:
//              reads state k % 2 (0: pixel_grown, 1: scratch), writes the other. Runs no
//              workgroup when sweep k - 1 changed nothing: both buffers then hold the fixed point.
//   2 settle   per pixel: unknown -> non-ground in pixel_grown; pixel_comp = pix where ground,
//              kNone elsewhere (every ground pixel its own tree); sizes[pix] = 0.
//   3 merge    per pixel: joins the trees of each ground pixel and its ground neighbours right,
//              below-left, below and below-right (every 8-neighbour pair once; columns wrap).
//   4 flatten  per pixel: pixel_comp = the root of the pixel's tree.
//   5 count    per pixel: sizes[pixel_comp[pix]] += 1 for ground pixels (integer atomics).
//   6 finish   per pixel: pixel_label = pixel_grown, ground -> non-ground where the component has
//              fewer than min_component pixels; invocation 0 writes the summary word.
// Growing: tiles of 8 rows x 32 columns, one invocation per tile pixel (local size 256), the tile
// and a one-pixel halo in shared memory (columns wrap; halo slots, and tile slots past the last
// column, are read-only copies of the previous sweep). Inside a tile the sweep iterates to the
// tile's own fixed point (two barriers per step: all read, then all write), so one global sweep
// carries growth across a whole tile; a global sweep that changes nothing anywhere proves the
// global fixed point. Growing is monotone (the least fixed point is unique, SPEC 2), so any
// schedule gives the reference's bytes.
// Components: a lock-free union-find over pixel_comp (the parent of each ground pixel), in which
// a tree's root is hung only under a lower pixel with atomicMin and parents only decrease; after
// the merge pass each component is one tree whose root is its lowest pixel (the lowest pixel's
// parent is never lower, so it stays a root, and there is one root), which is the reference's
// component label in any schedule. Parents are read with atomics inside the merge pass.
// Flags (binding 10): budget + 1 indirect dispatch arguments (x, y, z) for the grow sweeps: entry
// 0 holds the tile count, entry k + 1 is set to it by every workgroup of sweep k that changed
// something and stays 0 otherwise, so the sweeps after the first one that changes nothing launch
// no workgroup and the loop ends on the GPU. Word 3 (budget + 1): the grow sweeps run up to and
// including the first one that changed nothing (the fixed point proved), 0 when the budget ran
// out before that (non-convergence: the outputs are not valid).
// Step test (reference StepAllowed), each op rounded (`precise`): di = |ir - iq|, dz = |zr - zq|,
// step = |rr - rq|, when the column changes step = step + rq * column_arc; allowed = grow_dz +
// grow_grade * step; di <= grow_di && dz <= allowed.
#version 450
#extension GL_GOOGLE_include_directive : require

#include "common/params.h"

layout(local_size_x_id = 0) in;  // must be 256 (kTileW * kTileH)

layout(std140, set = 0, binding = 0) uniform ParamsBlock { Params p; };
layout(std430, set = 0, binding = 1) readonly buffer PixelFused { uint pixel_fused[]; };
layout(std430, set = 0, binding = 2) readonly buffer Inten { float f_inten[]; };
layout(std430, set = 0, binding = 3) readonly buffer Height { float f_height[]; };
layout(std430, set = 0, binding = 4) readonly buffer Range { float f_range[]; };
layout(std430, set = 0, binding = 5) buffer PixelGrown { uint pixel_grown[]; };
layout(std430, set = 0, binding = 6) coherent buffer PixelComp { uint pixel_comp[]; };
layout(std430, set = 0, binding = 7) writeonly buffer PixelLabel { uint pixel_label[]; };
layout(std430, set = 0, binding = 8) buffer Scratch { uint scratch[]; };
layout(std430, set = 0, binding = 9) buffer Sizes { uint sizes[]; };
layout(std430, set = 0, binding = 10) buffer Flags { uint flags[]; };

layout(push_constant) uniform Push {
  uint mode;
  uint sweep;
  uint count;   // invocations that do work: pixels (per-pixel modes), tiles * 256 (tile modes)
  uint budget;  // sweeps recorded per fixed point (grow_max_iters)
} pc;

const uint kNone = 0xFFFFFFFFu;  // reference_cpu/frame.h
const uint kPixNonGround = 0u;
const uint kPixGround = 1u;
const uint kPixUnknown = 2u;

const uint kTileW = 32u, kTileH = 8u;
const uint kSW = kTileW + 2u, kSH = kTileH + 2u, kSlots = kSW * kSH;

shared uint s_val[kSlots];    // state (grow) or label (label)
shared uint s_col[kSlots];    // the slot's column; kNone: outside the image (row out of range)
shared float s_inten[kSlots];
shared float s_height[kSlots];
shared float s_range[kSlots];
shared uint s_flag[3];        // per local step, rotating (see TileSweep)
shared uint s_any;            // the tile changed something this sweep

// The x word of the dispatch arguments for grow sweep k, and the summary word.
uint ArgsWord(uint k) { return 3u * k; }
uint SummaryWord() { return 3u * (pc.budget + 1u); }

// The step test from ground slot q to unknown slot r.
bool StepAllowed(uint q, uint r) {
  float iq = s_inten[q], zq = s_height[q], rq = s_range[q];
  float ir = s_inten[r], zr = s_height[r], rr = s_range[r];
  precise float di = abs(ir - iq);
  precise float dz = abs(zr - zq);
  precise float step = abs(rr - rq);
  if (s_col[q] != s_col[r]) {
    precise float arc = rq * p.column_arc;
    step = step + arc;
  }
  precise float allowed = p.grow_dz + p.grow_grade * step;
  return di <= p.grow_di && dz <= allowed;
}

void GrowSweep() {
  uint w = p.width, h = p.beams;
  uint tiles_x = (w + kTileW - 1u) / kTileW;
  uint tile = gl_WorkGroupID.x;
  uint tx = tile % tiles_x, ty = tile / tiles_x;
  uint lid = gl_LocalInvocationID.x;
  uint lx = lid % kTileW, ly = lid / kTileW;
  bool from_grown = (pc.sweep & 1u) == 0u;  // even sweeps read the stage output buffer

  // Load the tile and its halo (previous sweep's values).
  for (uint i = lid; i < kSlots; i += kTileW * kTileH) {
    uint sy = i / kSW, sx = i % kSW;
    uint vv = ty * kTileH + sy;  // row + 1
    uint col = (tx * kTileW + sx + w - 1u) % w;
    uint val = 0u;
    uint c = kNone;
    if (vv >= 1u && vv <= h) {
      uint q = (vv - 1u) * w + col;
      c = col;
      val = from_grown ? pixel_grown[q] : scratch[q];
      s_inten[i] = f_inten[q];
      s_height[i] = f_height[q];
      s_range[i] = f_range[q];
    }
    s_val[i] = val;
    s_col[i] = c;
  }
  uint u = tx * kTileW + lx, v = ty * kTileH + ly;
  bool own = u < w && v < h;
  uint me = (ly + 1u) * kSW + lx + 1u;
  uint pix = v * w + u;
  if (lid < 3u) s_flag[lid] = 0u;
  if (lid == 0u) s_any = 0u;
  barrier();
  uint first = s_val[me];

  // Local steps to the tile's fixed point.
  for (uint it = 0u;; ++it) {
    uint f = it % 3u;
    if (lid == 0u) s_flag[(it + 1u) % 3u] = 0u;
    bool moves = false;
    uint next = s_val[me];
    if (own && next == kPixUnknown) {
      for (int dy = -1; dy <= 1 && !moves; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          if (dy == 0 && dx == 0) continue;
          uint q = uint(int(me) + dy * int(kSW) + dx);
          if (s_val[q] == kPixGround && s_col[q] != kNone && StepAllowed(q, me)) {
            moves = true;
            break;
          }
        }
      if (moves) next = kPixGround;
    }
    barrier();
    if (moves) {
      s_val[me] = next;
      s_flag[f] = 1u;
    }
    barrier();
    if (s_flag[f] == 0u) break;
  }

  if (own) {
    uint last = s_val[me];
    if (from_grown) scratch[pix] = last; else pixel_grown[pix] = last;
    if (last != first) s_any = 1u;
  }
  barrier();
  if (lid == 0u && s_any != 0u) flags[ArgsWord(pc.sweep + 1u)] = gl_NumWorkGroups.x;
}

// The sweeps up to and including the first that changed nothing; 0 when there is none.
uint SweepsRun() {
  for (uint k = 0u; k < pc.budget; ++k)
    if (flags[ArgsWord(k + 1u)] == 0u) return k + 1u;
  return 0u;
}

// The root of x's tree, reading parents with atomics (other invocations are re-hanging roots).
uint Find(uint x) {
  for (;;) {
    uint parent = atomicOr(pixel_comp[x], 0u);
    if (parent == x) return x;
    x = parent;
  }
}

// Joins the trees of ground pixels a and b: the higher root is hung under the lower one. When
// another invocation re-hung that root meanwhile (atomicMin returns its new parent), the join is
// retried from there, so no link is lost.
void Union(uint a, uint b) {
  for (;;) {
    a = Find(a);
    b = Find(b);
    if (a == b) return;
    if (a > b) {
      uint t = a;
      a = b;
      b = t;
    }
    uint old = atomicMin(pixel_comp[b], a);
    if (old == b) return;
    b = old;
  }
}

// The merge pass for pixel pix = v * w + u (a ground pixel).
void Merge(uint pix) {
  uint w = p.width, h = p.beams;
  uint u = pix % w, v = pix / w;
  uint right = v * w + (u + 1u) % w;
  if (right != pix && pixel_grown[right] == kPixGround) Union(pix, right);
  if (v + 1u >= h) return;
  uint below = pix + w;
  uint left = (v + 1u) * w + (u + w - 1u) % w;
  uint below_right = (v + 1u) * w + (u + 1u) % w;
  if (pixel_grown[below] == kPixGround) Union(pix, below);
  if (left != below && pixel_grown[left] == kPixGround) Union(pix, left);
  if (below_right != below && below_right != left && pixel_grown[below_right] == kPixGround)
    Union(pix, below_right);
}

void main() {
  uint mode = pc.mode;
  if (mode == 1u) {
    GrowSweep();
    return;
  }
  uint pix = gl_GlobalInvocationID.x;
  if (mode == 0u) {
    if (pix < SummaryWord()) {  // dispatch arguments: (tiles, 1, 1) for sweep 0, else (0, 1, 1)
      uint tiles = ((p.width + kTileW - 1u) / kTileW) * ((p.beams + kTileH - 1u) / kTileH);
      flags[pix] = pix % 3u != 0u ? 1u : pix == 0u ? tiles : 0u;
    } else if (pix == SummaryWord()) {
      flags[pix] = 0u;
    }
    if (pix < pc.count) pixel_grown[pix] = pixel_fused[pix];
    return;
  }
  if (mode == 6u && pix == 0u) flags[SummaryWord()] = SweepsRun();
  if (pix >= pc.count) return;
  if (mode == 2u) {
    uint g = pixel_grown[pix];
    if (g == kPixUnknown) pixel_grown[pix] = kPixNonGround;
    pixel_comp[pix] = g == kPixGround ? pix : kNone;
    sizes[pix] = 0u;
  } else if (mode == 3u) {
    if (pixel_grown[pix] == kPixGround) Merge(pix);
  } else if (mode == 4u) {
    if (pixel_grown[pix] == kPixGround) atomicMin(pixel_comp[pix], Find(pix));  // atomic: others read it
  } else if (mode == 5u) {
    if (pixel_grown[pix] == kPixGround) atomicAdd(sizes[pixel_comp[pix]], 1u);
  } else if (mode == 6u) {
    uint g = pixel_grown[pix];
    if (g == kPixGround && sizes[pixel_comp[pix]] < p.min_component) g = kPixNonGround;
    pixel_label[pix] = g;
  }
}
