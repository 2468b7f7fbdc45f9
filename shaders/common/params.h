// Every threshold of the method, read by the shaders and the CPU reference alike. Valid GLSL and
// C++: scalars only (std430 pads vec3), no initialisers (defaults live in
// reference_cpu/params.cpp). Units: metres, counts in pixels/points. No parameter reads intensity:
// the method does not use it (docs/decisions/intensity.md).
#ifndef LPIR_SHADERS_COMMON_PARAMS_H_
#define LPIR_SHADERS_COMMON_PARAMS_H_

#ifdef __cplusplus
#include <cstdint>
namespace lpir {
using uint = uint32_t;
#endif

struct Params {
  // --- image (derived from the sensor profile) ---
  uint width;             // columns
  uint beams;             // rows
  uint ring_zero_is_top;  // 1 when the input ring index 0 is the top beam
  uint has_ring;  // 1 when the cloud carries ring indices (row = ring), else elevation table

  // --- stage 1 prepare (III-B.1, eq. 3) ---
  float min_range2;     // m^2, planar range^2 below which a point is invalid
  float max_range2;     // m^2, planar range^2 above which a point is invalid
  float k_xz;           // eq. 3 tilt slope along x
  float k_yz;           // eq. 3 tilt slope along y
  float h_noise;        // m, corrected height below which a point is reflection noise
  float sensor_height;  // m

  // --- stage 3 grid reduce (eq. 4) ---
  uint rings_near;      // rings of width ring_res_near up to near_radius
  uint rings_far;       // rings of width ring_res_far beyond it
  uint sectors_near;    // sectors per revolution in the near zone (divides width)
  uint sectors_far;     // sectors per revolution in the far zone (divides width)
  float ring_res_near;  // m, radial size of a near cell (res_r^c)
  float ring_res_far;   // m, radial size of a far cell (res_r^f)

  // --- stage 4 coarse segment (eqs. 5-7) ---
  float slope_max;    // xi_slope, the steepest ground grade (0.05-0.08)
  float seed_margin;  // m, sensor-noise margin added to lambda
  float h_athr;       // m, whole cell is seed when h_max - h_nmin <= h_athr (eq. 5)
  float
      rise_margin;  // m, a cell whose h_min rises more than this + slope above h_nmin has no seeds
  float plane_dist_floor;  // m, smallest point-to-plane threshold
  float plane_dist_scale;  // threshold = max(floor, scale * mean seed distance)
  float normal_min_z2;     // squared z-component a unit ground normal must keep (cos^2 of max tilt)
  float ground_max_above;  // m, a seed higher than -sensor_height + this + slope*r is not ground

  // --- stage 5 feature maps (III-D.1) ---
  float hole_gap;  // m, 1-pixel holes are filled when the two neighbours' ranges differ less

  // --- stage 6 classify pixels (eqs. 8-12) ---
  float t_edge;       // m, eq. 8
  float t_slope_low;  // eq. 9 (|dz|/|dr|, unitless)
  float t_slope_high;
  float t_stdz_low;  // m^2, eq. 10 (variance of height in the 3x3 window about its line in range)
  float t_stdz_high;
  // --- our addition: stages 6-8, banks (see classify_pixels.cpp and grow.cpp) ---
  float bank_slope;  // a non-ground pixel no steeper (dz/dr) than this and smoother than bank_rough
                     // is a bank: unknown, not non-ground, where the coarse label is non-ground;
                     // growing climbs to such a pixel up its column at this grade
  float bank_rough;  // m^2, the variance (as t_stdz_*) under which a bank is smooth

  // --- stage 8 grow (Alg. 1, IV-A) ---
  float grow_dz;       // m, height change of one growing step allowed at zero distance
  float grow_grade;    // ... plus this times the step's planar length (|dr|, + the nearer
                       // pixel's r * column_arc when the column changes)
  float column_arc;    // rad, one column (2 pi / width; set from the profile)
  uint min_component;  // ground components smaller than this (pixels) become non-ground

  // --- stage 9 back-project (III-D.2) ---
  float bp_range_gate;   // m, a non-winning point takes its pixel's label within this range
  float bp_height_gate;  // m, ... and within this height of the winner
  // --- our addition: stage 7 fuse, the occlusion veto (see fuse.cpp) ---
  uint occ_rows;     // rows above a pixel searched for an occluder (0 disables the veto)
  float occ_margin;  // m, an occluder is a pixel above that is nearer than range + this ...
  float occ_rise;    // m, ... and higher than the pixel by more than this
  float occ_grade;   // 1/m, ... + this * range^2 (flat ground's range step between beams grows
                     // as range^2 * beam spacing / sensor height)
  float occ_front;   // m, ... and, for a pixel whose class is ground, nearer than range + this (an
                     // object standing farther behind such a pixel leaves it ground)
  float occ_pass;  // m, ... and, for a pixel of class ground, not one its ray passed under with at
                   // least this clearance above the pixel's height (ground seen past an object)
  // --- our addition: stage 7 fuse, a step in the ground is not an occluder (see fuse.cpp) ---
  uint occ_step_rows;    // rows above an occluded pixel searched for the step's shape (0: none)
  float occ_step;        // m, the tallest step in the ground (a curb) that spares the pixel ...
  float occ_step_grade;  // ... plus this times how far beyond the pixel the pixel above lies
  float occ_step_reach;  // m, pixels above farther than range + this are not looked at
  // --- our addition: stage 8 grow, a small component of seeds stays ground (see grow.cpp) ---
  uint comp_seed_min;     // pixels: a component smaller than this is non-ground whatever it holds
  float comp_seed_share;  // a component under min_component stays ground when at least this share
                          // of its pixels are seeds (fused ground); above 1: never
  uint pad0, pad1;        // unused: the block is a whole number of vec4s
};

#ifdef __cplusplus
static_assert(sizeof(Params) % 16 == 0, "Params must be a whole number of vec4s");
}  // namespace lpir
#endif

#endif  // LPIR_SHADERS_COMMON_PARAMS_H_
