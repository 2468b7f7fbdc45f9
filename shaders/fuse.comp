// Stage 7, fuse (paper III-D.2): the GPU twin of reference_cpu/fuse.cpp, same bytes.
// One invocation per pixel pix < pixels (push constant), row v = pix / width.
// In: binding 0 Params (uniform), 1 pixel_class, 2 pixel_point (kNone: no point), 3 coarse (per
//     point; any buffer of at least one element when there are no points), 4 pixel_filled,
//     5 f_range, 6 f_height (floats). Out: 7 pixel_fused (kPix*).
// Opinion: the coarse bit of the pixel's winning point, kPixUnknown where it has none.
// Occlusion veto over rows v - k, k = 1 .. min(occ_rows, v) of the same column: the pixel's
// bounds, each one rounded float op (`precise`, never an FMA), in this order: rr = r * r,
// grade = occ_grade * rr, near = r + occ_margin, reach = near + grade; top = z + occ_rise. An
// occluder: filled above != 0, range above < reach, height above > top (computed for every pixel,
// empty ones too, as the reference does; an empty pixel is empty whatever they say).
// Decision: agree = class == opinion, or class unknown and opinion ground; vote = agree ? opinion
// : unknown; kept = occluded ? non-ground : vote; fused = class empty ? empty : kept.
// No ties and no reductions: each pixel is its own invocation and reads only its inputs.
#version 450
#extension GL_GOOGLE_include_directive : require

#include "common/params.h"

layout(local_size_x_id = 0) in;

layout(std140, set = 0, binding = 0) uniform ParamsBlock { Params p; };
layout(std430, set = 0, binding = 1) readonly buffer PixelClass { uint pixel_class[]; };
layout(std430, set = 0, binding = 2) readonly buffer PixelPoint { uint pixel_point[]; };
layout(std430, set = 0, binding = 3) readonly buffer Coarse { uint coarse[]; };
layout(std430, set = 0, binding = 4) readonly buffer PixelFilled { uint pixel_filled[]; };
layout(std430, set = 0, binding = 5) readonly buffer Range { float f_range[]; };
layout(std430, set = 0, binding = 6) readonly buffer Height { float f_height[]; };
layout(std430, set = 0, binding = 7) writeonly buffer PixelFused { uint pixel_fused[]; };

layout(push_constant) uniform Push { uint pixels; } pc;

const uint kNone = 0xFFFFFFFFu;  // reference_cpu/frame.h
const uint kPixNonGround = 0u;
const uint kPixGround = 1u;
const uint kPixUnknown = 2u;
const uint kPixEmpty = 3u;
const uint kNoOpinion = kPixUnknown;

void main() {
  uint pix = gl_GlobalInvocationID.x;
  if (pix >= pc.pixels) return;
  uint w = p.width;
  uint v = pix / w;

  // The occlusion veto looks at rows v - k for k = 1 .. min(occ_rows, v).
  uint rows_above = min(p.occ_rows, v);
  uint occluded = 0u;
  if (rows_above != 0u) {
    float r = f_range[pix];
    precise float rr = r * r;
    precise float grade = p.occ_grade * rr;
    precise float near = r + p.occ_margin;
    precise float reach = near + grade;
    precise float top = f_height[pix] + p.occ_rise;
    for (uint k = 1u; k <= rows_above; ++k) {
      uint above = pix - k * w;
      occluded |= uint(pixel_filled[above] != 0u) & uint(f_range[above] < reach) &
                  uint(f_height[above] > top);
    }
  }

  // The coarse label of the pixel's winning point; kNoOpinion without one.
  uint i = pixel_point[pix];
  uint opinion = kNoOpinion;
  if (i != kNone) opinion = uint(coarse[i] != 0u);

  uint c = pixel_class[pix];
  uint agree = uint(c == opinion) | (uint(c == kPixUnknown) & uint(opinion == kPixGround));
  uint vote = agree != 0u ? opinion : kPixUnknown;
  uint kept = occluded != 0u ? kPixNonGround : vote;
  pixel_fused[pix] = c == kPixEmpty ? kPixEmpty : kept;
}
