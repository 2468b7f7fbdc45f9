// frame_digest: a fingerprint of every buffer of every stage for each scan, so that two builds
// (before and after a change that must not move a byte) or two backends and shapes can be
// compared with diff. Not part of the product.
//
// usage: frame_digest --sensor NAME [--backend cpu|vulkan] SCAN.bin...
// Prints, per scan and per buffer of reference_cpu/frame.h in table order:
//   <scan> <stage>.<buffer> <bytes> <FNV-1a 64 of the bytes, hex>
// The Vulkan shape follows LPIR_VK_SHAPE (gpu or cpu; host/vk/shape.h).
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <exception>
#include <string>
#include <vector>

#include "host/api/segmenter.h"
#include "host/io/kitti_bin.h"
#include "host/io/sensor_profile.h"
#include "reference_cpu/frame.h"

namespace lpir {
namespace {

uint64_t Fnv1a(const void* data, size_t bytes) {
  uint64_t h = 0xcbf29ce484222325ull;
  const auto* p = static_cast<const unsigned char*>(data);
  for (size_t i = 0; i < bytes; ++i) h = (h ^ p[i]) * 0x100000001b3ull;
  return h;
}

int Main(int argc, char** argv) {
  std::string sensor, backend = "cpu";
  std::vector<std::string> scans;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--sensor" && i + 1 < argc) {
      sensor = argv[++i];
    } else if (a == "--backend" && i + 1 < argc) {
      backend = argv[++i];
    } else if (a.rfind("--", 0) == 0) {
      std::fprintf(stderr, "usage: frame_digest --sensor NAME [--backend cpu|vulkan] SCAN...\n");
      return 2;
    } else {
      scans.push_back(a);
    }
  }
  if (sensor.empty() || scans.empty()) {
    std::fprintf(stderr, "usage: frame_digest --sensor NAME [--backend cpu|vulkan] SCAN...\n");
    return 2;
  }
  SegmenterOptions options = SegmenterOptions::For(ParseBackend(backend));
  options.all_buffers = true;
  Segmenter segmenter(LoadSensorProfile(sensor), options);
  for (const std::string& scan : scans) {
    const Frame& f = segmenter.Segment(ReadKittiBin(scan));
    ForEachBuffer(
        [&](const BufferInfo& info, const auto& buffer) {
          const size_t bytes = buffer.size() * sizeof(buffer[0]);
          std::printf("%s %s.%s %zu %016llx\n", scan.c_str(), info.stage, info.name, bytes,
                      static_cast<unsigned long long>(Fnv1a(buffer.data(), bytes)));
        },
        f);
  }
  return 0;
}

}  // namespace
}  // namespace lpir

int main(int argc, char** argv) {
  try {
    return lpir::Main(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "frame_digest: %s\n", e.what());
    return 1;
  }
}
