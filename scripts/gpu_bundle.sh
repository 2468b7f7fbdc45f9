#!/usr/bin/env bash
# Builds a self-contained GPU check for a bare x86-64 Linux machine (an NVIDIA driver, no build
# packages, no package archive): scripts/gpu_bundle.sh DIR writes DIR/run.sh, DIR/payload.tar.xz
# and DIR/MANIFEST.txt, at most 60 MiB in all (docs/gpu_bundle.md).
#
# The payload holds, under bin/, lpir-gseg and the Vulkan equality tests (tests/vk_*_test.cpp,
# tests/*_vk_test.cpp), stripped; under lib/, every shared library they, the Vulkan loader and the
# validation layer need that is not part of glibc (ldd; libstdc++ and libgcc_s included: a machine
# may have an older libstdc++ than the one the binaries were linked against, and glibc itself is
# the one library every such machine has, tied to its own ld-linux, so it is never copied; run.sh
# checks that the machine's glibc is at least the version the binaries need, written to
# MANIFEST.txt); under layers/, the Khronos validation layer (the Vulkan tests run with
# validation on); the sensor profiles; and the real scans of ../shared/data (or $LPIR_DATA_DIR)
# without their ground-truth .label files, which no Vulkan test reads. Compressed with xz:
# uncompressed, the scans and the layer alone pass 60 MiB. The pictures' library (--images) is
# left out, and with it OpenCV: no check draws pictures.
#
# Builds (Release, Ninja) into $LPIR_BUILD_DIR or <repo>/build, reusing what is built there; a
# build folder of another build type, or configured with the sanitizers or for fuzzing, is left
# alone (<repo>/build-bundle instead).
set -euo pipefail

say() { echo "[gpu_bundle] $*"; }
die() {
  say "error: $*" >&2
  exit 1
}

[[ $# -eq 1 ]] || die "usage: scripts/gpu_bundle.sh DIR"
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
mkdir -p "$1"
dir="$(cd "$1" && pwd)"
for f in "${dir}"/* "${dir}"/.[!.]*; do
  [[ -e "${f}" ]] || continue
  case "${f##*/}" in
    run.sh | payload.tar.xz | payload.tar.xz.part | MANIFEST.txt | out) ;;
    *) die "${dir} holds ${f##*/}, which no bundle has: refusing to write into it" ;;
  esac
done
data="${LPIR_DATA_DIR:-${root}/../shared/data}"
[[ -d "${data}" ]] || die "no real scans at ${data} (set LPIR_DATA_DIR)"
data="$(cd "${data}" && pwd)"
max_mib=60

# The build.
build="${LPIR_BUILD_DIR:-${root}/build}"
cache="${build}/CMakeCache.txt"
if [[ -f "${cache}" ]] && { grep -Eq '^LPIR_(SANITIZE|FUZZ):BOOL=ON' "${cache}" ||
  ! grep -qx 'CMAKE_BUILD_TYPE:STRING=Release' "${cache}"; }; then
  say "${build} is not a plain Release build; using ${root}/build-bundle"
  build="${root}/build-bundle"
fi
mapfile -t tests < <(cd "${root}/tests" && ls vk_*_test.cpp *_vk_test.cpp 2> /dev/null |
  sed 's/\.cpp$//' | sort -u)
[[ ${#tests[@]} -gt 0 ]] || die "no Vulkan tests under ${root}/tests"
say "building lpir-gseg and ${#tests[@]} Vulkan tests in ${build} (Release)"
LPIR_BUILD_DIR="${build}" LPIR_BUILD_TYPE=Release bash "${root}/scripts/build.sh" lpir-gseg \
  "${tests[@]}"

# The staging folder, packed at the end.
stage="$(mktemp -d "${TMPDIR:-/tmp}/gpu_bundle.XXXXXX")"
trap 'rm -rf "${stage}"' EXIT
mkdir -p "${stage}/bin" "${stage}/lib" "${stage}/layers" "${stage}/sensors" "${stage}/data"
for t in lpir-gseg "${tests[@]}"; do
  src="${build}/${t}"
  [[ "${t}" == lpir-gseg ]] || src="${build}/tests/${t}"
  [[ -x "${src}" ]] || die "${src} was not built"
  strip --strip-unneeded -o "${stage}/bin/${t}" "${src}"
done

# The validation layer: its manifest and library, the manifest pointing beside itself.
layer_json=""
for d in /usr/share/vulkan/explicit_layer.d /usr/local/share/vulkan/explicit_layer.d \
  /etc/vulkan/explicit_layer.d; do
  if [[ -f "${d}/VkLayer_khronos_validation.json" ]]; then
    layer_json="${d}/VkLayer_khronos_validation.json"
    break
  fi
done
[[ -n "${layer_json}" ]] || die "no VkLayer_khronos_validation.json (vulkan-validationlayers)"
layer_lib="$(sed -n 's/.*"library_path": *"\([^"]*\)".*/\1/p' "${layer_json}" | head -n 1)"
if [[ "${layer_lib}" != /* ]]; then
  for d in "$(dirname "${layer_json}")" /usr/lib/x86_64-linux-gnu /usr/lib64 /usr/lib; do
    if [[ -f "${d}/${layer_lib}" ]]; then
      layer_lib="${d}/${layer_lib}"
      break
    fi
  done
fi
[[ -f "${layer_lib}" ]] || die "the validation layer's library ${layer_lib} is missing"
cp -L "${layer_lib}" "${stage}/layers/"
sed 's|"library_path": *"[^"]*"|"library_path": "./'"$(basename "${layer_lib}")"'"|' \
  "${layer_json}" > "${stage}/layers/VkLayer_khronos_validation.json"

# Shared libraries: everything ldd names for the binaries and the layer, but glibc's own.
glibc_re='^(linux-vdso|linux-gate|ld-linux[^ ]*|libc|libm|libdl|libpthread|librt|libresolv|libutil|libanl|libmvec|libnsl|libcrypt|libBrokenLocale|libnss_[a-z]+|libthread_db)\.so'
declare -A seen=()
for elf in "${stage}"/bin/* "${stage}"/layers/*.so; do
  while read -r name path; do
    [[ -n "${path}" && -f "${path}" ]] || continue
    [[ "${name}" =~ ${glibc_re} ]] && continue
    [[ -n "${seen[${name}]:-}" ]] && continue
    seen[${name}]=1
    cp -L "${path}" "${stage}/lib/${name}"
  done < <(ldd "${elf}" | awk '$2 == "=>" { print $1, $3 }')
done
[[ -f "${stage}/lib/libvulkan.so.1" ]] || die "libvulkan.so.1 not found through ldd"

cp "${root}"/sensors/*.txt "${root}/sensors/README.md" "${stage}/sensors/"
tar -C "${data}" --exclude='*.label' -cf - . | tar -C "${stage}/data" -xf - ||
  die "could not copy ${data}"

# The highest glibc symbol version anything in the payload needs.
glibc_need="$(for f in "${stage}"/bin/* "${stage}"/lib/* "${stage}"/layers/*.so; do
  objdump -T "${f}" 2> /dev/null | grep -o 'GLIBC_[0-9][0-9.]*' || true
done | sed 's/GLIBC_//' | sort -t. -k1,1n -k2,2n -k3,3n -u | tail -n 1)"

rm -f "${dir}/payload.tar.xz" "${dir}/payload.tar.xz.part" "${dir}/run.sh" "${dir}/MANIFEST.txt"
{
  echo "lpir-gseg GPU bundle (scripts/gpu_bundle.sh, docs/gpu_bundle.md)"
  echo "commit: $(git -C "${root}" rev-parse HEAD 2> /dev/null || echo unknown)$(
    git -C "${root}" diff --quiet HEAD 2> /dev/null || echo ' (with uncommitted changes)')"
  echo "built: $(date -u +%Y-%m-%dT%H:%M:%SZ) on $(uname -srm)"
  echo "glibc_required: ${glibc_need}"
  echo "tests: ${tests[*]}"
  echo
  echo "payload (uncompressed bytes, path):"
  (cd "${stage}" && find . -type f -printf '%s %P\n' | sort -k2)
} > "${dir}/MANIFEST.txt"
say "packing $(du -sh "${stage}" | cut -f1) (xz)"
tar -C "${stage}" -cf - . | xz -6 -T0 > "${dir}/payload.tar.xz.part"
mv "${dir}/payload.tar.xz.part" "${dir}/payload.tar.xz"
install -m 0755 "${root}/scripts/gpu_bundle_run.sh" "${dir}/run.sh"

files=("${dir}/run.sh" "${dir}/payload.tar.xz" "${dir}/MANIFEST.txt")
size_kib="$(du -ck "${files[@]}" | tail -n 1 | cut -f1)"
say "wrote ${dir}: $(du -ch "${files[@]}" | tail -n 1 | cut -f1) (run.sh, payload.tar.xz, MANIFEST.txt)"
((size_kib <= max_mib * 1024)) || die "the bundle is over ${max_mib} MiB"
say "on the GPU machine: cd $(basename "${dir}") && ./run.sh   (results in ./out, or \$OUT)"
