// KITTI Velodyne .bin: little-endian float32 x y z intensity per point; nuScenes .pcd.bin has a
// fifth float, the ring index.
#pragma once
#include <string>

#include "reference_cpu/cloud.h"

namespace lpir {

enum class BinLayout { kKitti4, kNuScenes5 };

// IoError (naming the file) when the file is missing, empty, or its size is not a whole number of
// points. NaN/Inf values are read as they are (prepare marks such points invalid). With
// kNuScenes5 the fifth float becomes `ring` (must be a whole number >= 0, else IoError).
Cloud ReadKittiBin(const std::string& path, BinLayout layout = BinLayout::kKitti4);
void WriteKittiBin(const std::string& path, const Cloud& cloud);
// kKitti4 as above (any ring is dropped); kNuScenes5 appends the ring as a float (the cloud must
// have one ring per point, else IoError).
void WriteKittiBin(const std::string& path, const Cloud& cloud, BinLayout layout);

}  // namespace lpir
