#!/usr/bin/env bash
# The benchmark suite in one command, on this machine's Vulkan device (a discrete GPU first,
# lavapipe otherwise) and the CPU reference: installs what is missing, builds `lpir-gseg` and the
# Google Benchmark programs (Release, Ninja, ./build) and runs `lpir-gseg bench`, which prints one
# table. Arguments go to it, e.g. scripts/bench.sh --json, scripts/bench.sh --device nvidia.
# On a machine without a package mirror, LPIR_SKIP_DEPS=1 skips the install step.
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "${root}"
echo "[bench] step 1/3: system packages" >&2
bash "${root}/scripts/install_deps.sh" >&2
echo "[bench] step 2/3: build" >&2
bash "${root}/scripts/build.sh" lpir-gseg frame_bench reference_bench >&2
build_dir="${LPIR_BUILD_DIR:-${root}/build}"
echo "[bench] step 3/3: + ${build_dir}/lpir-gseg bench $*" >&2
exec "${build_dir}/lpir-gseg" bench "$@"
