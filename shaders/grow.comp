// Stage 8, grow (Alg. 1, IV-A): the GPU twin of reference_cpu/grow.cpp, same bytes.
// One shader, ten passes chosen by the specialization constant kMode, one pipeline each
// (host/stages/grow.cpp records them in this order, a compute-to-compute barrier after each
// dispatch):
//   0 reset    per flags word: the flags buffer to its start.
//   1 init     per quad of pixels: pixel_grown = pixel_fused; sizes = 0; the unknown pixels go
//              on the list (scratch).
//   2 list     one invocation: init for the last pixels % 4, then the list's workgroup count,
//              which is sweep 0's.
//   7 steps    per list entry (indirect, sweep 0's count): the pixel's step mask (StepMask).
//   3 sweep k  k = 0 .. budget - 1, per list entry, dispatched indirectly from the flags buffer:
//              a listed pixel still unknown with a ground neighbour it may step from becomes
//              ground (Claim) and the growth spreads on from it (Spread); odd sweeps walk the list
//              backwards. A sweep that changed something sets the next sweep's workgroup count;
//              so the sweeps after the first that changes nothing launch no workgroup and the
//              loop ends on the GPU.
//   9 runs     per quad of pixels (4i .. 4i + 3, the last one short): pixel_comp = the first
//              pixel of the ground pixel's run within the quad and row, kNone off ground.
//   4 merge    per 4 columns of a row: joins the trees of each ground pixel and its ground
//              neighbours right, below, below-left and below-right (columns wrap), skipping the
//              pairs that a path through other pairs joins anyway (Merge); the 4 columns'
//              classes are two vector loads when the width is a multiple of 4.
//   5 flatten  per quad of pixels: each ground pixel's root into scratch (the list is spent),
//              sizes[root] += the run's length.
//   6 finish   per quad of pixels: pixel_comp = the roots; unknown -> non-ground in pixel_grown;
//              pixel_label = pixel_grown, ground -> non-ground where the component has fewer
//              than min_component pixels; invocation 0 writes the summary word. 8: the same for
//              the last pixels % 4.
// Growing is monotone and its result the least fixed point (SPEC 2, reference_cpu/grow.cpp), so
// any schedule that grows only pixels with an allowed step from a ground pixel and stops after a
// sweep that changed nothing gives the reference's bytes. Here pixels change in place during a
// sweep (atomic loads, stores and compare-and-swap on pixel_grown: no data race); a sweep that
// changed nothing read a state nobody wrote, every unknown pixel (all are on the list) was tested
// against it, so that state is the fixed point. Spread walks on from each pixel an
// invocation grows (depth first, a private stack of kStack pixels; a pixel that does not fit is
// still ground and its neighbours are tested by the next sweep), so a long chain of unknown pixels
// costs one sweep, not one per pixel. (Earlier versions swept 8 x 32 tiles, one invocation each:
// on lavapipe every buffer access of an invocation is a loop over the SIMD lanes, and serial
// per-tile loops cost 50-65 ms of the 75 ms stage on a KITTI frame; and as lavapipe runs every
// branch under a lane mask, the growing code runs only over the list, 5 % of a KITTI image.)
// Components: a union-find over pixel_comp (the parent of each ground pixel), in which a root is
// hung only under a lower pixel and parents only decrease (unions and path halving by atomicMin),
// so each component ends as one tree whose root is its lowest pixel: the reference's component
// label in any schedule. All parent accesses of the merge and flatten passes are atomic.
// Flags (binding 10), words: 0 the list's length, 1 its workgroup count, 2 unused; then budget + 1
// indirect dispatch arguments (x, y, z), entry k for sweep k at words 3 (k + 1) .. 3 (k + 1) + 2:
// sweep 0's x set by the list pass, sweep k's (k > 0) by a sweep k - 1 that changed something,
// else 0; word 3 (budget + 2), the summary: the sweeps run up to and including the first that
// changed nothing (the fixed point proved), 0 when the budget ran out before that (the outputs
// are not valid). An empty list: sweep 0 runs no workgroup and the summary says 1.
// Step test (reference StepAllowed), each op rounded (`precise`): di = |ir - iq|, dz = |zr - zq|,
// step = |rr - rq|, when the column changes step = step + rq * column_arc; allowed = grow_dz +
// grow_grade * step; di <= grow_di && dz <= allowed.
#version 450
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_memory_scope_semantics : require  // atomicLoad/atomicStore (core SPIR-V)

#include "common/params.h"

layout(local_size_x_id = 0) in;

layout(std140, set = 0, binding = 0) uniform ParamsBlock { Params p; };
layout(std430, set = 0, binding = 1) readonly buffer PixelFused { uint pixel_fused[]; };
layout(std430, set = 0, binding = 2) readonly buffer Inten { float f_inten[]; };
layout(std430, set = 0, binding = 3) readonly buffer Height { float f_height[]; };
layout(std430, set = 0, binding = 4) readonly buffer Range { float f_range[]; };
layout(std430, set = 0, binding = 5) buffer PixelGrown { uint pixel_grown[]; };
layout(std430, set = 0, binding = 6) buffer PixelComp { uint pixel_comp[]; };
layout(std430, set = 0, binding = 7) buffer PixelLabel { uint pixel_label[]; };  // + step masks
layout(std430, set = 0, binding = 8) buffer List { uint list[]; };  // unknown pixels after sweep 0
layout(std430, set = 0, binding = 9) buffer Sizes { uint sizes[]; };
layout(std430, set = 0, binding = 10) buffer Flags { uint flags[]; };
// Four pixels at a time (init and finish: on a CPU driver each buffer access is a loop over the
// SIMD lanes, and one uvec4 access costs about a third of four).
layout(std430, set = 0, binding = 1) readonly buffer PixelFused4 { uvec4 pixel_fused4[]; };
layout(std430, set = 0, binding = 5) buffer PixelGrown4 { uvec4 pixel_grown4[]; };
layout(std430, set = 0, binding = 6) buffer PixelComp4 { uvec4 pixel_comp4[]; };
layout(std430, set = 0, binding = 7) buffer PixelLabel4 { uvec4 pixel_label4[]; };
layout(std430, set = 0, binding = 9) buffer Sizes4 { uvec4 sizes4[]; };
layout(std430, set = 0, binding = 8) buffer Roots4 { uvec4 roots4[]; };  // the list, after merge

layout(constant_id = 1) const uint kMode = 0u;

layout(push_constant) uniform Push {
  uint sweep;
  uint count;   // pixels (per-pixel modes)
  uint budget;  // sweeps recorded per fixed point (grow_max_iters)
} pc;

const uint kNone = 0xFFFFFFFFu;  // reference_cpu/frame.h
const uint kPixNonGround = 0u;
const uint kPixGround = 1u;
const uint kPixUnknown = 2u;

const uint kStack = 16u;  // Spread's depth-first stack

const uint kListLength = 0u, kListGroups = 1u;  // flags words

#define LoadAtomic(word) \
  atomicLoad(word, gl_ScopeDevice, gl_StorageSemanticsBuffer, gl_SemanticsRelaxed)

// The x word of the dispatch arguments of sweep k (0 .. budget), and the summary word.
uint ArgsWord(uint k) { return 3u * (k + 1u); }
uint SummaryWord() { return 3u * (pc.budget + 2u); }

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

// Unknown pixel r -> ground, when no other invocation got there first.
bool Claim(uint r) {
  return atomicCompSwap(pixel_grown[r], kPixUnknown, kPixGround) == kPixUnknown;
}

// The bit of a step mask for the neighbour at row offset dy (-1 .. 1) and column offset dx - 1
// (dx 0 .. 2): a step mask (mode 7, kept in pixel_label until the finish pass overwrites it) has
// that bit set when the step from that neighbour to the pixel is allowed, whatever the
// neighbour's class; so a sweep reads one word instead of both pixels' features per step.
uint StepBit(int dy, uint dx) { return 1u << (uint(dy + 1) * 3u + dx); }

// The step mask of unknown pixel r (mode 7).
uint StepMask(uint r) {
  uint w = p.width, h = p.beams;
  uint v = r / w, u = r - v * w, mask = 0u;
  for (int dy = -1; dy <= 1; ++dy) {
    int vv = int(v) + dy;
    if (vv < 0 || vv >= int(h)) continue;
    for (uint dx = 0u; dx < 3u; ++dx) {
      if (dy == 0 && dx == 1u) continue;
      uint uu = (u + w + dx - 1u) % w;  // columns wrap
      if (StepAllowed(uint(vv) * w + uu, r, uu, u)) mask |= StepBit(dy, dx);
    }
  }
  return mask;
}

// Grows on from the ground pixel x0 (just claimed): every unknown neighbour the pixel on the
// stack may step to is claimed and pushed, depth first, until the stack runs dry. Seen from
// neighbour y = x + (dy, dx - 1), x is at (-dy, 1 - dx): y's bit StepBit(-dy, 2 - dx).
void Spread(uint x0) {
  uint w = p.width, h = p.beams;
  uint stack[kStack];
  uint top = 1u;
  stack[0] = x0;
  while (top > 0u) {
    uint x = stack[--top];
    uint v = x / w, u = x - v * w;
    for (int dy = -1; dy <= 1; ++dy) {
      int vv = int(v) + dy;
      if (vv < 0 || vv >= int(h)) continue;
      for (uint dx = 0u; dx < 3u; ++dx) {
        if (dy == 0 && dx == 1u) continue;
        uint y = uint(vv) * w + (u + w + dx - 1u) % w;  // columns wrap
        if (LoadAtomic(pixel_grown[y]) == kPixUnknown &&
            (pixel_label[y] & StepBit(-dy, 2u - dx)) != 0u && Claim(y) && top < kStack)
          stack[top++] = y;
      }
    }
  }
}

// Does the unknown pixel r have a ground neighbour that may step to it (columns wrap)?
bool CanGrow(uint r) {
  uint w = p.width, h = p.beams;
  uint v = r / w, u = r - v * w, mask = pixel_label[r];
  for (int dy = -1; dy <= 1; ++dy) {
    int vv = int(v) + dy;
    if (vv < 0 || vv >= int(h)) continue;
    for (uint dx = 0u; dx < 3u; ++dx) {
      if (dy == 0 && dx == 1u) continue;
      uint q = uint(vv) * w + (u + w + dx - 1u) % w;
      if ((mask & StepBit(dy, dx)) != 0u && LoadAtomic(pixel_grown[q]) == kPixGround) return true;
    }
  }
  return false;
}

// One sweep's work on pixel r: true when it (and what spread from it) became ground here.
bool GrowPixel(uint r) {
  if (!CanGrow(r) || !Claim(r)) return false;
  Spread(r);
  return true;
}

// The sweeps up to and including the first that changed nothing; 0 when there is none.
uint SweepsRun() {
  for (uint k = 0u; k < pc.budget; ++k)
    if (flags[ArgsWord(k + 1u)] == 0u) return k + 1u;
  return 0u;
}

// The root of x's tree, halving the path on the way (parents only decrease: atomicMin).
uint Find(uint x) {
  for (;;) {
    uint parent = LoadAtomic(pixel_comp[x]);
    if (parent == x) return x;
    uint grand = LoadAtomic(pixel_comp[parent]);
    if (grand == parent) return parent;
    atomicMin(pixel_comp[x], grand);
    x = grand;
  }
}

// Joins the trees of ground pixels a and b: the higher root is hung under the lower one. When
// another invocation changed that root's parent meanwhile (atomicMin returns it), the join is
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

bool Ground(uint pix) { return pixel_grown[pix] == kPixGround; }

// The bits k (0 .. 3) of the ground pixels among four classes.
uint GroundBits(uvec4 g) {
  uvec4 bit = uvec4(equal(g, uvec4(kPixGround))) << uvec4(0u, 1u, 2u, 3u);
  return bit.x | bit.y | bit.z | bit.w;
}

// Pixel first + k is a column 0 pixel.
bool RowStart(uint first, uint k) { return (first + k) % p.width == 0u; }

// Pixels first + k and first + k - 1 (0 < k < 4) are ground pixels side by side in one row.
bool Joined(uint first, uvec4 g, uint k) {
  return g[k] == kPixGround && g[k - 1u] == kPixGround && !RowStart(first, k);
}

// The runs pass for the pixels first .. first + 3 of classes g (kPixNonGround past the image):
// each ground pixel's parent is the first pixel of its run among them (ground pixels side by
// side in one row), kNone off ground. Parents only decrease, and each run is one tree before the
// merge pass, which then joins only what lies across runs.
uvec4 RunParents(uint first, uvec4 g) {
  uvec4 parent = uvec4(kNone);
  for (uint k = 0u; k < 4u; ++k)
    if (g[k] == kPixGround) parent[k] = k > 0u && Joined(first, g, k) ? parent[k - 1u] : first + k;
  return parent;
}

// The flatten pass for the same pixels: each ground pixel's root (kNone off ground) and the
// component sizes, one Find and one size increment per run (in one loop over the runs: one copy
// of Find's code).
uvec4 Roots(uint first, uvec4 g) {
  uint joined = 0u;  // bit k: pixel k continues the run of pixel k - 1
  for (uint k = 1u; k < 4u; ++k)
    if (Joined(first, g, k)) joined |= 1u << k;
  uint starts = GroundBits(g) & ~joined;
  uvec4 root = uvec4(kNone);
  while (starts != 0u) {
    uint k = uint(findLSB(starts));
    starts &= starts - 1u;
    uint end = uint(findLSB((~joined & ~((2u << k) - 1u)) | 16u));  // the run: k .. end - 1
    uint r = Find(first + k);
    atomicAdd(sizes[r], end - k);
    uvec4 index = uvec4(0u, 1u, 2u, 3u);
    root = mix(root, uvec4(r), bvec4(uvec4(greaterThanEqual(index, uvec4(k))) &
                                     uvec4(lessThan(index, uvec4(end)))));
  }
  return root;
}

// The merge pass for the pixels k = 0 .. n - 1 at columns c0 + k of row v (n = min(4, width -
// c0), c0 a multiple of 4): each ground pixel is joined with its right, below, below-left and
// below-right ground neighbours (columns wrap), except where a path through other pairs joins
// them anyway:
//   right: the runs pass joined the next pixel of the same quad of pixel indices and row;
//   below: through the left pair when both its pixels are ground (left, down, right: side by
//     side pixels are always joined); column 0 never skips it, so every pair is reached;
//   below-left: through the left neighbour (its right and below pairs) or through below
//     (below-left's right pair) when either is ground; below-right likewise through right or
//     below.
// Images under two columns wide repeat neighbours: a pair with itself is skipped, a repeated
// pair is harmless. The pairs are bit masks over k (the four pixels' classes from two vector
// loads when the width is a multiple of 4); the unions run in one loop over the set bits, so the
// union code appears once (lavapipe runs code under a lane mask: inline unions cost on every
// quad, the loop only as many as a lane needs).
void Merge(uint v, uint c0) {
  uint w = p.width, row = v * w, first = row + c0, n = min(4u, w - c0);
  bool has_below = v + 1u < p.beams;
  uvec4 q = uvec4(kPixNonGround), b = uvec4(kPixNonGround);
  if (w % 4u == 0u) {
    q = pixel_grown4[first / 4u];
    if (has_below) b = pixel_grown4[(first + w) / 4u];
  } else {
    for (uint k = 0u; k < n; ++k) {
      q[k] = pixel_grown[first + k];
      if (has_below) b[k] = pixel_grown[first + w + k];
    }
  }
  uint self = GroundBits(q);
  if (self == 0u) return;
  // Bit k + 1 of the windows: pixel k (row, below); bit 0: the left neighbour of pixel 0, bit
  // n + 1: the right neighbour of pixel n - 1.
  uint left = row + (c0 + w - 1u) % w, right = row + (c0 + n) % w;
  uint row_bits = uint(Ground(left)) | (self << 1) | (uint(Ground(right)) << (n + 1u));
  uint below_bits = has_below ? uint(Ground(left + w)) | (GroundBits(b) << 1) |
                                    (uint(Ground(right + w)) << (n + 1u))
                              : 0u;
  uint gl = row_bits & 15u, gr = (row_bits >> 2) & 15u;
  uint gb = (below_bits >> 1) & 15u, gbl = below_bits & 15u, gbr = (below_bits >> 2) & 15u;
  uint apart = 0u;  // pixels whose right neighbour the runs pass did not join
  for (uint k = 0u; k < 4u; ++k)
    if (c0 + k + 1u == w || ((first + k) & 3u) == 3u) apart |= 1u << k;
  uint wide = w > 1u ? 15u : 0u;
  uint column0 = c0 == 0u ? 1u : 0u;
  uint pairs = (self & gr & apart & wide) |                // right
               ((self & gb & (column0 | ~gl | ~gbl)) << 4) |  // below
               ((self & ~gb & ~gl & gbl & wide) << 8) |       // below-left
               ((self & ~gb & ~gr & gbr & wide) << 12);       // below-right
  while (pairs != 0u) {
    uint bit = uint(findLSB(pairs)), k = bit & 3u, kind = bit >> 2;
    pairs &= pairs - 1u;
    uint u = c0 + k, pix = first + k;
    uint right_k = row + (u + 1u) % w, left_k = row + (u + w - 1u) % w;
    Union(pix, kind == 0u ? right_k : kind == 1u ? pix + w : kind == 2u ? left_k + w : right_k + w);
  }
}

// Init of pixel i (its own invocation in the list pass for the last pixels % 4).
void InitPixel(uint i) {
  uint c = pixel_fused[i];
  pixel_grown[i] = c;
  sizes[i] = 0u;
  if (c == kPixUnknown) list[atomicAdd(flags[kListLength], 1u)] = i;
}

// The finish of one pixel, whose class g, component c: its pixel_grown and pixel_label words.
uvec2 Finished(uint g, uint c) {
  if (g == kPixUnknown) g = kPixNonGround;
  return uvec2(g, g == kPixGround && sizes[c] < p.min_component ? kPixNonGround : g);
}

void main() {
  const uint mode = kMode;
  uint i = gl_GlobalInvocationID.x;
  if (mode == 0u) {  // reset: dispatch arguments (0, 1, 1), the other words 0
    if (i <= SummaryWord()) flags[i] = i >= 3u && i < SummaryWord() && i % 3u != 0u ? 1u : 0u;
    return;
  }
  if (mode == 1u) {  // init, pixels 4i .. 4i + 3
    if (i >= pc.count / 4u) return;
    uvec4 c = pixel_fused4[i];
    pixel_grown4[i] = c;
    uint first = 4u * i;
    sizes4[i] = uvec4(0u);
    uvec4 unknown = uvec4(equal(c, uvec4(kPixUnknown)));
    uint n = unknown.x + unknown.y + unknown.z + unknown.w;
    if (n == 0u) return;
    uint slot = atomicAdd(flags[kListLength], n);
    for (uint k = 0u; k < 4u; ++k)
      if (unknown[k] != 0u) list[slot++] = first + k;
    return;
  }
  if (mode == 2u) {  // the last pixels % 4's init, then the list's workgroups: sweep 0's
    if (i != 0u) return;
    for (uint pix = pc.count / 4u * 4u; pix < pc.count; ++pix) InitPixel(pix);
    uint groups = (flags[kListLength] + gl_WorkGroupSize.x - 1u) / gl_WorkGroupSize.x;
    flags[kListGroups] = groups;
    flags[ArgsWord(0u)] = groups;
    return;
  }
  if (mode == 7u) {  // the listed pixels' step masks
    if (i < flags[kListLength]) pixel_label[list[i]] = StepMask(list[i]);
    return;
  }
  if (mode == 3u) {  // sweep k
    uint n = flags[kListLength];
    if (i >= n) return;
    uint r = list[(pc.sweep & 1u) != 0u ? n - 1u - i : i];
    if (LoadAtomic(pixel_grown[r]) == kPixUnknown && GrowPixel(r))
      atomicMax(flags[ArgsWord(pc.sweep + 1u)], flags[kListGroups]);
    return;
  }
  if (mode == 6u) {  // finish, pixels 4i .. 4i + 3
    if (i == 0u) flags[SummaryWord()] = SweepsRun();
    if (i >= pc.count / 4u) return;
    uvec4 g = pixel_grown4[i], c = roots4[i];
    pixel_comp4[i] = c;
    uvec2 a = Finished(g.x, c.x), b = Finished(g.y, c.y), d = Finished(g.z, c.z),
          e = Finished(g.w, c.w);
    pixel_grown4[i] = uvec4(a.x, b.x, d.x, e.x);
    pixel_label4[i] = uvec4(a.y, b.y, d.y, e.y);
    return;
  }
  if (mode == 8u) {  // finish of the last pixels % 4
    uint pix = pc.count / 4u * 4u + i;
    if (pix >= pc.count) return;
    uint c = list[pix];
    pixel_comp[pix] = c;
    uvec2 f = Finished(pixel_grown[pix], c);
    pixel_grown[pix] = f.x;
    pixel_label[pix] = f.y;
    return;
  }
  if (mode == 9u || mode == 5u) {  // runs; flatten and count: pixels 4i .. 4i + 3
    uint first = 4u * i;
    if (first >= pc.count) return;
    bool whole = first + 4u <= pc.count;  // else the last pixels % 4, one by one
    uvec4 g = uvec4(kPixNonGround);        // past the image: never ground
    if (whole) g = pixel_grown4[i];
    else
      for (uint k = 0u; first + k < pc.count; ++k) g[k] = pixel_grown[first + k];
    if (mode == 9u) {
      uvec4 parent = RunParents(first, g);
      if (whole) pixel_comp4[i] = parent;
      else
        for (uint k = 0u; first + k < pc.count; ++k) pixel_comp[first + k] = parent[k];
    } else {
      uvec4 root = Roots(first, g);
      if (whole) roots4[i] = root;
      else
        for (uint k = 0u; first + k < pc.count; ++k) list[first + k] = root[k];
    }
    return;
  }
  if (mode == 4u) {  // merge, pixels 4j .. 4j + 3 of row v
    uint per_row = (p.width + 3u) / 4u, v = i / per_row;
    if (v < p.beams) Merge(v, 4u * (i - v * per_row));
  }
}
