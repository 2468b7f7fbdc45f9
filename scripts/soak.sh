#!/usr/bin/env bash
# Soak: runs FRAMES frames (default 10,000) through `lpir-gseg segment` on Vulkan (lavapipe unless
# VK_ICD_FILENAMES says otherwise) and on the reference (`--backend cpu`), and checks that memory
# does not grow with the number of frames:
#  - host: the process's peak RSS (VmHWM in /proc/PID/status) at the end of warm-up, once frame
#    WARM is written, against its peak RSS at the end of the run (the larger of VmHWM read after
#    the last frame was written and ru_maxrss from /usr/bin/time -v at exit); they must differ by
#    less than 1 %. WARM is a third of the run (3,333 of 10,000): allocators settle over the
#    first frames (on lavapipe a malloc arena of a driver thread grows in 1 MiB steps for the
#    first ~2,500 frames, then stays flat; docs/testing.md), so growth before WARM is no leak,
#    and a leak of a few hundred bytes a frame still shows in the two thirds after it (on
#    lavapipe a run needs about 7,000 frames for WARM to fall past that settling).
#    VmRSS/VmHWM at frame 100, WARM and every 1,000 frames are printed too. On lavapipe the
#    device's memory is host memory, so this covers it as well.
#  - device: every vkAllocateMemory/vkFreeMemory call is counted by a small LD_PRELOAD shim
#    (built here with cc), in a run of 100 frames and in the run of FRAMES frames; the counts and
#    bytes must be equal (allocate once, however many frames) and all freed at exit.
# (The kernel updates these counters lazily, per thread: readings of one process wobble by a few
# hundred kB, 0.2 % here, and VmHWM can even read lower later.)
# Frame k is written as f<k>.label, so "frame 100 done" is the appearance of f00099.label. The
# frames are symlinks to four small simulated VLP-16 scans (~20k points each), in input order.
# Usage: scripts/soak.sh [FRAMES]   (the CLI from $LPIR_BUILD_DIR, default <repo>/build; or
#        $LPIR_GSEG; scratch files in $LPIR_SOAK_DIR, default a fresh folder under /tmp)
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
frames="${1:-10000}"
cli="${LPIR_GSEG:-${LPIR_BUILD_DIR:-${root}/build}/lpir-gseg}"
work="${LPIR_SOAK_DIR:-$(mktemp -d /tmp/lpir-soak.XXXXXX)}"
say() { echo "[soak] $*"; }
fail() {
  say "FAIL: $*" >&2
  failed=1
}
failed=0

if (( frames < 1000 )); then
  say "error: FRAMES must be at least 1000 (got ${frames})" >&2
  exit 2
fi
[[ -x "${cli}" ]] || { say "error: no ${cli}; build first (scripts/build.sh)" >&2; exit 1; }
[[ -x /usr/bin/time ]] || { say "error: /usr/bin/time missing (Debian: apt-get install time)" >&2; exit 1; }
if [[ -z "${VK_ICD_FILENAMES:-}" ]]; then
  icd="$(ls /usr/share/vulkan/icd.d/lvp_icd.*.json 2> /dev/null | head -n 1 || true)"
  [[ -n "${icd}" ]] && export VK_ICD_FILENAMES="${icd}"
fi
mkdir -p "${work}"
say "CLI ${cli}; ${frames} frames; scratch ${work}; VK_ICD_FILENAMES=${VK_ICD_FILENAMES:-}"

# The device-memory counter: wraps the loader's vkAllocateMemory/vkFreeMemory, prints totals at
# exit to $LPIR_VK_ALLOC_LOG.
cat > "${work}/vk_alloc_count.c" << 'EOF'
#define _GNU_SOURCE
#include <dlfcn.h>
#include <stdio.h>
#include <stdlib.h>
#include <vulkan/vulkan.h>

static unsigned long long allocs, frees, bytes;
VKAPI_ATTR VkResult VKAPI_CALL vkAllocateMemory(VkDevice d, const VkMemoryAllocateInfo* info,
                                                const VkAllocationCallbacks* a, VkDeviceMemory* m) {
  static PFN_vkAllocateMemory next;
  if (!next) next = (PFN_vkAllocateMemory)dlsym(RTLD_NEXT, "vkAllocateMemory");
  VkResult r = next(d, info, a, m);
  if (r == VK_SUCCESS) ++allocs, bytes += info->allocationSize;
  return r;
}
VKAPI_ATTR void VKAPI_CALL vkFreeMemory(VkDevice d, VkDeviceMemory m, const VkAllocationCallbacks* a) {
  static PFN_vkFreeMemory next;
  if (!next) next = (PFN_vkFreeMemory)dlsym(RTLD_NEXT, "vkFreeMemory");
  if (m != VK_NULL_HANDLE) ++frees;
  next(d, m, a);
}
__attribute__((destructor)) static void Report(void) {
  const char* path = getenv("LPIR_VK_ALLOC_LOG");
  FILE* f = path ? fopen(path, "w") : NULL;
  if (!f) return;
  fprintf(f, "%llu %llu %llu\n", allocs, bytes, frees);
  fclose(f);
}
EOF
cc -O1 -shared -fPIC -o "${work}/vk_alloc_count.so" "${work}/vk_alloc_count.c" -ldl

# Four scans, and folders of 100 and FRAMES symlinks to them.
for seed in 1 2 3 4; do
  [[ -f "${work}/s${seed}.bin" ]] ||
    "${cli}" simulate --sensor vlp16 --seed "${seed}" --out "${work}/s${seed}.bin" \
      --labels "${work}/s${seed}.label" > /dev/null
done
make_folder() {  # make_folder DIR COUNT
  rm -rf "$1" && mkdir -p "$1"
  (cd "$1" && for ((k = 0; k < $2; ++k)); do
    ln -s "${work}/s$((k % 4 + 1)).bin" "$(printf 'f%05d.bin' "${k}")"
  done)
}
make_folder "${work}/in100" 100
make_folder "${work}/in" "${frames}"
last=$(printf 'f%05d' $((frames - 1)))
warm=$(( frames / 3 ))
# next_checkpoint K: the frame after K at which RSS is printed: 100, WARM, then every 1,000.
next_checkpoint() {
  local k=$(( ($1 / 1000 + 1) * 1000 ))
  (( $1 < warm && warm < k )) && k=${warm}
  (( $1 < 100 && 100 < k )) && k=100
  echo "${k}"
}

elapsed() { awk -v s="$1" -v n="$(date +%s.%N)" 'BEGIN { printf "%.1f", n - s }'; }
# read_status PID: sets rss and hwm (kB) from /proc/PID/status without forking; "" once it exited.
read_status() {
  rss="" hwm=""
  local key value rest
  while read -r key value rest; do
    case "${key}" in
      VmRSS:) rss="${value}" ;;
      VmHWM:) hwm="${value}" ;;
    esac
  done 2> /dev/null < "/proc/$1/status" || true
}

for backend in vulkan cpu; do
  say "=== ${backend}"
  out="${work}/out_${backend}"
  # Device allocations over 100 frames.
  rm -rf "${out}100"
  LD_PRELOAD="${work}/vk_alloc_count.so" LPIR_VK_ALLOC_LOG="${work}/alloc100_${backend}" \
    "${cli}" segment "${work}/in100" --sensor vlp16 --backend "${backend}" --quiet \
    --out "${out}100" > "${work}/log100_${backend}" 2>&1 || fail "${backend}: 100 frames failed"
  # The long run, watched; not --quiet, so that its summary names the backend it ran on.
  rm -rf "${out}" && mkdir -p "${out}"
  start=$(date +%s.%N)
  # (env, not /usr/bin/time, gets the shim: time's own exit would overwrite the counts)
  /usr/bin/time -v -o "${work}/time_${backend}" \
    env LD_PRELOAD="${work}/vk_alloc_count.so" LPIR_VK_ALLOC_LOG="${work}/alloc_${backend}" \
    "${cli}" segment "${work}/in" --sensor vlp16 --backend "${backend}" \
    --out "${out}" > "${work}/log_${backend}" 2>&1 &
  timer=$!
  pid=""
  for _ in $(seq 100); do  # the CLI is /usr/bin/time's child (env execs it: same process)
    pid="$(pgrep -P "${timer}" | head -n 1 || true)"
    [[ -n "${pid}" ]] && break
    sleep 0.05
  done
  # Peak RSS at frame WARM; at the end: the last VmHWM read once the last label file exists (the
  # process is then shutting down), and ru_maxrss at exit; the larger of those two counts.
  hwm_warm="" hwm_end="" hwm_last=""
  next=100
  printf '[soak] %8s %10s %10s %8s\n' frame VmRSS_kB VmHWM_kB seconds
  while kill -0 "${timer}" 2> /dev/null; do
    read_status "${pid}"
    if [[ -n "${hwm}" ]]; then
      hwm_last="${hwm}"
      [[ -e "${out}/${last}.label" ]] && hwm_end="${hwm}"
      if (( next <= frames )) && [[ -e "${out}/$(printf 'f%05d' $((next - 1))).label" ]]; then
        printf '[soak] %8d %10s %10s %8.1f\n' "${next}" "${rss}" "${hwm}" "$(elapsed "${start}")"
        [[ ${next} -eq ${warm} ]] && hwm_warm="${hwm}"
        next=$(next_checkpoint "${next}")
        continue
      fi
    fi
    sleep 0.02
  done
  wait "${timer}" || fail "${backend}: the run of ${frames} frames failed (see ${work}/log_${backend})"
  seconds="$(elapsed "${start}")"
  maxrss="$(awk -F': ' '/Maximum resident set size/ { print $2 }' "${work}/time_${backend}")"
  hwm_final="${hwm_end:-${hwm_last}}"
  when="after the last frame"
  [[ -n "${hwm_end}" ]] || when="at the last read"
  peak=$(( maxrss > ${hwm_final:-0} ? maxrss : ${hwm_final:-0} ))
  labels="$(find "${out}" -name '*.label' | wc -l)"
  [[ "${labels}" -eq "${frames}" ]] || fail "${backend}: ${labels} label files, not ${frames}"
  [[ -e "${out}/${last}.label" ]] || fail "${backend}: no ${last}.label"
  if [[ -z "${hwm_warm}" ]]; then
    fail "${backend}: frame ${warm} (end of warm-up) passed before its peak RSS could be read"
  else
    growth="$(awk -v a="${hwm_warm}" -v b="${peak}" 'BEGIN { printf "%.3f", 100 * (b - a) / a }')"
    say "${backend}: ${frames} frames in ${seconds} s; peak RSS after frame ${warm} (end of" \
      "warm-up): ${hwm_warm} kB," \
      "after frame ${frames}: ${peak} kB (${growth} %; VmHWM ${hwm_final:-?} kB ${when}," \
      "ru_maxrss ${maxrss} kB)"
    if ! awk -v g="${growth}" 'BEGIN { exit !(g < 1 && g > -1) }'; then
      fail "${backend}: peak RSS grew by ${growth} % from frame ${warm} to frame ${frames}"
    fi
  fi
  read -r a100 b100 f100 < "${work}/alloc100_${backend}"
  read -r a b f < "${work}/alloc_${backend}"
  say "${backend}: device memory: 100 frames ${a100} allocations, ${b100} bytes, ${f100} freed;" \
    "${frames} frames ${a} allocations, ${b} bytes, ${f} freed"
  [[ "${a}" == "${a100}" && "${b}" == "${b100}" ]] ||
    fail "${backend}: device allocations differ between 100 and ${frames} frames"
  [[ "${f}" == "${a}" ]] || fail "${backend}: ${a} device allocations but ${f} freed"
  if [[ "${backend}" == vulkan ]]; then
    (( a > 0 )) || fail "vulkan: no device allocation counted (did the run use Vulkan?)"
    grep -q "on Vulkan on " "${work}/log_${backend}" || fail "vulkan: the run did not use Vulkan"
  fi
done

# Both backends wrote the same labels for every frame.
if ! diff -rq "${work}/out_vulkan" "${work}/out_cpu" > /dev/null; then
  fail "the .label files differ between vulkan and cpu"
else
  say "all ${frames} .label files identical on vulkan and cpu"
fi
if (( failed )); then
  say "FAILED (scratch files kept in ${work})"
  exit 1
fi
say "passed"
[[ -n "${LPIR_SOAK_DIR:-}" ]] || rm -rf "${work}"
