#!/usr/bin/env bash
# The whole test suite in one command: installs what is missing, checks that every C++ source
# is as clang-format leaves it (.clang-format; `git ls-files '*.cpp' '*.h' | xargs clang-format
# -i` fixes it), then
#   1. builds everything (Release, Ninja, ./build or $LPIR_BUILD_DIR) and runs ctest; then the
#      package check: a library-only build (LPIR_BUILD_TESTS/BENCH/APPS=OFF; ./build-pkg or
#      $LPIR_PKG_BUILD_DIR, through ccache when installed) installed to a temporary prefix,
#      examples/cpp built against that prefix alone, its labels of a KITTI scan (a simulated one
#      without ../shared/data) compared byte for byte with `lpir-gseg segment --backend cpu`'s,
#      from the CPU reference and from Vulkan on lavapipe;
#   2. builds everything again under AddressSanitizer + UBSan (LPIR_SANITIZE=ON, -O1, no
#      benchmarks; ./build-asan or $LPIR_ASAN_BUILD_DIR) and runs ctest there. With clang++ when
#      installed (a third less build time than g++ on 2 cores, and a second compiler's view:
#      it found the simulator's order-of-evaluation dependence), else c++; $LPIR_SANITIZE_CXX
#      chooses;
#   3. builds the libFuzzer targets with clang (LPIR_FUZZ=ON; ./build-fuzz or $LPIR_FUZZ_BUILD_DIR)
#      and runs their bounded runs (a few seconds each, ctest -L fuzz);
#   4. builds the CPU backend's threaded tests alone (threads_test, cpu_pipeline_test) under
#      ThreadSanitizer with clang and LLVM's OpenMP (LPIR_TSAN=ON; ./build-tsan or
#      $LPIR_TSAN_BUILD_DIR) and runs them: every stage at 2 to 8 threads and frames in flight.
# After step 1, the Python package: a fresh `python3 -m venv --system-site-packages` (./build-venv
# or $LPIR_PY_VENV; Debian's /usr/bin/python3, whose site packages hold python3-numpy and the
# rest, or $LPIR_PYTHON), `pip install --no-build-isolation --no-index ./python` (offline; the
# CMake build in python/build/ is kept, so a rerun recompiles only what changed), then its pytest
# suite (python/tests/) against step 1's lpir-gseg, with Vulkan on lavapipe. LPIR_TEST_PYTHON=0
# skips it.
# Steps 1 and 2 run every Vulkan equality test once per shape (tests/CMakeLists.txt registers
# <file>.gpu.<test> and <file>.cpu.<test> with LPIR_VK_SHAPE set; docs/decisions/shapes.md).
# ctest runs on every core and prints the output of failing tests. Every step runs even when an
# earlier one failed; the exit code is non-zero when any failed. Arguments go to the ctest of steps
# 1 and 2, e.g. scripts/test.sh -R images. LPIR_TEST_SANITIZE=0 / LPIR_TEST_FUZZ=0 /
# LPIR_TEST_TSAN=0 skip step 2 / 3 / 4.
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "${root}"
jobs="$(nproc 2> /dev/null || echo 2)"
build_dir="${LPIR_BUILD_DIR:-${root}/build}"
asan_dir="${LPIR_ASAN_BUILD_DIR:-${root}/build-asan}"
fuzz_dir="${LPIR_FUZZ_BUILD_DIR:-${root}/build-fuzz}"
tsan_dir="${LPIR_TSAN_BUILD_DIR:-${root}/build-tsan}"
pkg_dir="${LPIR_PKG_BUILD_DIR:-${root}/build-pkg}"
say() { echo "[test] $*"; }
failed=()
summary=()
# step NAME COMMAND...: runs it and times it; a failure is recorded (and returned), not fatal.
step() {
  local name="$1" start=${SECONDS}
  shift
  say "+ $*"
  if "$@"; then
    summary+=("${name}: passed in $((SECONDS - start)) s")
    return 0
  fi
  failed+=("${name}")
  summary+=("${name}: FAILED after $((SECONDS - start)) s")
  return 1
}

say "step 0: system packages"
bash "${root}/scripts/install_deps.sh"

say "format: every C++ source as .clang-format leaves it"
# format_check: clang-format --dry-run -Werror over the tracked *.cpp and *.h files.
format_check() {
  if ! git -C "${root}" rev-parse --is-inside-work-tree > /dev/null 2>&1; then
    say "not a git checkout: no list of sources to check"
    return 1
  fi
  local files
  mapfile -t files < <(git -C "${root}" ls-files '*.cpp' '*.h')
  (cd "${root}" && clang-format --dry-run -Werror "${files[@]}")
}
step "format" format_check || true

# package_check: the installed C++ package (docs/usage.md, The library) against the CLI of step 1,
# in a temporary folder (removed after) holding the prefix, the example's build and the labels.
package_check() {
  local work rc=0
  work="$(mktemp -d)"
  package_steps "${work}" || rc=1
  rm -rf "${work}"
  return "${rc}"
}
package_steps() {
  local work="$1" prefix="$1/prefix" cli scan icd launcher=() rc=0
  cli="$(cd "${build_dir}" && pwd)/lpir-gseg"
  if [[ -z "${CMAKE_CXX_COMPILER_LAUNCHER:-}" ]] && command -v ccache > /dev/null 2>&1; then
    launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
  fi
  # The prefix is compiled into the library (DefaultSensorsDir()), so it is set when configuring.
  if ! {
    cmake -S "${root}" -B "${pkg_dir}" -G Ninja -DCMAKE_BUILD_TYPE=Release "${launcher[@]}" \
      -DLPIR_BUILD_TESTS=OFF -DLPIR_BUILD_BENCH=OFF -DLPIR_BUILD_APPS=OFF \
      -DCMAKE_INSTALL_PREFIX="${prefix}" &&
      cmake --build "${pkg_dir}" --parallel "${jobs}" && cmake --install "${pkg_dir}"
  } > "${work}/package.log" 2>&1; then
    cat "${work}/package.log"
    return 1
  fi
  # A library-only configuration never looks for the apps', tests' or benchmarks' packages.
  if grep -E '^(OpenCV_core_LIBRARY|PNG_LIBRARY_RELEASE|GTest_DIR|benchmark_DIR)[:=]' \
    "${pkg_dir}/CMakeCache.txt"; then
    say "the library-only configuration looked for the packages above"
    return 1
  fi
  # The example sees the prefix only: no package registry, the source tree on none of its paths.
  if ! {
    cmake -S "${root}/examples/cpp" -B "${work}/example" -G Ninja -DCMAKE_BUILD_TYPE=Release \
      -DCMAKE_PREFIX_PATH="${prefix}" -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF &&
      cmake --build "${work}/example"
  } > "${work}/example.log" 2>&1; then
    cat "${work}/example.log"
    return 1
  fi
  scan="${LPIR_DATA_DIR:-${root}/../shared/data}/kitti/00/velodyne/000000.bin"
  if [[ ! -f "${scan}" ]]; then
    say "no ${scan}: a simulated HDL-64E scan instead"
    scan="${work}/000000.bin"
    "${cli}" simulate --sensor hdl64e --seed 1 --out "${scan}" \
      --labels "${work}/truth.label" > /dev/null || return 1
  fi
  (cd "${work}" && env -u LPIR_SENSORS_DIR "${cli}" segment "${scan}" \
    --sensor hdl64e --backend cpu --out cli --quiet > /dev/null) || return 1
  # A profile that only the prefix holds: found only when DefaultSensorsDir() is the installed one.
  cp "${prefix}/share/lpir_gseg/sensors/hdl64e.txt" \
    "${prefix}/share/lpir_gseg/sensors/installed-hdl64e.txt" || return 1
  if ! (cd "${work}" && env -u LPIR_SENSORS_DIR example/segment_file "${scan}" installed-hdl64e \
    cpu.label cpu && cmp cpu.label cli/000000.label); then
    rc=1
  fi
  icd="$(compgen -G '/usr/share/vulkan/icd.d/lvp_icd.*.json' | head -n 1 || true)"
  if [[ -n "${icd}" ]]; then
    if ! (cd "${work}" && env -u LPIR_SENSORS_DIR VK_ICD_FILENAMES="${icd}" \
      example/segment_file "${scan}" installed-hdl64e vulkan.label vulkan &&
      cmp vulkan.label cli/000000.label); then
      rc=1
    fi
  else
    say "no lavapipe ICD: the example's Vulkan run is skipped"
  fi
  return "${rc}"
}

say "step 1/4: Release build and suite"
built=0
if step "build" bash "${root}/scripts/build.sh"; then
  built=1
  step "suite" ctest --test-dir "${build_dir}" --output-on-failure -j "${jobs}" "$@" || true
  say "package: library-only build installed to a temporary prefix, examples/cpp against it"
  step "package" package_check || true
fi

# python_suite: the package installed into a fresh venv, and its pytest suite (see the top).
python_suite() {
  local python="${LPIR_PYTHON:-/usr/bin/python3}" venv="${LPIR_PY_VENV:-${root}/build-venv}"
  [[ -x "${python}" ]] || python="$(command -v python3)"
  local icd
  icd="$(ls /usr/share/vulkan/icd.d/lvp_icd.*.json 2> /dev/null | head -n 1 || true)"
  rm -rf "${venv}"
  "${python}" -m venv --system-site-packages "${venv}" &&
    CMAKE_BUILD_PARALLEL_LEVEL="${jobs}" "${venv}/bin/pip" install --quiet --no-build-isolation \
      --no-index "${root}/python" &&
    (cd "${root}/python/tests" && VK_ICD_FILENAMES="${icd}" LPIR_CLI="${build_dir}/lpir-gseg" \
      "${venv}/bin/python" -m pytest -q -p no:cacheprovider .)
}
if [[ "${LPIR_TEST_PYTHON:-1}" != "0" && ${built} -eq 1 ]]; then
  say "Python package: install into a fresh venv, pytest"
  step "python" python_suite || true
fi

if [[ "${LPIR_TEST_SANITIZE:-1}" != "0" ]]; then
  say "step 2/4: AddressSanitizer + UBSan build and suite in ${asan_dir}"
  asan_cxx="${LPIR_SANITIZE_CXX:-$(command -v clang++ || command -v c++)}"
  asan_cxx="$(command -v "${asan_cxx}")"
  # A folder configured with another compiler is started afresh (cmake would refuse to switch).
  if [[ -f "${asan_dir}/CMakeCache.txt" ]] &&
    ! grep -qx "CMAKE_CXX_COMPILER:[A-Z]*=${asan_cxx}" "${asan_dir}/CMakeCache.txt"; then
    say "${asan_dir} was configured with another compiler: removing it"
    rm -rf "${asan_dir}"
  fi
  asan_configure=(cmake -S "${root}" -B "${asan_dir}" -G Ninja -DCMAKE_BUILD_TYPE=Debug
                  -DCMAKE_CXX_COMPILER="${asan_cxx}" -DLPIR_SANITIZE=ON)
  if step "sanitizer configure" "${asan_configure[@]}" &&
    step "sanitizer build" cmake --build "${asan_dir}" --parallel "${jobs}"; then
    step "sanitizer suite" ctest --test-dir "${asan_dir}" --output-on-failure -j "${jobs}" "$@" ||
      true
  fi
fi

if [[ "${LPIR_TEST_FUZZ:-1}" != "0" ]]; then
  say "step 3/4: fuzz targets (clang) and their bounded runs in ${fuzz_dir}"
  if ! command -v clang++ > /dev/null 2>&1; then
    say "no clang++: the fuzz targets are not built (Debian: apt-get install clang libclang-rt-14-dev)"
    failed+=("fuzz (no clang++)")
  elif step "fuzz configure" cmake -S "${root}" -B "${fuzz_dir}" -G Ninja \
    -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER=clang++ -DLPIR_FUZZ=ON &&
    step "fuzz build" cmake --build "${fuzz_dir}" --parallel "${jobs}" --target lpir_fuzzers; then
    step "fuzz runs" ctest --test-dir "${fuzz_dir}" --output-on-failure -j "${jobs}" -L fuzz || true
  fi
fi

if [[ "${LPIR_TEST_TSAN:-1}" != "0" ]]; then
  say "step 4/4: ThreadSanitizer build of the threaded CPU tests (clang) in ${tsan_dir}"
  if ! command -v clang++ > /dev/null 2>&1; then
    say "no clang++: the ThreadSanitizer tests are not built (Debian: apt-get install clang libomp-dev)"
    failed+=("tsan (no clang++)")
  elif step "tsan configure" cmake -S "${root}" -B "${tsan_dir}" -G Ninja \
    -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER=clang++ -DLPIR_TSAN=ON \
    -DLPIR_BUILD_BENCH=OFF &&
    step "tsan build" cmake --build "${tsan_dir}" --parallel "${jobs}" \
      --target threads_test cpu_pipeline_test; then
    step "tsan suite" ctest --test-dir "${tsan_dir}" --output-on-failure -j "${jobs}" || true
  fi
fi

for line in "${summary[@]}"; do say "${line}"; done
if [[ ${#failed[@]} -gt 0 ]]; then
  say "FAILED: ${failed[*]}"
  exit 1
fi
say "all passed"
