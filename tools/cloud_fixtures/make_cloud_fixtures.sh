#!/usr/bin/env bash
# Makes the committed cloud-file fixtures, tests/data/clouds/, with writers that share no code with
# lpir-gseg's readers. One scan, written here by Python as an ASCII PCD and an ASCII PLY, is
# converted by
#   PCL 1.13 (Debian's pcl-tools, pcl_convert_pcd_ascii_binary) to
#     pcl_binary.pcd             DATA binary
#     pcl_binary_compressed.pcd  DATA binary_compressed (PCL's LZF, the fields stored one after
#                                another)
#   CloudCompare 2.11 (Debian's cloudcompare, command line, no display) to
#     cloudcompare.ply           binary little-endian, the intensity as CloudCompare names a
#                                scalar field: scalar_Intensity
# The scan: an organised 16 x 40 grid (HEIGHT 16 rings, WIDTH 40 columns, 9 degrees apart) of a
# VLP-16-like sensor 1.7 m above flat ground with a wall 12 m ahead, every 37th point from the 5th
# a no-return (NaN; the PLY leaves those points out), fields x y z intensity (float32), ring
# (uint16), time (float64) and normal (float32 x 3, COUNT 3) in the PCD: sizes 1, 2, 4 and 8, a
# multi-count field, values LZF finds runs in (normals, rings) and values it does not
# (coordinates). PCL's files come out byte for byte the same on every run; CloudCompare's differ
# in the date of their "comment Created" line.
# usage: tools/cloud_fixtures/make_cloud_fixtures.sh [OUT_DIR]   (default tests/data/clouds)
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
out="${1:-${root}/tests/data/clouds}"
say() { echo "[make_cloud_fixtures] $*"; }
die() { say "error: $*" >&2; exit 1; }

command -v pcl_convert_pcd_ascii_binary > /dev/null ||
  die "needs pcl_convert_pcd_ascii_binary (Debian: apt-get install --no-install-recommends pcl-tools)"
command -v CloudCompare > /dev/null ||
  die "needs CloudCompare (Debian: apt-get install --no-install-recommends cloudcompare)"

tmp="$(mktemp -d)"
trap 'rm -rf "${tmp}"' EXIT
mkdir -p "${out}"
/usr/bin/python3 - "${tmp}/scan.pcd" "${tmp}/scan.ply" << 'PY'
import math
import sys

rows, cols = 16, 40
pcd, ply = [], []
for ring in range(rows):
    elevation = math.radians(-15.0 + 2.0 * ring)
    for col in range(cols):
        azimuth = math.radians(9.0 * col)
        index = ring * cols + col
        intensity = (ring * 13 + col * 7) % 256
        time = col * 1e-4 + ring * 2.3e-6
        if index % 37 == 5:
            pcd.append(f"nan nan nan {intensity} {ring} {time:.9g} 0 0 1")
            continue
        # the ground 1.7 m below, or the wall at x = 12 when the ray reaches it first
        reach = 1.7 / -math.sin(elevation) if elevation < 0 else math.inf
        ahead = math.cos(elevation) * math.cos(azimuth)
        if ahead > 0 and 12.0 / ahead < reach:
            reach = 12.0 / ahead
        reach = min(reach, 100.0)
        x = f"{reach * math.cos(elevation) * math.cos(azimuth):.6g}"
        y = f"{reach * math.cos(elevation) * math.sin(azimuth):.6g}"
        z = f"{reach * math.sin(elevation):.6g}"
        pcd.append(f"{x} {y} {z} {intensity} {ring} {time:.9g} 0 0 1")
        ply.append(f"{x} {y} {z} {intensity}")
with open(sys.argv[1], "w") as f:
    f.write("# .PCD v0.7 - Point Cloud Data file format\nVERSION 0.7\n"
            "FIELDS x y z intensity ring time normal\nSIZE 4 4 4 4 2 8 4\nTYPE F F F F U F F\n"
            f"COUNT 1 1 1 1 1 1 3\nWIDTH {cols}\nHEIGHT {rows}\nVIEWPOINT 0 0 0 1 0 0 0\n"
            f"POINTS {rows * cols}\nDATA ascii\n" + "\n".join(pcd) + "\n")
with open(sys.argv[2], "w") as f:  # the property name CloudCompare keeps as its field's name
    f.write(f"ply\nformat ascii 1.0\nelement vertex {len(ply)}\nproperty float x\n"
            "property float y\nproperty float z\nproperty float Intensity\nend_header\n" +
            "\n".join(ply) + "\n")
PY
pcl_convert_pcd_ascii_binary "${tmp}/scan.pcd" "${out}/pcl_binary.pcd" 1 > /dev/null
pcl_convert_pcd_ascii_binary "${tmp}/scan.pcd" "${out}/pcl_binary_compressed.pcd" 2 > /dev/null
grep -aq '^DATA binary_compressed$' "${out}/pcl_binary_compressed.pcd" ||
  die "PCL did not write DATA binary_compressed"
(cd "${tmp}" && QT_QPA_PLATFORM=offscreen CloudCompare -SILENT -AUTO_SAVE OFF -O scan.ply \
  -C_EXPORT_FMT PLY -PLY_EXPORT_FMT BINARY_LE -SAVE_CLOUDS FILE cloudcompare.ply > cc.log) ||
  die "CloudCompare failed: $(tail -3 "${tmp}/cc.log")"
grep -aq '^property float scalar_Intensity$' "${tmp}/cloudcompare.ply" ||
  die "CloudCompare did not write scalar_Intensity"
cp "${tmp}/cloudcompare.ply" "${out}/cloudcompare.ply"
say "done: $(du -sh "${out}" | cut -f1) in ${out}"
