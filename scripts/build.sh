#!/usr/bin/env bash
# Configures and builds lpir-gseg (Release, Ninja) into <repo>/build, or $LPIR_BUILD_DIR.
# Usage: scripts/build.sh [TARGET...]   (no target: everything, tests included)
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "${root}"
build_dir="${LPIR_BUILD_DIR:-${root}/build}"
build_type="${LPIR_BUILD_TYPE:-Release}"

say() { echo "[build] $*"; }
run() {
  say "+ $*"
  "$@"
}

jobs="$(nproc 2> /dev/null || echo 2)"
say "repository ${root}, build folder ${build_dir} (${build_type}, ${jobs} jobs)"
# A folder configured earlier with another generator cannot be reused (cmake would refuse).
cache="${build_dir}/CMakeCache.txt"
if [[ -f "${cache}" ]] && ! grep -qx 'CMAKE_GENERATOR:INTERNAL=Ninja' "${cache}"; then
  say "error: ${build_dir} was configured with another generator than Ninja;" >&2
  say "remove it (rm -rf ${build_dir}) or choose another folder with LPIR_BUILD_DIR" >&2
  exit 1
fi
run cmake -S "${root}" -B "${build_dir}" -G Ninja -DCMAKE_BUILD_TYPE="${build_type}"
targets=()
for target in "$@"; do targets+=(--target "${target}"); done
run cmake --build "${build_dir}" --parallel "${jobs}" "${targets[@]}"
say "done"
