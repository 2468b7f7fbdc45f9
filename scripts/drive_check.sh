#!/usr/bin/env bash
# Recorded drives at full size, outside the suite (issue 20, done-when 1, 2 and 4): N simulated
# HDL-64E frames (`lpir-gseg simulate`, seeds 1..N, urban scene) kept as KITTI .bin files and
# written by the independent writers of tools/drive_fixtures/ as six drives: MCAP with zstd, lz4
# and none (@mcap/core), .db3 (sqlite3, CDR by @foxglove/rosmsg2-serialization), ROS 1 bag with
# bz2 and lz4 (python3-rosbag). The drives carry x y z intensity time, no ring: the .bin files
# have none, so both inputs hold the same points.
#   1. `segment --backend cpu` on the .bin folder and on each drive; the drive's .label files,
#      in natural name order, must equal the .bin folder's, in name order, byte for byte (cmp).
#   2. `segment --format mcap` on the zstd MCAP, read back by read_mcap.mjs (@mcap/core): every
#      record of the input as it was, TOPIC/labelled, TOPIC/ground and TOPIC/nonground with N
#      messages each, fields aligned, every label equal to step 1's; and `segment --format bag`
#      on the lz4 bag, read back by read_bag.py (python3-rosbag) the same way.
#   3. Time per frame (the whole command's time / N), as wall time and as CPU time (user + sys,
#      which other jobs on the machine disturb less): 3 runs of the .bin folder and of each drive
#      taken in turns; the medians and each drive's ratio to the .bin folder's (goal <= 1.10).
# Exits non-zero on any mismatch or failed command (a ratio over 1.10 is printed, not fatal: the
# machine's load moves it).
# usage: scripts/drive_check.sh [N]   (default 50). LPIR_CLI names lpir-gseg (default
# build/lpir-gseg); LPIR_DRIVE_CHECK_DIR keeps the work folder (default: a temporary one, removed).
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
frames="${1:-50}"
cli="${LPIR_CLI:-${root}/build/lpir-gseg}"
tools="${root}/tools/drive_fixtures"
python=/usr/bin/python3  # Debian's, which sees python3-rosbag
topic=/points
sensor=hdl64e
kinds=(zstd.mcap lz4.mcap none.mcap db3 bz2.bag lz4.bag)
say() { echo "[drive_check] $*"; }
die() { say "error: $*" >&2; exit 1; }

[[ "${frames}" =~ ^[1-9][0-9]*$ ]] || die "N must be a positive integer, got '${frames}'"
[[ -x "${cli}" ]] || die "no lpir-gseg at ${cli} (build it, or set LPIR_CLI)"
# shellcheck source=tools/drive_fixtures/writers.sh
source "${tools}/writers.sh"
require_writers
if [[ -n "${LPIR_DRIVE_CHECK_DIR:-}" ]]; then
  work="${LPIR_DRIVE_CHECK_DIR}"
  mkdir -p "${work}"
else
  work="$(mktemp -d)"
  trap 'rm -rf "${work}"' EXIT
fi

say "simulating ${frames} ${sensor} frames in ${work}/bin"
rm -rf "${work:?}/bin" "${work:?}/drives" "${work:?}/out"
mkdir -p "${work}/bin" "${work}/drives" "${work}/out"
bins=()
for ((i = 0; i < frames; ++i)); do
  name="$(printf '%06d' "${i}")"
  "${cli}" simulate --sensor "${sensor}" --seed "$((i + 1))" --out "${work}/bin/${name}.bin" \
    --labels "${work}/${name}.truth" > /dev/null
  rm -f "${work}/${name}.truth"
  bins+=("${work}/bin/${name}.bin")
done

say "writing the six drives"
write_drives "${work}/drives" drive "${topic}" "${work}/cdr" 0 "${bins[@]}"
drive_path() {  # kind -> file
  local kind="$1"
  case "${kind}" in
    db3) echo "${work}/drives/drive.db3" ;;
    *) echo "${work}/drives/drive_${kind}" ;;
  esac
}

# One timed segment run: its wall and CPU (user + sys) times in ms appended to wall[$1] and
# cpu[$1]. $2 the output folder, the rest its inputs.
declare -A wall cpu
run_segment() {
  local key="$1" out="$2"
  shift 2
  rm -rf "${out}"
  local TIMEFORMAT='%3R %3U %3S' line
  { time "${cli}" segment "$@" --sensor "${sensor}" --out "${out}" --backend cpu --quiet; } \
    2> "${work}/time.txt" || { cat "${work}/time.txt" >&2; die "segment $* failed"; }
  line="$(tail -n 1 "${work}/time.txt")"
  wall[${key}]+=" $(awk -v r="${line%% *}" 'BEGIN { printf "%d", r * 1000 }')"
  cpu[${key}]+=" $(echo "${line}" | awk '{ printf "%d", ($2 + $3) * 1000 }')"
}

median3() { printf '%s\n' "$@" | sort -n | sed -n 2p; }

say "timing: 3 runs each of the .bin folder and the six drives, in turns"
for _ in 1 2 3; do
  run_segment bin "${work}/out/bin" "${work}/bin"
  for kind in "${kinds[@]}"; do
    run_segment "${kind}" "${work}/out/${kind}" "$(drive_path "${kind}")" --topic "${topic}"
  done
done

# Labels: the .bin folder's in name order against each drive's in natural name order.
mapfile -t bin_labels < <(find "${work}/out/bin" -maxdepth 1 -name '*.label' -printf '%f\n' | sort)
[[ ${#bin_labels[@]} -eq ${frames} ]] || die "the .bin folder gave ${#bin_labels[@]} .label files, not ${frames}"
mismatch=0
for kind in "${kinds[@]}"; do
  mapfile -t drive_labels < <(find "${work}/out/${kind}" -maxdepth 1 -name '*.label' -printf '%f\n' | sort -V)
  if [[ ${#drive_labels[@]} -ne ${frames} ]]; then
    say "MISMATCH ${kind}: ${#drive_labels[@]} .label files, not ${frames}"
    mismatch=1
    continue
  fi
  same=0
  for ((i = 0; i < frames; ++i)); do
    if cmp -s "${work}/out/bin/${bin_labels[i]}" "${work}/out/${kind}/${drive_labels[i]}"; then
      same=$((same + 1))
    else
      say "MISMATCH ${kind}: ${drive_labels[i]} differs from ${bin_labels[i]}"
      mismatch=1
    fi
  done
  say "labels ${kind}: ${same}/${frames} frames equal to the .bin folder's, byte for byte"
done

say "--format mcap on the zstd MCAP and --format bag on the lz4 bag, read back by @mcap/core and rosbag"
clouds=()
for suffix in labelled ground nonground; do clouds+=(--expect "${topic}/${suffix}:${frames}"); done
for kind in zstd.mcap lz4.bag; do
  format="${kind##*.}"
  rm -rf "${work}/out/${format}"
  "${cli}" segment "$(drive_path "${kind}")" --topic "${topic}" --sensor "${sensor}" \
    --out "${work}/out/${format}" --backend cpu --format "${format}" --quiet ||
    die "segment --format ${format} failed"
  mapfile -t outputs < <(find "${work}/out/${format}" -name "*.${format}")
  [[ ${#outputs[@]} -eq 1 ]] || die "segment --format ${format} wrote ${#outputs[@]} files, not 1"
  if [[ "${format}" == mcap ]]; then
    reader=(node "${tools}/read_mcap.mjs")
  else
    reader=("${python}" "${tools}/read_bag.py")
  fi
  if "${reader[@]}" "${outputs[0]}" --input "$(drive_path "${kind}")" "${clouds[@]}" \
    --labels "${work}/out/bin"; then
    say "--format ${format}: read back whole, labels equal to the .bin folder's"
  else
    say "MISMATCH --format ${format}: ${reader[*]} failed on ${outputs[0]}"
    mismatch=1
  fi
done

say "time per frame (median of 3, --backend cpu, ${frames} frames; load $(cut -d' ' -f1-3 /proc/loadavg)):"
for clock in wall cpu; do
  declare -n times="${clock}"
  # shellcheck disable=SC2086  # the lists of times are meant to split
  bin_ms="$(median3 ${times[bin]})"
  for kind in bin "${kinds[@]}"; do
    # shellcheck disable=SC2086
    ms="$(median3 ${times[${kind}]})"
    awk -v clock="${clock}" -v kind="${kind}" -v ms="${ms}" -v bin="${bin_ms}" -v n="${frames}" \
      -v runs="${times[${kind}]}" 'BEGIN {
        r = ms / bin
        verdict = kind == "bin" ? "" : sprintf("ratio %.3f %s", r, r <= 1.10 ? "ok" : "OVER 1.10")
        printf "[drive_check]   %-4s %-10s %8.2f ms/frame  %-21s runs:%s ms\n", clock, kind,
               ms / n, verdict, runs }'
  done
  unset -n times
done
[[ ${mismatch} -eq 0 ]] || die "labels differ (see MISMATCH above)"
say "every drive's labels equal the .bin folder's"
