// The six consecutive SemanticKITTI 00 scans the benchmark programs time, from ../shared/data.
#pragma once
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

namespace lpir::bench {

// Their paths, 000000.bin .. 000005.bin; empty (after saying so on stdout, as `program`) when the
// data folder is absent.
inline std::vector<std::string> Kitti00Scans(const char* program) {
  const std::string dir = std::string(LPIR_DATA_DIR) + "/kitti/00/velodyne";
  std::error_code ec;
  if (!std::filesystem::is_directory(dir, ec)) {
    std::printf("%s: %s not found (../shared/data absent): nothing to benchmark\n", program,
                dir.c_str());
    return {};
  }
  std::vector<std::string> paths;
  for (int i = 0; i <= 5; ++i) {
    char name[32];
    std::snprintf(name, sizeof name, "/%06d.bin", i);
    paths.push_back(dir + name);
  }
  return paths;
}

// "kitti00_000000" for .../000000.bin.
inline std::string ScanLabel(const std::string& path) {
  return "kitti00_" + std::filesystem::path(path).stem().string();
}

}  // namespace lpir::bench
