#!/usr/bin/env bash
# run.sh of a GPU bundle (scripts/gpu_bundle.sh copies this file there; docs/gpu_bundle.md):
# unpacks the payload into a temporary folder, runs every Vulkan equality test in both shapes
# (LPIR_VK_SHAPE=gpu, then cpu; gtest XML and a log per test program), then
# `lpir-gseg bench --json`, and writes into $OUT (./out when OUT is unset):
#   run.log                 everything printed
#   devices.txt             `lpir-gseg devices`
#   tests/<shape>/<test>.xml, .log, .rc
#   bench.json, bench.log   (bench.rc: its exit code)
#   bench/results/<device>.json   the file to commit: the bench JSON with labels_equal_reference
# then prints a one-screen summary. Exit code 0 when labels_equal_reference is true.
#
# labels_equal_reference is true when a Vulkan device ran, every test program exited 0 in both
# shapes with no failed test, and bench exited 0 with its CPU-versus-Vulkan label comparison equal
# in both shapes (gpu_cost.<shape>.labels_equal_reference).
#
# The device: whatever the Vulkan loader finds (VK_ICD_FILENAMES is left as the caller set it;
# unset, the loader reads /usr/share/vulkan/icd.d and /etc/vulkan/icd.d), the tests and bench take
# the first usable device, a discrete GPU first; LPIR_VK_DEVICE=<index or name part> picks
# another (the tests read it, bench gets it as --device). When the loader finds no device and the NVIDIA driver's library is there without its
# ICD manifest (containers often lack it), a manifest is written for it and used.
#
# Time: on a GPU, each shape's tests get 100 s (programs in parallel, one per core), bench 90 s:
# under 5 minutes in all. On a CPU driver (lavapipe) the tests are 10-50 times slower: the same
# programs and shapes run, with 900 s per shape, and bench with fewer repetitions (--runs 3
# --scaling-runs 3 --frames 6), 600 s at most; about 25 minutes at most in all.
# LPIR_BUNDLE_SHAPE_SECONDS and LPIR_BUNDLE_BENCH_SECONDS override those budgets.
set -uo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
out="${OUT:-${PWD}/out}"
mkdir -p "${out}" || exit 1
out="$(cd "${out}" && pwd)"
rm -rf "${out}/tests" "${out}/bench" "${out}"/bench.* "${out}/devices.txt"
start=$(date +%s)
say() { echo "[run] $*"; }
elapsed() { echo $(($(date +%s) - start)); }

# Everything below, its output also into run.log (a pipe into tee rather than a process
# substitution, which `wait` would wait for).
main() {
  work="$(mktemp -d "${TMPDIR:-/tmp}/lpir_bundle.XXXXXX")" || exit 1
  cleanup() { rm -rf "${work}"; }
  trap cleanup EXIT

  # The payload.
  say "unpacking ${here}/payload.tar.xz into ${work}"
  if command -v xz > /dev/null 2>&1; then
    tar -C "${work}" -xJf "${here}/payload.tar.xz"
  elif command -v python3 > /dev/null 2>&1; then
    python3 -c 'import sys, tarfile; tarfile.open(sys.argv[1]).extractall(sys.argv[2])' \
      "${here}/payload.tar.xz" "${work}"
  else
    say "error: neither xz nor python3 to unpack the payload"
    exit 1
  fi || {
    say "error: could not unpack the payload"
    exit 1
  }
  bin="${work}/bin"

  # glibc: the machine's own, at least the version the payload was linked against.
  need="$(sed -n 's/^glibc_required: //p' "${here}/MANIFEST.txt")"
  have="$(getconf GNU_LIBC_VERSION 2> /dev/null | awk '{print $2}')"
  say "glibc: this machine ${have:-unknown}, the payload needs ${need:-unknown}"
  if [[ -n "${need}" && -n "${have}" ]] &&
    [[ "$(printf '%s\n%s\n' "${need}" "${have}" | sort -V | head -n 1)" != "${need}" ]]; then
    say "error: glibc ${have} is older than ${need}: build the bundle on an older distribution"
    exit 1
  fi

  # The libraries: the payload's, except those of the display stack that the NVIDIA driver itself
  # loads, when the machine has them (the driver was built against the machine's).
  mkdir -p "${work}/lib-active" "${work}/tmp" "${work}/home"
  has_system_lib() {
    local d
    for d in /lib/x86_64-linux-gnu /usr/lib/x86_64-linux-gnu /lib64 /usr/lib64 /usr/lib /lib; do
      [[ -e "${d}/$1" ]] && return 0
    done
    return 1
  }
  for lib in "${work}"/lib/*; do
    name="$(basename "${lib}")"
    case "${name}" in
      libGLdispatch.so.* | libGLX.so.* | libX11.so.* | libxcb.so.* | libXau.so.* | libXdmcp.so.* | \
        libXext.so.* | libbsd.so.* | libmd.so.*)
        has_system_lib "${name}" && continue
        ;;
    esac
    ln -s "${lib}" "${work}/lib-active/${name}"
  done
  export LD_LIBRARY_PATH="${work}/lib-active${LD_LIBRARY_PATH:+:${LD_LIBRARY_PATH}}"
  export VK_LAYER_PATH="${work}/layers"
  export LPIR_DATA_DIR="${work}/data" LPIR_SENSORS_DIR="${work}/sensors"
  export LPIR_CLI="${bin}/lpir-gseg"
  export TMPDIR="${work}/tmp" HOME="${HOME:-${work}/home}"
  unset LPIR_VK_SHAPE LPIR_VK_VALIDATION

  # The device.
  devices() { "${bin}/lpir-gseg" devices > "${out}/devices.txt" 2>&1; }
  say "VK_ICD_FILENAMES=${VK_ICD_FILENAMES:-(unset: the loader searches its folders)}"
  if ! devices && [[ -z "${VK_ICD_FILENAMES:-}" ]]; then
    for lib in libGLX_nvidia.so.0 libEGL_nvidia.so.0; do
      found=""
      for d in /lib/x86_64-linux-gnu /usr/lib/x86_64-linux-gnu /lib64 /usr/lib64 /usr/lib \
        /usr/local/nvidia/lib64 /usr/local/nvidia/lib; do
        [[ -e "${d}/${lib}" ]] && found="${d}/${lib}" && break
      done
      [[ -n "${found}" ]] || continue
      say "no device through the loader's search; trying the NVIDIA driver at ${found}"
      printf '{"file_format_version": "1.0.0", "ICD": {"library_path": "%s", "api_version": "1.3.0"}}\n' \
        "${found}" > "${work}/nvidia_icd.json"
      export VK_ICD_FILENAMES="${work}/nvidia_icd.json"
      devices && break
      unset VK_ICD_FILENAMES
    done
  fi
  sed 's/^/  /' "${out}/devices.txt"
  device="$(sed -n 's/^default (segment --backend auto without --device): //p' "${out}/devices.txt")"
  [[ -n "${LPIR_VK_DEVICE:-}" ]] && device="(LPIR_VK_DEVICE=${LPIR_VK_DEVICE}) ${device}"
  cpu_driver=0
  grep -F -- "${device:-no device}" "${out}/devices.txt" | grep -q '(CPU, ' && cpu_driver=1
  if [[ -z "${device}" ]]; then
    say "no Vulkan device: the tests will skip and labels_equal_reference will be false"
  fi
  if ((cpu_driver)); then
    shape_budget=900 bench_budget=600
    bench_args=(--runs 3 --scaling-runs 3 --frames 6)
    say "device ${device} is a CPU driver: ${shape_budget} s per shape, bench with ${bench_args[*]}"
  else
    shape_budget=100 bench_budget=90
    bench_args=()
  fi
  shape_budget="${LPIR_BUNDLE_SHAPE_SECONDS:-${shape_budget}}"
  bench_budget="${LPIR_BUNDLE_BENCH_SECONDS:-${bench_budget}}"
  [[ -n "${LPIR_VK_DEVICE:-}" ]] && bench_args+=(--device "${LPIR_VK_DEVICE}")
  jobs="$(nproc 2> /dev/null || echo 2)"

  # The tests, in both shapes: the programs in parallel, each with the time left in its shape.
  tests=()
  for t in "${bin}"/*; do
    [[ "${t##*/}" == lpir-gseg ]] || tests+=("${t##*/}")
  done
  run_test() {  # shape, test, deadline (seconds since the epoch)
    local dir="${out}/tests/$1" left=$(($3 - $(date +%s)))
    ((left > 0)) || left=1
    LPIR_VK_SHAPE="$1" timeout -k 5 "${left}" "${bin}/$2" --gtest_output="xml:${dir}/$2.xml" \
      > "${dir}/$2.log" 2>&1
    echo $? > "${dir}/$2.rc"
  }
  for shape in gpu cpu; do
    mkdir -p "${out}/tests/${shape}"
    deadline=$(($(date +%s) + shape_budget))
    say "tests, LPIR_VK_SHAPE=${shape}: ${#tests[@]} programs, ${jobs} at a time, ${shape_budget} s"
    running=0
    for t in "${tests[@]}"; do
      if ((running >= jobs)); then
        wait -n
        running=$((running - 1))
      fi
      run_test "${shape}" "${t}" "${deadline}" &
      running=$((running + 1))
    done
    wait
  done

  # Bench, alone on the machine.
  say "lpir-gseg bench --json${bench_args[*]:+ ${bench_args[*]}} (at most ${bench_budget} s)"
  timeout -k 5 "${bench_budget}" "${bin}/lpir-gseg" bench --json "${bench_args[@]}" \
    > "${out}/bench.json" 2> "${out}/bench.log"
  bench_rc=$?
  echo "${bench_rc}" > "${out}/bench.rc"

  # The verdict.
  attr() { sed -n 's/.*<testsuites [^>]*\b'"$1"'="\([0-9]*\)".*/\1/p' "$2" | head -n 1; }
  all_ok=1
  [[ -n "${device}" ]] || all_ok=0
  declare -A total=() failed=() skipped=() bad=()
  for shape in gpu cpu; do
    total[${shape}]=0 failed[${shape}]=0 skipped[${shape}]=0 bad[${shape}]=""
    for t in "${tests[@]}"; do
      f="${out}/tests/${shape}/${t}"
      rc="$(cat "${f}.rc" 2> /dev/null || echo missing)"
      n="" nf="" ne=""
      if [[ -f "${f}.xml" ]]; then
        n="$(attr tests "${f}.xml")" nf="$(attr failures "${f}.xml")" ne="$(attr errors "${f}.xml")"
        skipped[${shape}]=$((skipped[${shape}] + $(grep -c 'result="skipped"' "${f}.xml")))
      fi
      total[${shape}]=$((total[${shape}] + ${n:-0}))
      failed[${shape}]=$((failed[${shape}] + ${nf:-0} + ${ne:-0}))
      if [[ "${rc}" != 0 || -z "${n}" ]]; then
        case "${rc}" in
          124 | 137) why="timed out" ;;
          *) why="exit ${rc}" ;;
        esac
        bad[${shape}]+="${t} (${why}) "
        all_ok=0
      fi
    done
    ((failed[${shape}] == 0)) || all_ok=0
  done
  [[ "${bench_rc}" == 0 ]] || all_ok=0
  bench_equal="$(grep -o '"labels_equal_reference": true' "${out}/bench.json" 2> /dev/null | wc -l)"
  bench_differ="$(grep -o '"labels_equal_reference": false' "${out}/bench.json" 2> /dev/null | wc -l)"
  ((bench_equal == 2 && bench_differ == 0)) || all_ok=0
  verdict=false
  ((all_ok)) && verdict=true

  # The results file.
  bench_device="$(sed -n 's/^{"device": "\([^"]*\)".*/\1/p' "${out}/bench.json" 2> /dev/null)"
  name="${bench_device:-${device}}"
  [[ -n "${device}" && "${name}" != none* ]] || name="no-device"
  slug="$(printf '%s' "${name}" | tr 'A-Z' 'a-z' | sed 's/[^a-z0-9]\{1,\}/-/g; s/^-//; s/-$//')"
  mkdir -p "${out}/bench/results"
  results="${out}/bench/results/${slug:-unknown}.json"
  json_str() { printf '"%s"' "$(printf '%s' "$1" | sed 's/\\/\\\\/g; s/"/\\"/g')"; }
  {
    printf '{"device": %s, "labels_equal_reference": %s, ' "$(json_str "${name}")" "${verdict}"
    printf '"commit": %s, ' "$(json_str "$(sed -n 's/^commit: //p' "${here}/MANIFEST.txt")")"
    printf '"equality_tests": {'
    sep=""
    for shape in gpu cpu; do
      printf '%s"%s": {"tests": %d, "failed": %d, "skipped": %d, "programs_failed": %s}' "${sep}" \
        "${shape}" "${total[${shape}]}" "${failed[${shape}]}" "${skipped[${shape}]}" \
        "$(json_str "${bad[${shape}]% }")"
      sep=", "
    done
    printf '}, "bench_exit_code": %d, "bench": ' "${bench_rc}"
    if [[ "${bench_rc}" == 0 && -s "${out}/bench.json" ]]; then
      tr -d '\n' < "${out}/bench.json"
    else
      printf 'null'
    fi
    printf ', "run_seconds": %d}\n' "$(elapsed)"
  } > "${results}"

  # The summary.
  ran="$(cat "${out}"/tests/*/*.log 2> /dev/null | sed -n 's/^\[vulkan\] device: //p' | sort -u |
    paste -sd ';' -)"
  echo
  echo "================ lpir-gseg GPU check ================"
  echo "device (default): ${device:-none}"
  echo "device the tests ran on: ${ran:-none}"
  echo "device bench ran on: ${bench_device:-none}"
  for shape in gpu cpu; do
    printf 'equality tests, LPIR_VK_SHAPE=%s: %d tests, %d failed, %d skipped%s\n' "${shape}" \
      "${total[${shape}]}" "${failed[${shape}]}" "${skipped[${shape}]}" \
      "${bad[${shape}]:+; programs failed: ${bad[${shape}]% }}"
  done
  bench_note=""
  [[ "${bench_rc}" == 0 ]] || bench_note=" (bench.log: $(tail -n 1 "${out}/bench.log" 2> /dev/null))"
  echo "bench: exit ${bench_rc}${bench_note}"
  if [[ -s "${out}/bench.json" ]]; then
    for shape in gpu cpu; do
      part="$(sed -n 's/.*"gpu_cost": \(.*\)/\1/p' "${out}/bench.json" |
        sed -n 's/.*"'"${shape}"'": {\([^}]*\)}.*/\1/p')"
      [[ -n "${part}" ]] && echo "  gpu_cost ${shape}: ${part}"
    done
    e2e="$(sed -n 's/.*"end_to_end": {"cpu": {"median_ms": \([0-9.]*\)[^}]*}, "vulkan": {"median_ms": \([0-9.]*\).*/cpu \1 ms, vulkan \2 ms/p' "${out}/bench.json")"
    [[ -n "${e2e}" ]] && echo "  end to end, median per frame: ${e2e}"
  fi
  echo "labels_equal_reference: ${verdict}"
  echo "results: ${results}"
  if [[ "${name}" == no-device ]]; then
    echo "  no Vulkan device ran: nothing to commit (see devices.txt)"
  else
    echo "  commit it as bench/results/$(basename "${results}") in the repository"
  fi
  echo "everything: ${out} ($(elapsed) s)"
  [[ "${verdict}" == true ]]
}

main 2>&1 | tee "${out}/run.log"
exit "${PIPESTATUS[0]}"
