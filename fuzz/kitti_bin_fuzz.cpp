// Fuzz target of the .bin reader (host/io/kitti_bin.h), both layouts on every input: KITTI's 4
// floats (any whole number of 16-byte points reads, as the very bytes given) and nuScenes' 5
// (the fifth a ring, whole and >= 0). A read either succeeds exactly when its contract says and
// survives a write/read round trip, or throws IoError; anything else is a finding.
#include <cstddef>
#include <cstdint>
#include <cstring>

#include "fuzz/cloud_checks.h"
#include "fuzz/fuzz_file.h"
#include "host/io/io_error.h"
#include "host/io/kitti_bin.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace lpir;
  static fuzz::FuzzFile in, out;
  in.Write(data, size);
  for (BinLayout layout : {BinLayout::kKitti4, BinLayout::kNuScenes5}) {
    const size_t stride = (layout == BinLayout::kKitti4 ? 4 : 5) * sizeof(float);
    const bool whole = size > 0 && size % stride == 0;
    Cloud cloud;
    try {
      cloud = ReadKittiBin(in.path(), layout);
    } catch (const IoError&) {
      // KITTI's layout has no other reason to refuse a file; nuScenes' may refuse a ring.
      LPIR_FUZZ_CHECK(!whole || layout == BinLayout::kNuScenes5);
      continue;
    }
    LPIR_FUZZ_CHECK(whole);
    LPIR_FUZZ_CHECK(cloud.size() == size / stride);
    fuzz::CheckCloudShape(cloud);
    if (layout == BinLayout::kKitti4) {
      LPIR_FUZZ_CHECK(cloud.ring.empty());
      LPIR_FUZZ_CHECK(std::memcmp(cloud.xyzi.data(), data, size) == 0);
    } else {
      LPIR_FUZZ_CHECK(cloud.ring.size() == cloud.size());
    }
    WriteKittiBin(out.path(), cloud, layout);
    fuzz::CheckSameCloud(cloud, ReadKittiBin(out.path(), layout), /*nan_matches_nan=*/false);
  }
  return 0;
}
