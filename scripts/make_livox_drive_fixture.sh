#!/usr/bin/env bash
# Makes the committed Livox drive fixture, tests/data/drives/livox/, with the independent MCAP
# writer of tools/drive_fixtures/ (@mcap/core, @foxglove/rosmsg2-serialization; no lpir-gseg code):
#   00000{0,1}.bin   two simulated Mid-70 frames (`lpir-gseg simulate --sensor mid70`, seeds 1 and
#                    2: consecutive 100 ms frames of the rosette, urban scene), whole
#   mid70.mcap       the two frames as sensor_msgs/PointCloud2 on /livox/lidar, frame_id
#                    livox_frame, in livox_ros_driver2's layout (x y z intensity float32, tag
#                    uint8, line uint8, timestamp float64, point_step 26:
#                    tools/drive_fixtures/pointcloud.mjs), zstd, one message per chunk
# usage: scripts/make_livox_drive_fixture.sh [OUT_DIR]   (default tests/data/drives/livox)
# LPIR_CLI names the lpir-gseg binary (default build/lpir-gseg). Runs `npm ci` in
# tools/drive_fixtures when its node_modules is missing.
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
out="${1:-${root}/tests/data/drives/livox}"
cli="${LPIR_CLI:-${root}/build/lpir-gseg}"
tools="${root}/tools/drive_fixtures"
python=/usr/bin/python3  # Debian's, which sees python3-rosbag (require_writers checks it)
say() { echo "[make_livox_drive_fixture] $*"; }
die() { say "error: $*" >&2; exit 1; }

[[ -x "${cli}" ]] || die "no lpir-gseg at ${cli} (build it, or set LPIR_CLI)"
# shellcheck source=tools/drive_fixtures/writers.sh
source "${tools}/writers.sh"
require_writers

tmp="$(mktemp -d)"
trap 'rm -rf "${tmp}"' EXIT
mkdir -p "${out}"
frames=()
for i in 0 1; do
  name="$(printf '%06d' "${i}")"
  "${cli}" simulate --sensor mid70 --seed "$((i + 1))" --out "${out}/${name}.bin" \
    --labels "${tmp}/${name}.label"
  frames+=("${out}/${name}.bin")
done
node "${tools}/write_mcap.mjs" --out "${out}/mid70.mcap" --compression zstd \
  --topic /livox/lidar --frame-id livox_frame --layout livox --chunk-size 1 "${frames[@]}"
say "done: $(du -sh "${out}" | cut -f1) in ${out}"
