// Any supported cloud file by its extension, from one table of formats (CloudFormats): .bin
// (KITTI, or nuScenes 5-float by option), .pcd (ASCII, binary or binary_compressed), .ply (ASCII
// or binary little-endian). A new format is its reader (and writer) and one row of that table:
// reading, folder listing, --format, the error messages and the help texts follow.
#pragma once
#include <optional>
#include <string>
#include <vector>

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

// A cloud file format: one row of CloudFormats.
struct CloudFormat {
  const char* extension;  // lower case, without the dot; a path's extension matches in any case
  const char* summary;    // its words in help texts and messages, e.g. ".bin (KITTI)"
  // Reads `path`; `note` as ReadCloud says.
  Cloud (*read)(const std::string& path, const ReadOptions& options, std::string* note);
  // Writes the cloud with a `label` field (uint8: 1 ground, 0 non-ground) beside x y z intensity
  // (and ring when the cloud has one), binary; null for a format only read.
  void (*write_labelled)(const std::string& path, const Cloud& cloud, const Labels& labels);
};

// Every format, in the order help texts list them.
const std::vector<CloudFormat>& CloudFormats();
// The row of `path`'s extension, or null.
const CloudFormat* CloudFormatOf(const std::string& path);
// The formats' summaries joined for help texts and messages: ".bin (KITTI), .pcd, .ply"; with
// `writable` only those with a writer, as "pcd, ply" (names for --format).
std::string CloudFormatList(bool writable = false);

// IoError naming the file for an unknown extension or a malformed file. `note` (when given): a
// sentence naming the file when the reader filled in what the file lacks (a .pcd or .ply without
// an intensity field: NoIntensityNote), else empty.
Cloud ReadCloud(const std::string& path, const ReadOptions& options = {},
                std::string* note = nullptr);
// True for the extensions ReadCloud accepts (used when listing a folder).
bool IsCloudFile(const std::string& path);

// Writes the labelled cloud in the format of `path`'s extension (CloudFormat::write_labelled);
// IoError naming the file when that format has no writer.
void WriteLabelledCloud(const std::string& path, const Cloud& cloud, const Labels& labels);

}  // namespace lpir
