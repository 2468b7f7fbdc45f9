#!/usr/bin/env bash
# scripts/sensitivity.sh: the DG F1 change, PP F1 and the share of car points labelled ground
# (summed over the eight labelled KITTI frames) when each main threshold of the hdl64e profile is
# set 25 % below and 25 % above its default (whole-number ones rounded down), one at a time, as a
# markdown table (docs/accuracy.md, "No knife edge"). The thresholds are the rows of
# shaders/common/params.def marked swept; `--list` prints them ("name default type") and stops.
# Needs build/attribute (scripts/build.sh attribute) and ../shared/data (or LPIR_DATA_DIR).
set -euo pipefail
cd "$(dirname "$0")/.."

# "name default type" of every swept row: the first line of each LPIR_PARAM row holds
# stage, type, name, default, unit, swept; the default loses its float suffix.
params=()
while read -r name value type; do
  params+=("$name $value $type")
done < <(sed -n 's/^LPIR_PARAM(\([^,]*\), *\([^,]*\), *\([^,]*\), *\([^,]*\), *"[^"]*", *1,.*/\3 \4 \2/p' \
  shaders/common/params.def | sed 's/^\([^ ]*\) \([-0-9.e]*\)f /\1 \2 /')
if [[ ${1:-} == --list ]]; then
  printf '%s\n' "${params[@]}"
  exit 0
fi

data=${LPIR_DATA_DIR:-../shared/data}
tool=${LPIR_BUILD_DIR:-build}/attribute
frames=(07/000964 unknown/000056 00/000000 00/000001 00/000002 sglc/000052 sglc/000088
  sglc/004501)
scans=()
for f in "${frames[@]}"; do
  scans+=("$data/kitti/${f%/*}/velodyne/${f#*/}.bin" "$data/kitti/${f%/*}/labels/${f#*/}.label")
done

# "DG-F1 PP-F1 car-%" of the summed line, with the given extra arguments.
scores() {
  "$tool" --sensor hdl64e "$@" "${scans[@]}" |
    sed -n 's/^summed: P [0-9.]* R [0-9.]* F1 \([0-9.]*\) | PP F1 \([0-9.]*\) | car points labelled ground \([0-9.]*\).*/\1 \2 \3/p'
}

read -r base base_pp base_car <<<"$(scores)"
echo "Defaults: DG F1 $base, PP F1 $base_pp, car points labelled ground $base_car % (summed over ${frames[*]})."
echo
echo "| parameter | default | DG F1 at -25 % | DG F1 at +25 % | change -25 % / +25 % | PP F1 -25 % / +25 % | car % -25 % / +25 % |"
echo "|---|---|---|---|---|---|---|"
for entry in "${params[@]}"; do
  read -r name value type <<<"$entry"
  lo=$(awk -v v="$value" -v t="$type" 'BEGIN { x = v * 0.75; if (t == "uint") x = int(x); print x }')
  hi=$(awk -v v="$value" -v t="$type" 'BEGIN { x = v * 1.25; if (t == "uint") x = int(x); print x }')
  read -r a a_pp a_car <<<"$(scores --param "$name" "$lo")"
  read -r b b_pp b_car <<<"$(scores --param "$name" "$hi")"
  awk -v n="$name" -v v="$value" -v a="$a" -v b="$b" -v base="$base" -v ap="$a_pp" -v bp="$b_pp" \
    -v ac="$a_car" -v bc="$b_car" \
    'BEGIN { printf "| %s | %s | %.2f | %.2f | %+.2f / %+.2f | %.2f / %.2f | %.2f / %.2f |\n", n, v, a, b, a - base, b - base, ap, bp, ac, bc }'
done
