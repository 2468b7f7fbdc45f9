// Any supported cloud file by its extension: .bin (KITTI, or nuScenes 5-float by option), .pcd
// (ASCII, binary or binary_compressed), .ply (ASCII or binary little-endian).
#pragma once
#include <optional>
#include <string>

#include "host/io/kitti_bin.h"
#include "reference_cpu/cloud.h"

namespace lpir {

struct ReadOptions {
  // The .bin layout; unset: nuScenes' 5 floats for files named *.pcd.bin (their naming), else
  // KITTI's 4. Both layouts can divide a file's size, so the name is the only evidence.
  std::optional<BinLayout> bin_layout;
};

// The layout ReadCloud uses for a .bin file at `path` under `options`.
BinLayout BinLayoutFor(const std::string& path, const ReadOptions& options);

// IoError naming the file for an unknown extension or a malformed file. `note` (when given): a
// sentence naming the file when the reader filled in what the file lacks (a .pcd or .ply without
// an intensity field: NoIntensityNote), else empty.
Cloud ReadCloud(const std::string& path, const ReadOptions& options = {},
                std::string* note = nullptr);
// True for the extensions ReadCloud accepts (used when listing a folder).
bool IsCloudFile(const std::string& path);

enum class CloudFormat { kPcd, kPly };
// Writes the cloud with a `label` field (uint8: 1 ground, 0 non-ground) beside x y z intensity
// (and ring when the cloud has one), binary.
void WriteLabelledCloud(const std::string& path, const Cloud& cloud, const Labels& labels,
                        CloudFormat format);

}  // namespace lpir
