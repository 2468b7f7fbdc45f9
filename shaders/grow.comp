// Stage 8, grow (Alg. 1, IV-A): the GPU twin of reference_cpu/grow.cpp, same bytes.
// One shader, eight passes chosen by the push constant `mode` (host/stages/grow.cpp records them
// in this order, a compute-to-compute barrier after each dispatch):
//   0 init     per pixel: pixel_grown = pixel_fused; sizes = 0; the flags buffer to its start.
//   1 grow     per tile, sweep k = 0 .. budget - 1, dispatched indirectly from the flags buffer:
//              reads state k % 2 (0: pixel_grown, 1: scratch), writes the other. Runs no
//              workgroup when sweep k - 1 changed nothing: both buffers then hold the fixed point.
//              A tile none of whose 3 x 3 neighbour tiles (itself included) changed in sweep
//              k - 1 returns at once: its inputs are those of sweep k - 1, and both buffers
//              already hold its values (a tile that did not change wrote what it read).
//              During the sweeps sizes[tile] = 1 + the last sweep that changed the tile.
//   2 settle   per pixel: unknown -> non-ground in pixel_grown; pixel_comp = pix where ground,
//              kNone elsewhere (every ground pixel its own tree); sizes[pix] = 0.
//   3 local    per tile: joins the trees of each ground pixel and its ground neighbours right,
//              below-left, below and below-right (every 8-neighbour pair once; columns wrap)
//              where both lie in the tile (a sequential union-find, no atomics).
//   4 border   per tile: the same for the pairs that cross into another tile (atomic union).
//   5 flatten  per pixel: pixel_comp = the root of the pixel's tree.
//   6 count    per pixel: sizes[pixel_comp[pix]] += 1 for ground pixels (integer atomics).
//   7 finish   per pixel: pixel_label = pixel_grown, ground -> non-ground where the component has
//              fewer than min_component pixels; invocation 0 writes the summary word.
// Growing: tiles of 8 rows x 32 columns, one invocation per tile (GrowTile), which scans its
// tile forward and backward until the tile reaches its own fixed point given its neighbours'
// pixels of the previous sweep, so one global sweep carries growth across a whole tile; a global
// sweep that changes nothing anywhere proves the global fixed point. Growing is monotone (the
// least fixed point is unique, SPEC 2), so any schedule gives the reference's bytes. (A first
// version iterated each tile with one invocation per pixel and two barriers per step: on lavapipe
// a barrier switches between all of a workgroup's invocations, and the sweeps cost ~25 ms each.)
// Components: a union-find over pixel_comp (the parent of each ground pixel), in which a root is
// hung only under a lower pixel and parents only decrease: first inside each tile by one
// invocation, then across tiles lock-free (atomicMin; a root re-hung meanwhile is retried from its
// new parent). After both, each component is one tree whose root is its lowest pixel (the lowest
// pixel's parent is never lower, so it stays a root, and there is one root), which is the
// reference's component label in any schedule. Across tiles, parents are read with atomic loads.
// Flags (binding 10): budget + 1 indirect dispatch arguments (x, y, z) for the grow sweeps: entry
// 0 holds the sweep's workgroup count, entry k + 1 is set to it by every workgroup of sweep k that changed
// something and stays 0 otherwise, so the sweeps after the first one that changes nothing launch
// no workgroup and the loop ends on the GPU. Word 3 (budget + 1): the grow sweeps run up to and
// including the first one that changed nothing (the fixed point proved), 0 when the budget ran
// out before that (non-convergence: the outputs are not valid).
// Step test (reference StepAllowed), each op rounded (`precise`): di = |ir - iq|, dz = |zr - zq|,
// step = |rr - rq|, when the column changes step = step + rq * column_arc; allowed = grow_dz +
// grow_grade * step; di <= grow_di && dz <= allowed.
#version 450
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_memory_scope_semantics : require  // atomicLoad (OpAtomicLoad, core SPIR-V)

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
  uint count;   // invocations that do work: pixels (per-pixel modes), tiles (mode 1)
  uint budget;  // sweeps recorded per fixed point (grow_max_iters)
} pc;

const uint kNone = 0xFFFFFFFFu;  // reference_cpu/frame.h
const uint kPixNonGround = 0u;
const uint kPixGround = 1u;
const uint kPixUnknown = 2u;

const uint kTileW = 32u, kTileH = 8u;  // host/stages/grow.h

// A relaxed atomic load: no race with the atomics other invocations write, and on a CPU driver a
// plain load instead of a locked read-modify-write.
#define LoadAtomic(word) atomicLoad(word, gl_ScopeDevice, gl_StorageSemanticsBuffer, gl_SemanticsRelaxed)

// The x word of the dispatch arguments for grow sweep k, and the summary word.
uint ArgsWord(uint k) { return 3u * k; }
uint SummaryWord() { return 3u * (pc.budget + 1u); }

// The step test from ground pixel q (column cq) to unknown pixel r (column cr), the reference's
// StepAllowed op for op.
bool StepAllowed(uint q, uint r, uint cq, uint cr) {
  float iq = f_inten[q], zq = f_height[q], rq = f_range[q];
  float ir = f_inten[r], zr = f_height[r], rr = f_range[r];
  precise float di = abs(ir - iq);
  precise float dz = abs(zr - zq);
  precise float step = abs(rr - rq);
  if (cq != cr) {
    precise float arc = rq * p.column_arc;
    step = step + arc;
  }
  precise float allowed = p.grow_dz + p.grow_grade * step;
  return di <= p.grow_di && dz <= allowed;
}

// Did tile (tx, ty) or one of its 8 neighbour tiles (columns wrap) change in sweep pc.sweep - 1?
bool NeighbourhoodChanged(uint tx, uint ty, uint tiles_x, uint tiles_y) {
  for (int dy = -1; dy <= 1; ++dy) {
    int yy = int(ty) + dy;
    if (yy < 0 || yy >= int(tiles_y)) continue;
    for (uint dx = 0u; dx < 3u; ++dx) {
      uint xx = (tx + tiles_x + dx - 1u) % tiles_x;
      if (LoadAtomic(sizes[uint(yy) * tiles_x + xx]) >= pc.sweep) return true;
    }
  }
  return false;
}

// Sweep pc.sweep of one tile, one invocation per tile: its pixels are copied from the previous
// sweep's buffer R into this sweep's buffer W and updated there in place (forward and backward
// raster scans until one changes nothing: the tile's own fixed point); its neighbours' pixels
// are read from R, which nobody writes during the sweep. No shared memory, no barrier, no race.
void GrowTile() {
  uint w = p.width, h = p.beams;
  uint tiles_x = (w + kTileW - 1u) / kTileW, tiles_y = (h + kTileH - 1u) / kTileH;
  uint tile = gl_GlobalInvocationID.x;
  if (tile >= tiles_x * tiles_y) return;
  uint tx = tile % tiles_x, ty = tile / tiles_x;
  if (pc.sweep > 0u && !NeighbourhoodChanged(tx, ty, tiles_x, tiles_y)) return;
  bool from_grown = (pc.sweep & 1u) == 0u;  // even sweeps: R = pixel_grown, W = scratch
  uint u0 = tx * kTileW, v0 = ty * kTileH;
  uint tw = min(kTileW, w - u0), th = min(kTileH, h - v0), n = tw * th;
  for (uint k = 0u; k < n; ++k) {
    uint q = (v0 + k / tw) * w + u0 + k % tw;
    if (from_grown) scratch[q] = pixel_grown[q]; else pixel_grown[q] = scratch[q];
  }
  bool changed = false;
  for (uint scan = 0u;; ++scan) {
    bool moved = false;
    for (uint k = 0u; k < n; ++k) {
      uint idx = (scan & 1u) == 0u ? k : n - 1u - k;
      uint u = u0 + idx % tw, v = v0 + idx / tw;
      uint r = v * w + u;
      uint state = from_grown ? scratch[r] : pixel_grown[r];
      if (state != kPixUnknown) continue;
      bool grows = false;
      for (int dy = -1; dy <= 1 && !grows; ++dy) {
        int vv = int(v) + dy;
        if (vv < 0 || vv >= int(h)) continue;
        for (uint dx = 0u; dx < 3u; ++dx) {
          if (dy == 0 && dx == 1u) continue;
          uint uu = (u + w + dx - 1u) % w;  // columns wrap
          uint q = uint(vv) * w + uu;
          bool mine = uu / kTileW == tx && uint(vv) / kTileH == ty;
          uint sq = mine == from_grown ? scratch[q] : pixel_grown[q];  // W if mine, else R
          if (sq == kPixGround && StepAllowed(q, r, uu, u)) {
            grows = true;
            break;
          }
        }
      }
      if (grows) {
        if (from_grown) scratch[r] = kPixGround; else pixel_grown[r] = kPixGround;
        moved = true;
      }
    }
    if (!moved) break;
    changed = true;
  }
  if (changed) {
    flags[ArgsWord(pc.sweep + 1u)] = gl_NumWorkGroups.x;
    atomicMax(sizes[tile], pc.sweep + 1u);
  }
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
    uint parent = LoadAtomic(pixel_comp[x]);
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

// The forward neighbours of pixel (u, v): right, below-left, below and below-right, columns
// wrapping (so every 8-neighbour pair once), without the pixel itself and without repeats (images
// under three columns wide). Returns how many.
uint Forward(uint u, uint v, out uint q[4]) {
  uint w = p.width, h = p.beams, n = 0u, pix = v * w + u;
  uint right = v * w + (u + 1u) % w;
  if (right != pix) q[n++] = right;
  if (v + 1u < h) {
    uint below = pix + w;
    uint left = (v + 1u) * w + (u + w - 1u) % w;
    uint below_right = (v + 1u) * w + (u + 1u) % w;
    q[n++] = below;
    if (left != below) q[n++] = left;
    if (below_right != below && below_right != left) q[n++] = below_right;
  }
  return n;
}

uint TileOf(uint pix) {
  uint w = p.width, tiles_x = (w + kTileW - 1u) / kTileW;
  return (pix / w / kTileH) * tiles_x + (pix % w) / kTileW;
}

// The tile-local union-find (mode 3): parents inside the invocation's own tile only, plain loads
// and stores (nobody else touches them in this pass), path halving, the lower root on top.
uint LocalFind(uint x) {
  while (pixel_comp[x] != x) {
    uint g = pixel_comp[pixel_comp[x]];
    pixel_comp[x] = g;
    x = g;
  }
  return x;
}

// Modes 3 (`border` false: the pairs inside the tile, LocalFind) and 4 (true: the pairs that
// cross into another tile, the atomic Union) over the ground pixels of the invocation's tile.
void MergeTile(bool border) {
  uint w = p.width, h = p.beams;
  uint tiles_x = (w + kTileW - 1u) / kTileW, tiles_y = (h + kTileH - 1u) / kTileH;
  uint tile = gl_GlobalInvocationID.x;
  if (tile >= tiles_x * tiles_y) return;
  uint u0 = (tile % tiles_x) * kTileW, v0 = (tile / tiles_x) * kTileH;
  uint tw = min(kTileW, w - u0), th = min(kTileH, h - v0);
  for (uint v = v0; v < v0 + th; ++v)
    for (uint u = u0; u < u0 + tw; ++u) {
      uint pix = v * w + u;
      if (pixel_grown[pix] != kPixGround) continue;
      // Only the border pixels have neighbours in other tiles.
      if (border && u != u0 && u != u0 + tw - 1u && v != v0 + th - 1u) continue;
      uint q[4];
      uint n = Forward(u, v, q);
      for (uint k = 0u; k < n; ++k) {
        if (pixel_grown[q[k]] != kPixGround || (TileOf(q[k]) != tile) != border) continue;
        if (border) {
          Union(pix, q[k]);
        } else {
          uint a = LocalFind(pix), b = LocalFind(q[k]);
          if (a < b) pixel_comp[b] = a;
          if (b < a) pixel_comp[a] = b;
        }
      }
    }
}

void main() {
  uint mode = pc.mode;
  if (mode == 1u || mode == 3u || mode == 4u) {  // per tile
    if (mode == 1u) GrowTile(); else MergeTile(mode == 4u);
    return;
  }
  uint pix = gl_GlobalInvocationID.x;
  if (mode == 0u) {
    if (pix < SummaryWord()) {  // dispatch arguments: (tiles, 1, 1) for sweep 0, else (0, 1, 1)
      uint tiles = ((p.width + kTileW - 1u) / kTileW) * ((p.beams + kTileH - 1u) / kTileH);
      uint groups = (tiles + gl_WorkGroupSize.x - 1u) / gl_WorkGroupSize.x;
      flags[pix] = pix % 3u != 0u ? 1u : pix == 0u ? groups : 0u;
    } else if (pix == SummaryWord()) {
      flags[pix] = 0u;
    }
    if (pix < pc.count) {
      pixel_grown[pix] = pixel_fused[pix];
      sizes[pix] = 0u;  // tiles <= pixels
    }
    return;
  }
  if (mode == 7u && pix == 0u) flags[SummaryWord()] = SweepsRun();
  if (pix >= pc.count) return;
  if (mode == 2u) {
    uint g = pixel_grown[pix];
    if (g == kPixUnknown) pixel_grown[pix] = kPixNonGround;
    pixel_comp[pix] = g == kPixGround ? pix : kNone;
    sizes[pix] = 0u;
  } else if (mode == 5u) {  // atomic: Find in other invocations reads the word
    if (pixel_grown[pix] == kPixGround)
      atomicStore(pixel_comp[pix], Find(pix), gl_ScopeDevice, gl_StorageSemanticsBuffer,
                  gl_SemanticsRelaxed);
  } else if (mode == 6u) {
    if (pixel_grown[pix] == kPixGround) atomicAdd(sizes[pixel_comp[pix]], 1u);
  } else if (mode == 7u) {
    uint g = pixel_grown[pix];
    if (g == kPixGround && sizes[pixel_comp[pix]] < p.min_component) g = kPixNonGround;
    pixel_label[pix] = g;
  }
}
