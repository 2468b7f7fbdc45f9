#!/usr/bin/env bash
# The whole test suite in one command: installs what is missing, builds everything (Release,
# Ninja, ./build) and runs ctest on every core, printing the output of failing tests. Arguments go
# to ctest, e.g. scripts/test.sh -R images.
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "${root}"
echo "[test] step 1/3: system packages"
bash "${root}/scripts/install_deps.sh"
echo "[test] step 2/3: build"
bash "${root}/scripts/build.sh"
build_dir="${LPIR_BUILD_DIR:-${root}/build}"
jobs="$(nproc 2> /dev/null || echo 2)"
echo "[test] step 3/3: + ctest --test-dir ${build_dir} --output-on-failure -j ${jobs} $*"
exec ctest --test-dir "${build_dir}" --output-on-failure -j "${jobs}" "$@"
