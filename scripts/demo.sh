#!/usr/bin/env bash
# The demo in one command: installs what is missing, builds (Release, Ninja, ./build) and runs
# `./build/lpir-gseg demo`. Arguments go to the demo, e.g. scripts/demo.sh --out /tmp/demo.
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "${root}"
echo "[demo] step 1/3: system packages"
bash "${root}/scripts/install_deps.sh"
echo "[demo] step 2/3: build"
bash "${root}/scripts/build.sh" lpir-gseg
build_dir="${LPIR_BUILD_DIR:-${root}/build}"
echo "[demo] step 3/3: + ${build_dir}/lpir-gseg demo $*"
exec "${build_dir}/lpir-gseg" demo "$@"
