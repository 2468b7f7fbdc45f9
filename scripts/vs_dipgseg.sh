#!/usr/bin/env bash
# The whole process against DipG-Seg's (issue 31, docs/speed.md "Against DipG-Seg, the whole
# process"): `lpir-gseg segment --backend cpu` and `dipgseg_driver --repeats 0` (its defaults,
# built -O3 by ../shared/peers/build.sh; one labelled call per frame, reading and writing
# included) over the same 30 KITTI frames (the six kitti/00 scans five times over, as copies
# named r<round>_<scan>.bin in a temporary folder: segment refuses two links to one file), wall time of each process from start to exit.
# Two settings: both cores (no affinity set) and pinned to one core (taskset -c 0). Runs are taken
# in turns (lpir-gseg, DipG-Seg, lpir-gseg, ...; within a run both settings in turn too), after
# one untimed warm-up of each (page cache), so that a spell of load on a shared machine falls on
# both alike. Prints the medians, their ratio, the median of each run's own ratio, and the load
# average before and after.
#   scripts/vs_dipgseg.sh [RUNS (default 9)] [extra lpir-gseg segment options, e.g. --threads 1]
# Environment: LPIR_BUILD_DIR (default ./build: its lpir-gseg), LPIR_DATA_DIR (default
# ../shared/data), PEERS_BIN (default /tmp/peers/bin; built there when missing, which needs
# MIRROR, see ../shared/peers/build.sh).
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
runs="${1:-9}"
shift || true
cli="${LPIR_BUILD_DIR:-${root}/build}/lpir-gseg"
data="${LPIR_DATA_DIR:-${root}/../shared/data}"
peers="${PEERS_BIN:-/tmp/peers/bin}"
scans="${data}/kitti/00/velodyne"

[[ -x "${cli}" ]] || { echo "vs_dipgseg: no ${cli} (build first: scripts/build.sh)" >&2; exit 1; }
[[ -d "${scans}" ]] || { echo "vs_dipgseg: no ${scans}: the KITTI scans are needed" >&2; exit 1; }
command -v taskset > /dev/null || { echo "vs_dipgseg: taskset (util-linux) is needed" >&2; exit 1; }
if [[ ! -x "${peers}/dipgseg_driver" ]]; then
  echo "vs_dipgseg: building the peers into $(dirname "${peers}")" >&2
  "${root}/../shared/peers/build.sh" "$(dirname "${peers}")" >&2
fi

work="$(mktemp -d)"
trap 'rm -rf "${work}"' EXIT
mkdir -p "${work}/in" "${work}/lpir" "${work}/dipg"
for round in 1 2 3 4 5; do
  for scan in "${scans}"/*.bin; do
    cp "${scan}" "${work}/in/r${round}_$(basename "${scan}")"
  done
done

python3 - "${runs}" "${cli}" "${peers}/dipgseg_driver" "${work}" "$@" << 'EOF'
import os, statistics, subprocess, sys, time

runs, cli, dipg, work = int(sys.argv[1]), sys.argv[2], sys.argv[3], sys.argv[4]
extra = sys.argv[5:]
files = sorted(os.path.join(work, "in", f) for f in os.listdir(os.path.join(work, "in")))
lpir = [cli, "segment", os.path.join(work, "in"), "--sensor", "hdl64e", "--backend", "cpu",
        "--out", os.path.join(work, "lpir"), "--quiet"] + extra
peer = [dipg, "--repeats", "0", "--out", os.path.join(work, "dipg")] + files
settings = {"both cores": [], "pinned to one core": ["taskset", "-c", "0"]}

def wall(cmd):
    t0 = time.perf_counter()
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
    return time.perf_counter() - t0

for prefix in settings.values():  # warm-up: page cache, dynamic loader
    wall(prefix + lpir), wall(prefix + peer)
times = {(s, who): [] for s in settings for who in ("lpir", "dipg")}
load_before = os.getloadavg()[0]
for _ in range(runs):
    for s, prefix in settings.items():
        times[(s, "lpir")].append(wall(prefix + lpir))
        times[(s, "dipg")].append(wall(prefix + peer))
load_after = os.getloadavg()[0]
labels = len(os.listdir(os.path.join(work, "lpir")))
print(f"{len(files)} frames, {runs} runs in turns, lpir-gseg options: "
      f"{' '.join(extra) or '(defaults)'}; load average {load_before:.2f} before, "
      f"{load_after:.2f} after; {labels} label files written")
print("| | lpir-gseg `segment --backend cpu` | DipG-Seg | ratio | paired ratio |")
print("|---|---|---|---|---|")
for s in settings:
    a = statistics.median(times[(s, "lpir")])
    b = statistics.median(times[(s, "dipg")])
    # Each run's two processes ran back to back: the median of their ratios cancels a spell of
    # load that falls on one run, where the ratio of the medians does not.
    paired = statistics.median(x / y for x, y in zip(times[(s, "lpir")], times[(s, "dipg")]))
    print(f"| {s} | {a:.3f} s | {b:.3f} s | {a / b:.2f} | {paired:.2f} |")
for s in settings:
    for who in ("lpir", "dipg"):
        print(f"  {s}, {who}: " + " ".join(f"{t:.3f}" for t in sorted(times[(s, who)])))
EOF
