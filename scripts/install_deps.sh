#!/usr/bin/env bash
# Installs the Debian 12 packages lpir-gseg needs to build and test, only those that are missing:
# checks each with dpkg-query, then `apt-get update` and `apt-get install` (through sudo when not
# root). Set LPIR_SKIP_DEPS=1 to skip this step (another distribution, no root, offline).
set -euo pipefail

PACKAGES=(
  build-essential cmake ninja-build pkg-config
  libeigen3-dev libopencv-core-dev libopencv-imgproc-dev libpng-dev
  libgtest-dev libbenchmark-dev
  libzstd-dev liblz4-dev libbz2-dev zlib1g-dev libsqlite3-dev  # recorded drives (host/drive/)
  libvulkan-dev vulkan-validationlayers mesa-vulkan-drivers glslang-tools
  clang libclang-rt-14-dev  # the fuzz build (fuzz/): clang with libFuzzer and its sanitizers
  libomp-dev  # OpenMP for clang (the sanitizer and fuzz builds); GCC brings its own libgomp
  clang-format  # scripts/test.sh checks every C++ source against .clang-format
  # The Python package (python/) and its suite: built offline in a venv that sees these
  python3-dev python3-venv python3-pip python3-setuptools python3-wheel python3-pybind11
  python3-numpy python3-pytest python3-dask python3-distributed
  # The independent ROS 1 bag writer of scripts/make_drive_fixtures.sh and drive_check.sh
  # (tools/drive_fixtures/write_bag.py); the suite reads only the committed fixtures. Those
  # scripts also need Node.js and npm (`nodejs npm`), which they ask for when missing.
  python3-rosbag python3-roslz4 python3-sensor-msgs
)

say() { echo "[install_deps] $*"; }

if [[ "${LPIR_SKIP_DEPS:-0}" == "1" ]]; then
  say "LPIR_SKIP_DEPS=1: not checking the system packages"
  exit 0
fi

if ! command -v dpkg-query > /dev/null 2>&1; then
  say "no dpkg-query: not a Debian system, so nothing is installed automatically."
  say "make sure the equivalents of these Debian packages are installed: ${PACKAGES[*]}"
  exit 0
fi

say "checking ${#PACKAGES[@]} Debian packages with dpkg-query"
missing=()
for package in "${PACKAGES[@]}"; do
  if ! dpkg-query -W -f='${db:Status-Status}\n' "${package}" 2> /dev/null | grep -qx installed; then
    missing+=("${package}")
  fi
done

if [[ ${#missing[@]} -eq 0 ]]; then
  say "all ${#PACKAGES[@]} packages are installed, nothing to do"
  exit 0
fi
say "missing: ${missing[*]}"

# Root runs apt-get itself; anyone else goes through sudo (asking for a password only when there
# is a terminal to ask on: without one, sudo -n fails at once instead of waiting).
as_root=()
if [[ "$(id -u)" -ne 0 ]]; then
  if ! command -v sudo > /dev/null 2>&1; then
    say "error: not root and no sudo; as root, run:" >&2
    say "  apt-get update && apt-get install -y --no-install-recommends ${missing[*]}" >&2
    exit 1
  fi
  if [[ -t 0 ]]; then
    as_root=(sudo)
  else
    as_root=(sudo -n)
  fi
fi

run() {
  say "+ $*"
  "$@"
}
run "${as_root[@]}" env DEBIAN_FRONTEND=noninteractive apt-get update
run "${as_root[@]}" env DEBIAN_FRONTEND=noninteractive \
  apt-get install -y --no-install-recommends "${missing[@]}"
say "installed: ${missing[*]}"
