#!/usr/bin/env bash
# Makes the committed recorded-drive fixtures, tests/data/drives/, with writers that share no code
# with lpir-gseg's readers (tools/drive_fixtures/: @mcap/core, @foxglove/rosmsg2-serialization,
# Python's sqlite3, Debian's python3-rosbag):
#   frames/00000{0,1,2}.bin   three simulated VLP-16 scans (`lpir-gseg simulate --sensor vlp16`,
#                             seeds 1-3, urban scene), the points within 22.5 degrees of straight
#                             ahead kept (an eighth of the turn, at full density, so that the
#                             segmenter still finds ground there; every 8th point finds none)
#   frames/00000{0,1,2}.ring  each point's ring (uint16 LE), its beam by elevation: VLP-16 beams
#                             lie 2 degrees apart from -15 (ring 0, the bottom, as the ROS
#                             Velodyne driver numbers them) to +15 (ring 15)
#   vlp16_{zstd,lz4,none}.mcap, vlp16.db3, vlp16_{bz2,lz4}.bag
#                             the three frames as sensor_msgs PointCloud2 on /velodyne_points,
#                             one message per chunk (tools/drive_fixtures/pointcloud.mjs and
#                             write_bag.py give the layout)
#   vlp16_full.{mcap,db3,bag} the same frames among an IMU's and a GNSS receiver's messages (and,
#                             in the MCAP, a metadata record and an attachment:
#                             tools/drive_fixtures/extras.mjs), chunks of about 64 KiB
#   narrow/00000{0,1,2}.{bin,ring}
#                             the same frames cut to the 11.25 degrees straight ahead (about 480
#                             points each): the drives of several files below stay small
#   vlp16_split_mcap/         a ROS 2 bag folder as `ros2 bag record` writes it: metadata.yaml
#                             (rosbag2's yaml-cpp text, Jazzy), vlp16_split_mcap_0.mcap (narrow
#                             frames 0 and 1) and _1.mcap (frame 2), zstd, a chunk per message
#   vlp16_split_db3/          the same as .db3 files, metadata.yaml as PyYAML dumps it (Humble)
#   vlp16_killed.bag.active   the narrow frames as a ROS 1 recorder killed while writing frame 2
#                             leaves them: frame 0's chunk closed, frames 1 and 2 in a chunk never
#                             finished, the file cut halfway through frame 2, no index
# usage: scripts/make_drive_fixtures.sh [OUT_DIR]   (default tests/data/drives)
# LPIR_CLI names the lpir-gseg binary (default build/lpir-gseg). Runs `npm ci` in
# tools/drive_fixtures when its node_modules is missing.
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
out="${1:-${root}/tests/data/drives}"
cli="${LPIR_CLI:-${root}/build/lpir-gseg}"
tools="${root}/tools/drive_fixtures"
python=/usr/bin/python3  # Debian's, which sees python3-rosbag
topic=/velodyne_points
say() { echo "[make_drive_fixtures] $*"; }
die() { say "error: $*" >&2; exit 1; }

[[ -x "${cli}" ]] || die "no lpir-gseg at ${cli} (build it, or set LPIR_CLI)"
# shellcheck source=tools/drive_fixtures/writers.sh
source "${tools}/writers.sh"
require_writers

tmp="$(mktemp -d)"
trap 'rm -rf "${tmp}"' EXIT
mkdir -p "${out}/frames"
frames=()
for i in 0 1 2; do
  name="$(printf '%06d' "${i}")"
  "${cli}" simulate --sensor vlp16 --seed "$((i + 1))" --out "${tmp}/${name}.bin" \
    --labels "${tmp}/${name}.label"
  "${python}" - "${tmp}/${name}.bin" "${out}/frames/${name}" << 'PY'
import sys
import numpy
points = numpy.fromfile(sys.argv[1], dtype="<f4").reshape(-1, 4)
azimuth = numpy.degrees(numpy.arctan2(points[:, 1].astype(numpy.float64), points[:, 0]))
points = points[numpy.abs(azimuth) <= 22.5]  # in sweep order, as simulated
points.tofile(sys.argv[2] + ".bin")
elevation = numpy.degrees(numpy.arctan2(points[:, 2].astype(numpy.float64),
                                        numpy.hypot(points[:, 0], points[:, 1])))
ring = numpy.clip(numpy.rint((elevation + 15.0) / 2.0), 0, 15).astype("<u2")
ring.tofile(sys.argv[2] + ".ring")
print(f"  {sys.argv[2]}.bin: {len(points)} points")
PY
  frames+=("${out}/frames/${name}.bin")
done

write_drives "${out}" vlp16 "${topic}" "${tmp}/cdr" 1 "${frames[@]}"
write_full_drives "${out}" vlp16 "${topic}" "${tmp}/full" "${frames[@]}"

mkdir -p "${out}/narrow"
narrow=()
for i in 0 1 2; do
  name="$(printf '%06d' "${i}")"
  "${python}" - "${out}/frames/${name}" "${out}/narrow/${name}" << 'PY'
import sys
import numpy
points = numpy.fromfile(sys.argv[1] + ".bin", dtype="<f4").reshape(-1, 4)
ring = numpy.fromfile(sys.argv[1] + ".ring", dtype="<u2")
azimuth = numpy.degrees(numpy.arctan2(points[:, 1].astype(numpy.float64), points[:, 0]))
keep = numpy.abs(azimuth) <= 5.625
points[keep].tofile(sys.argv[2] + ".bin")
ring[keep].tofile(sys.argv[2] + ".ring")
print(f"  {sys.argv[2]}.bin: {keep.sum()} points")
PY
  narrow+=("${out}/narrow/${name}.bin")
done
write_bag_folder "${out}" vlp16_split_mcap mcap rosbag2 "${topic}" "${tmp}/cdr" 2 "${narrow[@]}"
write_bag_folder "${out}" vlp16_split_db3 sqlite3 pyyaml "${topic}" "${tmp}/cdr" 2 "${narrow[@]}"
write_killed_bag "${out}/vlp16_killed.bag.active" "${topic}" "${narrow[@]}"
say "done: $(du -sh "${out}" | cut -f1) in ${out}"
