// Reading any supported cloud file by its extension, and writing labelled clouds: the table of
// formats and the lookups over it.
#include "host/io/cloud_file.h"

#include <algorithm>
#include <cctype>

#include "host/io/io_error.h"
#include "host/io/pcd.h"
#include "host/io/ply.h"

namespace lpir {

namespace {

// The lower-case extension of `path`'s last component, without the dot; "" when it has none.
std::string ExtensionOf(const std::string& path) {
  const size_t slash = path.find_last_of('/');
  const size_t dot = path.find_last_of('.');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
  std::string ext = path.substr(dot + 1);
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

Cloud ReadBin(const std::string& path, const ReadOptions& options, std::string*) {
  return ReadKittiBin(path, BinLayoutFor(path, options));
}
Cloud ReadPcdFile(const std::string& path, const ReadOptions&, std::string* note) {
  return ReadPcd(path, note);
}
Cloud ReadPlyFile(const std::string& path, const ReadOptions&, std::string* note) {
  return ReadPly(path, note);
}
void WritePcdLabelled(const std::string& path, const Cloud& cloud, const Labels& labels) {
  WritePcd(path, cloud, &labels, /*binary=*/true);
}
void WritePlyLabelled(const std::string& path, const Cloud& cloud, const Labels& labels) {
  WritePly(path, cloud, &labels, /*binary=*/true);
}

}  // namespace

const std::vector<CloudFormat>& CloudFormats() {
  static const std::vector<CloudFormat> formats = {
      {"bin", ".bin (KITTI)", ReadBin, nullptr},
      {"pcd", ".pcd", ReadPcdFile, WritePcdLabelled},
      {"ply", ".ply", ReadPlyFile, WritePlyLabelled},
  };
  return formats;
}

const CloudFormat* CloudFormatOf(const std::string& path) {
  const std::string ext = ExtensionOf(path);
  for (const CloudFormat& f : CloudFormats())
    if (ext == f.extension) return &f;
  return nullptr;
}

std::string CloudFormatList(bool writable) {
  std::string list;
  for (const CloudFormat& f : CloudFormats()) {
    if (writable && !f.write_labelled) continue;
    list += (list.empty() ? "" : ", ") + std::string(writable ? f.extension : f.summary);
  }
  return list;
}

BinLayout BinLayoutFor(const std::string& path, const ReadOptions& options) {
  if (options.bin_layout) return *options.bin_layout;
  const std::string suffix = ".pcd.bin";
  const bool nuscenes = path.size() >= suffix.size() &&
                        path.compare(path.size() - suffix.size(), suffix.size(), suffix) == 0;
  return nuscenes ? BinLayout::kNuScenes5 : BinLayout::kKitti4;
}

Cloud ReadCloud(const std::string& path, const ReadOptions& options, std::string* note) {
  if (note) note->clear();
  const CloudFormat* format = CloudFormatOf(path);
  if (!format)
    throw IoError(path, "unknown cloud file extension (expected " + CloudFormatList() + ")");
  return format->read(path, options, note);
}

bool IsCloudFile(const std::string& path) { return CloudFormatOf(path) != nullptr; }

void WriteLabelledCloud(const std::string& path, const Cloud& cloud, const Labels& labels) {
  const CloudFormat* format = CloudFormatOf(path);
  if (!format || !format->write_labelled)
    throw IoError(path, "no labelled-cloud writer for this extension (writable: " +
                            CloudFormatList(true) + ")");
  format->write_labelled(path, cloud, labels);
}

}  // namespace lpir
