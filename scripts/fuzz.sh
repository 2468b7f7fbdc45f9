#!/usr/bin/env bash
# Runs one libFuzzer target of fuzz/ for SECONDS (default 600), building the fuzzers first with
# clang into <repo>/build-fuzz (or $LPIR_FUZZ_BUILD_DIR). New inputs accumulate in
# <build>/fuzz/long/TARGET (kept between runs, seeded from fuzz/corpus/TARGET); a finding is
# written to <build>/fuzz/artifacts/ and makes the script exit non-zero.
# Usage: scripts/fuzz.sh TARGET [SECONDS] [libFuzzer flags...]
#        TARGET: bag_metadata, db3, kitti_bin, label_file, mcap, pcd, ply, pointcloud2, ros1_bag,
#                sensor_profile
#                (scripts/fuzz.sh list)
# Reproduce a finding: <build>/fuzz/TARGET_fuzz <build>/fuzz/artifacts/TARGET-crash-...
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build_dir="${LPIR_FUZZ_BUILD_DIR:-${root}/build-fuzz}"
targets=(bag_metadata db3 kitti_bin label_file mcap pcd ply pointcloud2 ros1_bag sensor_profile)
say() { echo "[fuzz] $*"; }

target="${1:-}"
if [[ -z "${target}" || "${target}" == "list" || "${target}" == "-h" || "${target}" == "--help" ]]; then
  echo "usage: scripts/fuzz.sh TARGET [SECONDS] [libFuzzer flags...]; targets: ${targets[*]}"
  [[ -n "${target}" ]] && exit 0 || exit 2
fi
if [[ " ${targets[*]} " != *" ${target} "* ]]; then
  say "error: unknown target '${target}'; targets: ${targets[*]}" >&2
  exit 2
fi
seconds="${2:-600}"
shift $(( $# >= 2 ? 2 : 1 ))

if ! command -v clang++ > /dev/null 2>&1; then
  say "error: clang++ not found (Debian: apt-get install clang libclang-rt-14-dev)" >&2
  exit 1
fi
cmake -S "${root}" -B "${build_dir}" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_COMPILER=clang++ -DLPIR_FUZZ=ON > /dev/null
cmake --build "${build_dir}" --parallel "$(nproc 2> /dev/null || echo 2)" \
  --target "${target}_fuzz" > /dev/null

work="${build_dir}/fuzz/long/${target}"
artifacts="${build_dir}/fuzz/artifacts"
mkdir -p "${work}" "${artifacts}"
say "${target} for ${seconds} s; corpus ${work} (+ fuzz/corpus/${target}); findings to ${artifacts}"
exec "${build_dir}/fuzz/${target}_fuzz" -max_total_time="${seconds}" -timeout=25 -max_len=8192 \
  -print_final_stats=1 -artifact_prefix="${artifacts}/${target}-" "$@" \
  "${work}" "${root}/fuzz/corpus/${target}"
