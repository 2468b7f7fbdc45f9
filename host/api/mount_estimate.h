// The mount of a sensor whose height and tilt the user does not know (profile key `mount
// per_frame`): the ground plane of each cloud, fitted on the host to the lowest point of each
// ground-sized cell before the frame is staged, so that both backends get the same Params
// (docs/decisions/mount.md).
#pragma once
#include <cstddef>
#include <cstdint>

#include "reference_cpu/cloud.h"
#include "reference_cpu/params.h"
#include "reference_cpu/sensor.h"

namespace lpir {

// Cells of kMountCell x kMountCell m in the sensor's x-y plane, within kMountReach m planar
// range: small enough that most hold ground, large enough that the lowest point of one is
// ground rather than the underside of an object.
constexpr double kMountCell = 2.0;
constexpr double kMountReach = 40.0;
// The fewest cells the final fit keeps, and the steepest tilt and the heights it may return:
// beyond them the cloud shows too little ground, and the profile's mount is used.
constexpr size_t kMountMinCells = 8;
constexpr double kMountMaxTilt = 0.5;  // |k_xz|, |k_yz|: about 27 degrees
// RANSAC over the cells: tries, the inlier band (m, vertical) and the generator's seed. The band
// is wide enough to hold gently curved terrain in one plane (a narrower one jumps between parts
// of it from frame to frame), narrow enough to leave out most reflection noise.
constexpr uint32_t kMountTries = 256;
constexpr double kMountInlier = 0.3;
constexpr uint32_t kMountSeed = 0x6A0D5EEDu;
constexpr double kMountMinHeight = 0.1, kMountMaxHeight = 50.0;  // m

struct MountEstimate {
  Mount mount;             // the fit, or the fallback when !estimated
  bool estimated = false;  // false: too little ground (see the constants above)
  size_t cells = 0;        // cells holding a point, and those the final fit kept
  size_t kept = 0;
};

// In: the cloud, the profile (its min_range and max_range select the points) and the mount to
// return when the cloud shows too little ground. Operations, in order:
//   1. every finite point, not (0, 0, 0), with planar range in [min_range, min(max_range,
//      kMountReach)]: the lowest (smallest z; the first in index order on ties) of its cell
//      (floor(x / kMountCell), floor(y / kMountCell));
//   2. RANSAC: kMountTries times, three cells drawn by std::mt19937(kMountSeed) (index =
//      output % cells; a draw repeating a cell is skipped) give the plane z = k_xz x + k_yz y - h
//      through their lowest points; among those within kMountMaxTilt, the first that the most
//      cells lie within kMountInlier of (vertically) wins. Reflection noise under the road and
//      the lowest points of walls fall outside it;
//   3. three times: least squares of that plane over the cells within kMountInlier of it
//      (double precision, normal equations);
//   4. the result is the mount when at least kMountMinCells cells lie within kMountInlier of it,
//      its tilts are within kMountMaxTilt and h within [kMountMinHeight, kMountMaxHeight]; else
//      the fallback is.
// Tilts under FLT_MIN in magnitude are 0 (no subnormal reaches a Params).
MountEstimate EstimateMount(const Cloud& cloud, const SensorProfile& sensor, const Mount& fallback);

// The mount a frame of `sensor` is segmented with, `params` being ParamsForSensor(sensor):
// MountOf(params) with `mount fixed`; with `mount per_frame`, EstimateMount's, MountOf(params)
// the fallback.
MountEstimate FrameMount(const Cloud& cloud, const SensorProfile& sensor, const Params& params);

}  // namespace lpir
