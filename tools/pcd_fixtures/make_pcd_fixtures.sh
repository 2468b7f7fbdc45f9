#!/usr/bin/env bash
# Makes the committed PCD fixtures, tests/data/pcd/, with PCL, which shares no code with
# lpir-gseg's reader: Debian's pcl-tools (`pcl_convert_pcd_ascii_binary`, PCL 1.13) converts one
# ASCII PCD, written here by Python, to
#   pcl_binary.pcd             DATA binary
#   pcl_binary_compressed.pcd  DATA binary_compressed (PCL's LZF, the fields stored one after
#                              another)
# The cloud: an organised 16 x 40 scan (HEIGHT 16 rings, WIDTH 40 columns, 9 degrees apart) of a
# VLP-16-like sensor 1.7 m above flat ground with a wall 12 m ahead, every 37th point a no-return
# (NaN), fields x y z intensity (float32), ring (uint16), time (float64) and normal (float32 x 3,
# COUNT 3): sizes 1, 2, 4 and 8, a multi-count field, values that LZF finds runs in (normals,
# rings) and values it does not (coordinates).
# usage: tools/pcd_fixtures/make_pcd_fixtures.sh [OUT_DIR]   (default tests/data/pcd)
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
out="${1:-${root}/tests/data/pcd}"
say() { echo "[make_pcd_fixtures] $*"; }
die() { say "error: $*" >&2; exit 1; }

command -v pcl_convert_pcd_ascii_binary > /dev/null ||
  die "needs pcl_convert_pcd_ascii_binary (Debian: apt-get install --no-install-recommends pcl-tools)"

tmp="$(mktemp -d)"
trap 'rm -rf "${tmp}"' EXIT
mkdir -p "${out}"
/usr/bin/python3 - "${tmp}/scan.pcd" << 'PY'
import math
import sys

rows, cols = 16, 40
lines = []
for ring in range(rows):
    elevation = math.radians(-15.0 + 2.0 * ring)
    for col in range(cols):
        azimuth = math.radians(9.0 * col)
        index = ring * cols + col
        if index % 37 == 5:
            x = y = z = "nan"
        else:
            # the ground 1.7 m below, or the wall at x = 12 when the ray reaches it first
            reach = 1.7 / -math.sin(elevation) if elevation < 0 else math.inf
            ahead = math.cos(elevation) * math.cos(azimuth)
            if ahead > 0 and 12.0 / ahead < reach:
                reach = 12.0 / ahead
            reach = min(reach, 100.0)
            x = f"{reach * math.cos(elevation) * math.cos(azimuth):.6g}"
            y = f"{reach * math.cos(elevation) * math.sin(azimuth):.6g}"
            z = f"{reach * math.sin(elevation):.6g}"
        intensity = (ring * 13 + col * 7) % 256
        time = col * 1e-4 + ring * 2.3e-6
        lines.append(f"{x} {y} {z} {intensity} {ring} {time:.9g} 0 0 1")
header = (
    "# .PCD v0.7 - Point Cloud Data file format\nVERSION 0.7\n"
    "FIELDS x y z intensity ring time normal\nSIZE 4 4 4 4 2 8 4\nTYPE F F F F U F F\n"
    f"COUNT 1 1 1 1 1 1 3\nWIDTH {cols}\nHEIGHT {rows}\nVIEWPOINT 0 0 0 1 0 0 0\n"
    f"POINTS {rows * cols}\nDATA ascii\n")
with open(sys.argv[1], "w") as f:
    f.write(header + "\n".join(lines) + "\n")
PY
pcl_convert_pcd_ascii_binary "${tmp}/scan.pcd" "${out}/pcl_binary.pcd" 1 > /dev/null
pcl_convert_pcd_ascii_binary "${tmp}/scan.pcd" "${out}/pcl_binary_compressed.pcd" 2 > /dev/null
grep -aq '^DATA binary_compressed$' "${out}/pcl_binary_compressed.pcd" ||
  die "PCL did not write DATA binary_compressed"
say "done: $(du -sh "${out}" | cut -f1) in ${out}"
