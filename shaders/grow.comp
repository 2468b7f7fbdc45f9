// grow (Alg. 1, IV-A): the GPU twin of reference_cpu/grow.cpp, same bytes.
// In: pixel_fused, f_height, f_range. Out: pixel_grown, pixel_comp, pixel_label.
// Growing is connected-component labelling (docs/spec.md, Readings of the paper): with the
// symmetric step tests below, the unknown pixels that grow are those whose component of the
// allowed-step graph (nodes: ground and unknown pixels; edges: 8-neighbours, columns wrapping,
// whose step is allowed) holds a ground pixel. Two union-finds with lowest-index roots (parents
// only decrease: links and path halving by atomicMin), each correct in any schedule: `grow_reach`
// over the allowed-step graph, in which every ground pixel starts under the virtual node 0 (node
// x + 1 is pixel x), so a component holds a seed exactly when its root is 0; `comp` (pixel_comp)
// over the 8-connected ground pixels after growing, whose roots are the components' lowest
// pixels.
// Five passes, one pixel an invocation, chosen by the specialization constant kPass, one
// pipeline each, recorded in this order with a compute-to-compute barrier between them
// (host/gpu/grow.cpp):
//   0 init    grow_reach[x + 1] = 0 for ground, x + 1 for unknown (kPixUnknown and
//             kPixUnknownOff alike), kNone otherwise;
//             grow_reach[0] = 0; pixel_comp[x] = x; grow_sizes[x] = grow_sizes[count + x] = 0.
//   1 reach   for each node x and each forward neighbour y (right, below-left, below,
//             below-right) that is a node, not both ground, with an allowed step (or, for the
//             neighbour below, a bank's step up to x): union of x + 1 and y + 1 in grow_reach.
//   2 join    x grows when it is ground, or unknown with grow_reach root 0; pixel_grown[x] = ground
//             then, non-ground for an unknown pixel that did not grow, pixel_fused[x] otherwise.
//             A grown x is joined in pixel_comp with each forward neighbour that grows (the
//             neighbour's test is made here too, so no pass sits between growing and joining).
//   3 count   for a grown x: root = Find(x) in pixel_comp, pixel_comp[x] = root,
//             grow_sizes[root] += 1, and grow_sizes[count + root] += 1 when x is a seed
//             (pixel_fused ground).
//   4 finish  pixel_comp[x] = kNone off ground; pixel_label[x] = pixel_grown[x], ground ->
//             non-ground where the component is removed: size < min_component and not (size >=
//             comp_seed_min and float(seeds) >= comp_seed_share * float(size), one rounded
//             product), size = grow_sizes[pixel_comp[x]], seeds = grow_sizes[count +
//             pixel_comp[x]]; a vetoed x -> ground where lifted, else non-ground.
// The veto's lift (the reference's LiftVetoed), judged on the pass-4 ground of the pixels around
// x ("ends ground": grown and its component kept): the two row neighbours (columns wrap) end
// ground and the step from each to x is allowed; or, x not on row 0, the pixel above ends ground
// and x's ray did not pass under it: not (d = Ftz0(range above - r) < 0 and Ftz0(z * d) >=
// Ftz0(occ_pass * r)).
// Step test from pixel a to pixel b (the reference's StepAllowed, each op rounded: `precise`):
// dz = |zb - za|, step = |rb - ra|, + min(ra, rb) * column_arc when the column changes;
// allowed = grow_dz + grow_grade * step; dz <= allowed. Every term is
// symmetric in a and b (IEEE |b - a| = |a - b|), so the graph is undirected. Each result goes
// through exact_Ftz0 as in the reference, so that a device that flushes subnormals agrees.
// A bank's step from pixel lo up to pixel up, the one above it in its column (the reference's
// BankStep), where either is kPixUnknownOff: d = r_up - r_lo, rise = z_up - z_lo, allowed =
// grow_dz + bank_slope * d, each through exact_Ftz0; d > 0 && rise >= 0 && rise <= allowed. An
// edge of the same undirected graph: it is tested once, from the upper pixel's forward
// neighbour below.
#version 450
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_memory_scope_semantics : require  // atomicLoad (core SPIR-V)

#include "common/params.h"
#include "common/frame_codes.h"
#include "common/exact.glsl"

layout(local_size_x_id = 0) in;

layout(std140, set = 0, binding = 0) uniform ParamsBlock { Params p; };
layout(std430, set = 0, binding = 1) readonly buffer PixelFused { uint pixel_fused[]; };
layout(std430, set = 0, binding = 2) readonly buffer Height { float f_height[]; };
layout(std430, set = 0, binding = 3) readonly buffer Range { float f_range[]; };
layout(std430, set = 0, binding = 4) buffer PixelGrown { uint pixel_grown[]; };
layout(std430, set = 0, binding = 5) buffer PixelComp { uint pixel_comp[]; };
layout(std430, set = 0, binding = 6) buffer PixelLabel { uint pixel_label[]; };
layout(std430, set = 0, binding = 7) buffer GrowReach { uint grow_reach[]; };  // pixels + 1 nodes
layout(std430, set = 0, binding = 8) buffer GrowSizes { uint grow_sizes[]; };  // 2 per pixel

layout(constant_id = 1) const uint kPass = 0u;

layout(push_constant) uniform Push {
  uint count;  // pixels: width * beams
} pc;

const uint kSeed = 0u;  // grow_reach's virtual node: the root of every component holding a seed

const uint kInit = 0u, kReach = 1u, kJoin = 2u, kCount = 3u, kFinish = 4u;

#define LoadAtomic(word) \
  atomicLoad(word, gl_ScopeDevice, gl_StorageSemanticsBuffer, gl_SemanticsRelaxed)

// One union-find per buffer; the macro keeps a single definition of Find and Union over either
// (GLSL passes no buffer by reference). Find: the root of x, halving the path on the way. Union:
// the higher root is hung under the lower; when another invocation changed that root's parent
// meanwhile (atomicMin returns it), the join is retried from there, so no link is lost.
#define UNION_FIND(Find, Union, up)                     \
  uint Find(uint x) {                                   \
    for (;;) {                                          \
      uint parent = LoadAtomic(up[x]);                  \
      if (parent == x) return x;                        \
      uint grand = LoadAtomic(up[parent]);              \
      if (grand == parent) return parent;               \
      atomicMin(up[x], grand);                          \
      x = grand;                                        \
    }                                                   \
  }                                                     \
  void Union(uint a, uint b) {                          \
    for (;;) {                                          \
      a = Find(a);                                      \
      b = Find(b);                                      \
      if (a == b) return;                               \
      if (a > b) {                                      \
        uint t = a;                                     \
        a = b;                                          \
        b = t;                                          \
      }                                                 \
      uint old = atomicMin(up[b], a);                   \
      if (old == b) return;                             \
      b = old;                                          \
    }                                                   \
  }
UNION_FIND(FindReach, UnionReach, grow_reach)
UNION_FIND(FindComp, UnionComp, pixel_comp)

// The step test between pixels a and b (columns ca, cb), the reference's StepAllowed op for op.
bool StepAllowed(uint a, uint b, uint ca, uint cb) {
  float za = f_height[a], ra = f_range[a];
  float zb = f_height[b], rb = f_range[b];
  precise float dz = exact_Ftz0(abs(zb - za));
  precise float step = exact_Ftz0(abs(rb - ra));
  if (ca != cb) {
    precise float arc = exact_Ftz0(min(ra, rb) * p.column_arc);
    step = exact_Ftz0(step + arc);
  }
  precise float graded = exact_Ftz0(p.grow_grade * step);
  precise float allowed = exact_Ftz0(p.grow_dz + graded);
  return dz <= allowed;
}

// The bank's step between pixel up and pixel lo, the one below it in its column, whose fused
// classes are cu and cl.
bool Climbs(uint up, uint lo, uint cu, uint cl) {
  if (cu != kPixUnknownOff && cl != kPixUnknownOff) return false;
  precise float d = exact_Ftz0(f_range[up] - f_range[lo]);
  precise float rise = exact_Ftz0(f_height[up] - f_height[lo]);
  precise float graded = exact_Ftz0(p.bank_slope * d);
  precise float allowed = exact_Ftz0(p.grow_dz + graded);
  return d > 0.0 && rise >= 0.0 && rise <= allowed;
}

bool Unknown(uint c) { return c == kPixUnknown || c == kPixUnknownOff; }
bool Node(uint c) { return c == kPixGround || Unknown(c); }

// Does pixel x grow (join pass: grow_reach is final)?
bool Grows(uint x) {
  uint c = pixel_fused[x];
  return c == kPixGround || (Unknown(c) && FindReach(x + 1u) == kSeed);
}

// Forward neighbour k (0 right, 1 below-left, 2 below, 3 below-right) of pixel x at row v,
// column u, with its column in `col`; kNone past the last row or where it is x itself (images
// one column wide).
uint Forward(uint x, uint v, uint u, uint k, out uint col) {
  uint w = p.width;
  if (k == 0u) {
    col = u + 1u == w ? 0u : u + 1u;
    return col == u ? kNone : x - u + col;
  }
  if (v + 1u >= p.beams) return kNone;
  col = k == 1u ? (u == 0u ? w - 1u : u - 1u) : k == 2u ? u : (u + 1u == w ? 0u : u + 1u);
  return x - u + w + col;
}

// Finish pass: is grown pixel q ground after the component test (its component kept)? Reads
// only what earlier passes wrote (pixel_grown, pixel_comp of grown pixels, grow_sizes).
bool EndsGround(uint q) {
  if (pixel_grown[q] != kPixGround) return false;
  uint root = pixel_comp[q];
  uint size = grow_sizes[root], seeds = grow_sizes[pc.count + root];
  precise float need = p.comp_seed_share * float(size);
  bool kept = size >= p.comp_seed_min && float(seeds) >= need;
  return size >= p.min_component || kept;
}

// Finish pass: the veto's lift of vetoed pixel x (row v, column u), on labels before any lift.
bool Lifted(uint x, uint v, uint u) {
  uint w = p.width;
  uint cl = u == 0u ? w - 1u : u - 1u, cr = u + 1u == w ? 0u : u + 1u;
  uint left = x - u + cl, right = x - u + cr;
  if (EndsGround(left) && EndsGround(right) && StepAllowed(left, x, cl, u) &&
      StepAllowed(right, x, cr, u))
    return true;
  if (v == 0u || !EndsGround(x - w)) return false;
  float r = f_range[x];
  precise float d = exact_Ftz0(f_range[x - w] - r);
  precise float clearance = exact_Ftz0(f_height[x] * d);
  precise float pass = exact_Ftz0(p.occ_pass * r);
  return !(d < 0.0 && clearance >= pass);
}

void main() {
  const uint pass = kPass;
  uint x = gl_GlobalInvocationID.x;
  if (x >= pc.count) return;
  if (pass == kInit) {
    uint c = pixel_fused[x];
    grow_reach[x + 1u] = c == kPixGround ? kSeed : Unknown(c) ? x + 1u : kNone;
    if (x == 0u) grow_reach[0] = kSeed;
    pixel_comp[x] = x;
    grow_sizes[x] = 0u;
    grow_sizes[pc.count + x] = 0u;
    return;
  }
  uint v = x / p.width, u = x - v * p.width;
  if (pass == kReach) {
    uint c = pixel_fused[x];
    if (!Node(c)) return;
    for (uint k = 0u; k < 4u; ++k) {
      uint col;
      uint y = Forward(x, v, u, k, col);
      if (y == kNone) continue;
      uint d = pixel_fused[y];
      if (!Node(d) || (c == kPixGround && d == kPixGround)) continue;
      if (StepAllowed(x, y, u, col) || (k == 2u && Climbs(x, y, c, d))) UnionReach(x + 1u, y + 1u);
    }
    return;
  }
  if (pass == kJoin) {
    uint c = pixel_fused[x];
    bool grows = Grows(x);
    pixel_grown[x] = grows ? kPixGround : Unknown(c) ? kPixNonGround : c;
    if (!grows) return;
    for (uint k = 0u; k < 4u; ++k) {
      uint col;
      uint y = Forward(x, v, u, k, col);
      if (y != kNone && Grows(y)) UnionComp(x, y);
    }
    return;
  }
  if (pass == kCount) {
    if (pixel_grown[x] != kPixGround) return;
    uint root = FindComp(x);
    atomicMin(pixel_comp[x], root);
    atomicAdd(grow_sizes[root], 1u);
    if (pixel_fused[x] == kPixGround) atomicAdd(grow_sizes[pc.count + root], 1u);
    return;
  }
  if (pass == kFinish) {
    uint g = pixel_grown[x];
    if (g == kPixGround) {
      pixel_label[x] = EndsGround(x) ? kPixGround : kPixNonGround;
      return;
    }
    pixel_comp[x] = kNone;
    pixel_label[x] = g != kPixVetoed ? g : Lifted(x, v, u) ? kPixGround : kPixNonGround;
  }
}
