// fuse (paper III-D.2): the GPU twin of reference_cpu/fuse.cpp, same bytes.
// One dispatch, of one of two passes (specialization constant kPass): pass 0, any width, one
// invocation per pixel < pixels (push constant), pass 1's code on component x; or instead, for a
// width that is a multiple of 4, pass 1, one invocation per quad of pixels 4q .. 4q + 3, every
// per-pixel buffer read and written as vec4 / uvec4 (a quad never straddles rows, and its rows
// above are quads too; docs/decisions/fuse.md).
// In: binding 0 Params (uniform), 1 pixel_class, 2 pixel_point (kNone: no point), 3 coarse (per
//     point; any buffer of at least one element when there are no points), 4 pixel_filled,
//     5 f_range, 6 f_height (floats). Out: 7 pixel_fused (kPix*, kPixVetoed, kPixUnknownOff).
// Opinion: the coarse bit of the pixel's winning point, kPixUnknown where it has none.
// Occlusion veto over rows v - k, k = 1 .. min(occ_rows, v) of the same column: the pixel's
// bounds, each one rounded float op (`precise`, never an FMA), in this order: rr = r * r,
// grade = occ_grade * rr, near = r + occ_margin, reach = near + grade, and where the pixel's class
// is ground reach = min(reach, r + occ_front); top = Ftz0(z + occ_rise); pass = Ftz0(occ_pass *
// r). An occluder: filled above != 0, range above < reach, height above > top, and not passed
// under: the pixel's class is ground, d = Ftz0(range above - r) < 0 and Ftz0(z * d) >= pass
// (computed for every pixel, empty ones too, as the reference does; an empty pixel is empty
// whatever they say).
// Step spare over rows v - k, k = 1 .. min(occ_step_rows, v): far = Ftz0(r + occ_step_reach),
// base = Ftz0(z + occ_step); for each row above, d = Ftz0(range above - r), beyond = d > 0 ? d :
// 0, bound = Ftz0(base + Ftz0(occ_step_grade * beyond)); it counts when filled != 0 and range
// above < far; steep |= counts & height above > bound; landing |= counts & class above == ground &
// d > 0. occluded &= !(landing & !steep).
// Decision: agree = class == opinion, or class unknown and opinion ground; unknown = opinion ==
// ground ? kPixUnknown : kPixUnknownOff; vote = agree and opinion != kNoOpinion ? opinion :
// unknown (a bank, kPixBank, never agrees); kept = occluded ? (vote == non-ground ? non-ground :
// vetoed) : vote; fused = class empty ? empty : kept.
// No ties and no reductions: each invocation writes only its own pixels.
#version 450
#extension GL_GOOGLE_include_directive : require

#include "common/params.h"
#include "common/frame_codes.h"
#include "common/exact.glsl"

layout(local_size_x_id = 0) in;

layout(std140, set = 0, binding = 0) uniform ParamsBlock { Params p; };
layout(std430, set = 0, binding = 1) readonly buffer PixelClass { uint pixel_class[]; };
layout(std430, set = 0, binding = 2) readonly buffer PixelPoint { uint pixel_point[]; };
layout(std430, set = 0, binding = 3) readonly buffer Coarse { uint coarse[]; };
layout(std430, set = 0, binding = 4) readonly buffer PixelFilled { uint pixel_filled[]; };
layout(std430, set = 0, binding = 5) readonly buffer Range { float f_range[]; };
layout(std430, set = 0, binding = 6) readonly buffer Height { float f_height[]; };
layout(std430, set = 0, binding = 7) writeonly buffer PixelFused { uint pixel_fused[]; };

// The same buffers four pixels at a time (pass 1).
layout(std430, set = 0, binding = 1) readonly buffer PixelClass4 { uvec4 pixel_class4[]; };
layout(std430, set = 0, binding = 2) readonly buffer PixelPoint4 { uvec4 pixel_point4[]; };
layout(std430, set = 0, binding = 4) readonly buffer PixelFilled4 { uvec4 pixel_filled4[]; };
layout(std430, set = 0, binding = 5) readonly buffer Range4 { vec4 f_range4[]; };
layout(std430, set = 0, binding = 6) readonly buffer Height4 { vec4 f_height4[]; };
layout(std430, set = 0, binding = 7) writeonly buffer PixelFused4 { uvec4 pixel_fused4[]; };

layout(constant_id = 1) const uint kPass = 0u;  // a pipeline per pass (host/vk/kernel.h)
const bool kQuad = kPass == 1u;
const uint kLanes = kQuad ? 4u : 1u;  // pixels per invocation

layout(push_constant) uniform Push { uint pixels; } pc;

const uint kNoOpinion = kPixUnknown;

// Element e of a buffer: a quad in pass 1, a pixel (in component x) in pass 0.
uvec4 ClassAt(uint e) { return kQuad ? pixel_class4[e] : uvec4(pixel_class[e]); }
uvec4 PointAt(uint e) { return kQuad ? pixel_point4[e] : uvec4(pixel_point[e]); }
uvec4 FilledAt(uint e) { return kQuad ? pixel_filled4[e] : uvec4(pixel_filled[e]); }
vec4 RangeAt(uint e) { return kQuad ? f_range4[e] : vec4(f_range[e]); }
vec4 HeightAt(uint e) { return kQuad ? f_height4[e] : vec4(f_height[e]); }

void main() {
  uint e = gl_GlobalInvocationID.x;
  if (e >= pc.pixels / kLanes) return;
  uint w = p.width, row = w / kLanes;  // elements per row
  uint v = e / row;

  // The occlusion veto looks at rows v - k for k = 1 .. min(occ_rows, v).
  uint rows_above = min(p.occ_rows, v);
  uvec4 occluded = uvec4(0u);
  uvec4 c = ClassAt(e);
  if (rows_above != 0u) {
    vec4 r = RangeAt(e);
    precise vec4 rr = r * r;
    precise vec4 grade = p.occ_grade * rr;
    precise vec4 near = r + p.occ_margin;
    precise vec4 any = near + grade;
    precise vec4 front = r + p.occ_front;
    vec4 reach = mix(any, min(any, front), equal(c, uvec4(kPixGround)));
    vec4 z = HeightAt(e);
    precise vec4 top = exact_Ftz0(z + p.occ_rise);  // as the reference: may flush
    precise vec4 pass = exact_Ftz0(p.occ_pass * r);
    uvec4 ground = uvec4(equal(c, uvec4(kPixGround)));
    for (uint k = 1u; k <= rows_above; ++k) {
      uint above = e - k * row;
      vec4 ra = RangeAt(above);
      precise vec4 d = exact_Ftz0(ra - r);
      precise vec4 clearance = exact_Ftz0(z * d);
      uvec4 passed = ground & uvec4(lessThan(d, vec4(0.0))) &
                     uvec4(greaterThanEqual(clearance, pass));
      occluded |= uvec4(notEqual(FilledAt(above), uvec4(0u))) & uvec4(lessThan(ra, reach)) &
                  uvec4(greaterThan(HeightAt(above), top)) & (passed ^ uvec4(1u));
    }
    // A step in the ground (a curb, a bank) spares the pixel.
    uint step_rows = min(p.occ_step_rows, v);
    if (step_rows != 0u) {
      precise vec4 far = exact_Ftz0(r + p.occ_step_reach);
      precise vec4 base = exact_Ftz0(z + p.occ_step);
      uvec4 steep = uvec4(0u), landing = uvec4(0u);
      for (uint k = 1u; k <= step_rows; ++k) {
        uint above = e - k * row;
        vec4 ra = RangeAt(above);
        precise vec4 d = exact_Ftz0(ra - r);
        vec4 beyond = mix(vec4(0.0), d, greaterThan(d, vec4(0.0)));
        precise vec4 lift = exact_Ftz0(p.occ_step_grade * beyond);
        precise vec4 bound = exact_Ftz0(base + lift);
        uvec4 counts = uvec4(notEqual(FilledAt(above), uvec4(0u))) & uvec4(lessThan(ra, far));
        steep |= counts & uvec4(greaterThan(HeightAt(above), bound));
        landing |= counts & uvec4(equal(ClassAt(above), uvec4(kPixGround))) &
                uvec4(greaterThan(d, vec4(0.0)));
      }
      occluded &= (landing & (steep ^ uvec4(1u))) ^ uvec4(1u);
    }
  }

  // The coarse label of each pixel's winning point; kNoOpinion without one.
  uvec4 i = PointAt(e), opinion = uvec4(kNoOpinion);
  for (uint k = 0u; k < kLanes; ++k)
    if (i[k] != kNone) opinion[k] = uint(coarse[i[k]] != 0u);

  uvec4 agree = uvec4(equal(c, opinion)) |
                (uvec4(equal(c, uvec4(kPixUnknown))) & uvec4(equal(opinion, uvec4(kPixGround))));
  uvec4 unknown = mix(uvec4(kPixUnknownOff), uvec4(kPixUnknown), equal(opinion, uvec4(kPixGround)));
  uvec4 decided = agree & uvec4(notEqual(opinion, uvec4(kNoOpinion)));
  uvec4 vote = mix(unknown, opinion, notEqual(decided, uvec4(0u)));
  uvec4 vetoed = mix(uvec4(kPixVetoed), uvec4(kPixNonGround), equal(vote, uvec4(kPixNonGround)));
  uvec4 kept = mix(vote, vetoed, notEqual(occluded, uvec4(0u)));
  uvec4 fused = mix(kept, uvec4(kPixEmpty), equal(c, uvec4(kPixEmpty)));
  if (kQuad) pixel_fused4[e] = fused;
  else pixel_fused[e] = fused.x;
}
