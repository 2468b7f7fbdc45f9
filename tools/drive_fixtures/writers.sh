# Sourced by scripts/make_drive_fixtures.sh and scripts/drive_check.sh: the independent drive
# writers of this folder, checked and driven the same way for both. Needs `tools` (this folder),
# `python` (an interpreter that sees python3-rosbag) and `die` set by the caller.

# Fails (die) unless Node.js, npm and python3-rosbag are there; runs `npm ci` here when
# node_modules is missing.
require_writers() {
  { command -v node && command -v npm; } > /dev/null ||
    die "needs Node.js and npm for tools/drive_fixtures (Debian: apt-get install nodejs npm)"
  "${python}" -c 'import rosbag, roslz4, sensor_msgs.msg' 2> /dev/null ||
    die "needs ${python} with python3-rosbag, python3-roslz4 and python3-sensor-msgs" \
      "(scripts/install_deps.sh installs them)"
  if [[ ! -d "${tools}/node_modules" ]]; then
    echo "npm ci in ${tools}"
    (cd "${tools}" && npm ci --no-audit --no-fund)
  fi
}

# write_drives DIR STEM TOPIC SCRATCH PER_CHUNK FRAME.bin...: the frames as one message each on
# TOPIC in DIR/STEM_{zstd,lz4,none}.mcap, DIR/STEM.db3 and DIR/STEM_{bz2,lz4}.bag. PER_CHUNK 1:
# one message per chunk (the fixtures), 0: the writers' default chunk sizes. SCRATCH holds the CDR
# messages the .db3 is made from, removed after.
write_drives() {
  local dir="$1" stem="$2" topic="$3" scratch="$4" per_chunk="$5"
  shift 5
  local mcap_chunk=() bag_chunk=() compression
  if [[ "${per_chunk}" == 1 ]]; then
    mcap_chunk=(--chunk-size 1)
    bag_chunk=(--chunk-threshold 1)
  fi
  for compression in zstd lz4 none; do
    node "${tools}/write_mcap.mjs" --out "${dir}/${stem}_${compression}.mcap" \
      --compression "${compression}" --topic "${topic}" "${mcap_chunk[@]}" "$@"
  done
  node "${tools}/write_cdr.mjs" --out-dir "${scratch}" "$@"
  "${python}" "${tools}/write_db3.py" --cdr-dir "${scratch}" --out "${dir}/${stem}.db3" \
    --topic "${topic}"
  rm -rf "${scratch}"
  for compression in bz2 lz4; do
    "${python}" "${tools}/write_bag.py" --out "${dir}/${stem}_${compression}.bag" \
      --compression "${compression}" --topic "${topic}" "${bag_chunk[@]}" "$@"
  done
}

# write_full_drives DIR STEM TOPIC SCRATCH FRAME.bin...: the frames on TOPIC with the other
# topics, metadata and attachment of extras.mjs, as DIR/STEM_full.mcap (zstd), DIR/STEM_full.db3
# (Jazzy's schema, with message definitions) and DIR/STEM_full.bag (lz4), chunks of about 64 KiB.
# SCRATCH holds the CDR messages the .db3 is made from, removed after.
write_full_drives() {
  local dir="$1" stem="$2" topic="$3" scratch="$4"
  shift 4
  node "${tools}/write_mcap.mjs" --out "${dir}/${stem}_full.mcap" --compression zstd \
    --topic "${topic}" --chunk-size 65536 --extras 1 "$@"
  node "${tools}/write_cdr.mjs" --out-dir "${scratch}/frames" --extras-dir "${scratch}/extras" "$@"
  "${python}" "${tools}/write_db3.py" --cdr-dir "${scratch}/frames" --out "${dir}/${stem}_full.db3" \
    --topic "${topic}" --extras-dir "${scratch}/extras"
  rm -rf "${scratch}"
  "${python}" "${tools}/write_bag.py" --out "${dir}/${stem}_full.bag" --compression lz4 \
    --topic "${topic}" --chunk-threshold 65536 --extras "$@"
}

# write_bag_folder DIR NAME STORAGE STYLE TOPIC SCRATCH SPLIT FRAME.bin...: a ROS 2 bag folder as
# `ros2 bag record` writes one split into two files: DIR/NAME/metadata.yaml (write_metadata.py,
# STYLE rosbag2 or pyyaml) and DIR/NAME/NAME_0 and NAME_1 .mcap (STORAGE mcap: zstd, a chunk per
# message) or .db3 (STORAGE sqlite3), the first SPLIT frames in _0 and the rest in _1, numbered
# on across the files. SCRATCH holds the .db3's CDR messages, removed after.
write_bag_folder() {
  local dir="$1" name="$2" storage="$3" style="$4" topic="$5" scratch="$6" split="$7"
  shift 7
  local bag="${dir}/${name}" head=("${@:1:${split}}") tail=("${@:$((split + 1))}")
  rm -rf "${bag}"
  mkdir -p "${bag}"
  if [[ "${storage}" == mcap ]]; then
    node "${tools}/write_mcap.mjs" --out "${bag}/${name}_0.mcap" --compression zstd \
      --topic "${topic}" --chunk-size 1 "${head[@]}"
    node "${tools}/write_mcap.mjs" --out "${bag}/${name}_1.mcap" --compression zstd \
      --topic "${topic}" --chunk-size 1 --first "${split}" "${tail[@]}"
    "${python}" "${tools}/write_metadata.py" --out "${bag}/metadata.yaml" --storage mcap \
      --style "${style}" --topic "${topic}" "${name}_0.mcap:${#head[@]}" "${name}_1.mcap:${#tail[@]}"
  else
    node "${tools}/write_cdr.mjs" --out-dir "${scratch}/0" "${head[@]}"
    node "${tools}/write_cdr.mjs" --out-dir "${scratch}/1" --first "${split}" "${tail[@]}"
    "${python}" "${tools}/write_db3.py" --cdr-dir "${scratch}/0" --out "${bag}/${name}_0.db3" \
      --topic "${topic}"
    "${python}" "${tools}/write_db3.py" --cdr-dir "${scratch}/1" --out "${bag}/${name}_1.db3" \
      --topic "${topic}"
    rm -rf "${scratch}"
    "${python}" "${tools}/write_metadata.py" --out "${bag}/metadata.yaml" --storage sqlite3 \
      --style "${style}" --topic "${topic}" "${name}_0.db3:${#head[@]}" "${name}_1.db3:${#tail[@]}"
  fi
}

# write_killed_bag FILE TOPIC FRAME.bin...: what a ROS 1 recorder killed while writing the last
# frame leaves (write_bag.py --recorder-died, uncompressed as `rosbag record` writes by default).
write_killed_bag() {
  local file="$1" topic="$2"
  shift 2
  "${python}" "${tools}/write_bag.py" --out "${file}" --compression none --topic "${topic}" \
    --recorder-died "$@"
}
