#!/usr/bin/env bash
# scripts/sensitivity.sh: the DG F1 change, PP F1 and the share of car points labelled ground
# (summed over the eight labelled KITTI frames) when each main threshold of the hdl64e profile is
# set 25 % below and 25 % above its default (whole-number ones rounded down), one at a time, as a
# markdown table (docs/accuracy.md, "No knife edge").
# Needs build/attribute (scripts/build.sh attribute) and ../shared/data (or LPIR_DATA_DIR).
set -euo pipefail
cd "$(dirname "$0")/.."
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

# name default: the defaults of reference_cpu/params.cpp that the hdl64e profile keeps.
params=(
  "slope_max 0.10" "seed_margin 0.06" "h_athr 0.12" "rise_margin 0.3" "plane_dist_floor 0.1"
  "plane_dist_scale 2.5" "ground_max_above 0.3" "hole_gap 0.25" "t_edge 0.12"
  "t_slope_low 0.09" "t_slope_high 0.25" "t_stdz_low 0.000025" "t_stdz_high 0.000144"
  "bank_slope 0.8" "bank_rough 0.01"
  "grow_dz 0.03" "min_component 300"
  "bp_range_gate 0.15" "bp_height_gate 0.2" "occ_margin 0.3" "occ_rise 0.045"
  "occ_grade 0.0002" "occ_front 0.1" "occ_pass 0.15" "occ_step_rows 10" "occ_step 0.15" "occ_step_grade 0.1"
  "occ_step_reach 3" "comp_seed_min 10" "comp_seed_share 0.8")

read -r base base_pp base_car <<<"$(scores)"
echo "Defaults: DG F1 $base, PP F1 $base_pp, car points labelled ground $base_car % (summed over ${frames[*]})."
echo
echo "| parameter | default | DG F1 at -25 % | DG F1 at +25 % | change -25 % / +25 % | PP F1 -25 % / +25 % | car % -25 % / +25 % |"
echo "|---|---|---|---|---|---|---|"
for entry in "${params[@]}"; do
  read -r name value <<<"$entry"
  lo=$(awk -v v="$value" -v n="$name" 'BEGIN { x = v * 0.75; if (n ~ /^(min_component|occ_step_rows|comp_seed_min)$/) x = int(x); print x }')
  hi=$(awk -v v="$value" -v n="$name" 'BEGIN { x = v * 1.25; if (n ~ /^(min_component|occ_step_rows|comp_seed_min)$/) x = int(x); print x }')
  read -r a a_pp a_car <<<"$(scores --param "$name" "$lo")"
  read -r b b_pp b_car <<<"$(scores --param "$name" "$hi")"
  awk -v n="$name" -v v="$value" -v a="$a" -v b="$b" -v base="$base" -v ap="$a_pp" -v bp="$b_pp" \
    -v ac="$a_car" -v bc="$b_car" \
    'BEGIN { printf "| %s | %s | %.2f | %.2f | %+.2f / %+.2f | %.2f / %.2f | %.2f / %.2f |\n", n, v, a, b, a - base, b - base, ap, bp, ac, bc }'
done
