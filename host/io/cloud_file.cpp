// Reading any supported cloud file by its extension, and writing labelled clouds.
#include "host/io/cloud_file.h"

#include <algorithm>
#include <cctype>

#include "host/io/io_error.h"
#include "host/io/pcd.h"
#include "host/io/ply.h"

namespace lpir {

namespace {

enum class Extension { kBin, kPcd, kPly, kOther };

Extension ExtensionOf(const std::string& path) {
  const size_t slash = path.find_last_of('/');
  const size_t dot = path.find_last_of('.');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) {
    return Extension::kOther;
  }
  std::string ext = path.substr(dot + 1);
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (ext == "bin") return Extension::kBin;
  if (ext == "pcd") return Extension::kPcd;
  if (ext == "ply") return Extension::kPly;
  return Extension::kOther;
}

}  // namespace

BinLayout BinLayoutFor(const std::string& path, const ReadOptions& options) {
  if (options.bin_layout) return *options.bin_layout;
  const std::string suffix = ".pcd.bin";
  const bool nuscenes = path.size() >= suffix.size() &&
                        path.compare(path.size() - suffix.size(), suffix.size(), suffix) == 0;
  return nuscenes ? BinLayout::kNuScenes5 : BinLayout::kKitti4;
}

Cloud ReadCloud(const std::string& path, const ReadOptions& options, std::string* note) {
  if (note) note->clear();
  switch (ExtensionOf(path)) {
    case Extension::kBin:
      return ReadKittiBin(path, BinLayoutFor(path, options));
    case Extension::kPcd:
      return ReadPcd(path, note);
    case Extension::kPly:
      return ReadPly(path, note);
    case Extension::kOther:
      break;
  }
  throw IoError(path, "unknown cloud file extension (expected .bin, .pcd or .ply)");
}

bool IsCloudFile(const std::string& path) { return ExtensionOf(path) != Extension::kOther; }

void WriteLabelledCloud(const std::string& path, const Cloud& cloud, const Labels& labels,
                        CloudFormat format) {
  if (format == CloudFormat::kPcd) {
    WritePcd(path, cloud, &labels, /*binary=*/true);
  } else {
    WritePly(path, cloud, &labels, /*binary=*/true);
  }
}

}  // namespace lpir
