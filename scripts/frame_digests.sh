#!/usr/bin/env bash
# Fingerprints every buffer of every frame of the labelled spinning-sensor scans of ../shared/data
# (8 KITTI frames with hdl64e, 40 nuScenes frames with hdl32e, RELLIS-3D 000104 with os1-64) on
# the CPU reference and on Vulkan in both shapes (LPIR_VK_SHAPE gpu and cpu), with build/
# frame_digest. Two builds' outputs compared with diff show whether a change moved any byte;
# the three files of one build must be identical (the bit-exact contract).
# usage: scripts/frame_digests.sh BUILD_DIR OUT_DIR   (DATA: ../shared/data by default)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${1:?usage: frame_digests.sh BUILD_DIR OUT_DIR}"
out="${2:?usage: frame_digests.sh BUILD_DIR OUT_DIR}"
data="${DATA:-${root}/../shared/data}"
tool="${build}/frame_digest"
[[ -x "${tool}" ]] || { echo "frame_digests: no ${tool} (ninja -C ${build} frame_digest)" >&2; exit 1; }
export VK_ICD_FILENAMES="${VK_ICD_FILENAMES:-$(ls /usr/share/vulkan/icd.d/lvp_icd.*.json 2> /dev/null | head -1)}"
mkdir -p "${out}"
kitti=()
for f in 07/000964 unknown/000056 00/000000 00/000001 00/000002 sglc/000052 sglc/000088 sglc/004501; do
  kitti+=("${data}/kitti/${f%/*}/velodyne/${f#*/}.bin")
done
nuscenes=("${data}"/nuscenes/lidarseg/scene-000{1,6}/velodyne/*.bin)
run() {  # backend shape file
  : > "${out}/$3"
  LPIR_VK_SHAPE="$2" "${tool}" --backend "$1" --sensor hdl64e "${kitti[@]}" >> "${out}/$3"
  LPIR_VK_SHAPE="$2" "${tool}" --backend "$1" --sensor hdl32e "${nuscenes[@]}" >> "${out}/$3"
  LPIR_VK_SHAPE="$2" "${tool}" --backend "$1" --sensor os1-64 "${data}/rellis3d/os1/000104.bin" \
    >> "${out}/$3"
  echo "frame_digests: ${out}/$3: $(wc -l < "${out}/$3") buffers"
}
run cpu "" cpu.txt
run vulkan gpu vulkan-gpu.txt
run vulkan cpu vulkan-cpu.txt
cmp "${out}/cpu.txt" "${out}/vulkan-gpu.txt" && cmp "${out}/cpu.txt" "${out}/vulkan-cpu.txt" &&
  echo "frame_digests: the three are identical"
