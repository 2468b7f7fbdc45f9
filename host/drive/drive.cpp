#include "host/drive/drive.h"

#include <filesystem>

#include "host/drive/bag_folder.h"
#include "host/drive/chunk_pool.h"
#include "host/drive/db3_reader.h"
#include "host/drive/mcap_reader.h"
#include "host/drive/pointcloud2.h"
#include "host/drive/ros1_bag_reader.h"
#include "host/io/io_error.h"

namespace lpir {

namespace {

constexpr char kActive[] = ".bag.active";  // what a ROS 1 recorder writes until it closes the bag

bool EndsWith(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() &&
         s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

}  // namespace

bool IsDriveFile(const std::string& path) {
  const std::string ext = std::filesystem::path(path).extension().string();
  return ext == ".mcap" || ext == ".db3" || ext == ".bag" || EndsWith(path, kActive);
}

bool IsDrive(const std::string& path) { return IsDriveFile(path) || IsBagFolder(path); }

DriveFormat DriveFormatOf(const std::string& path) {
  const std::string ext = std::filesystem::path(path).extension().string();
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) {
    if (IsBagFolder(path)) return DriveFormat::kBagFolder;
    throw IoError(
        path,
        "a folder, not a ROS 2 bag: it holds no metadata.yaml and no <folder name>_0.mcap "
        "or _0.db3");
  }
  if (ext == ".mcap") return DriveFormat::kMcap;
  if (ext == ".db3") return DriveFormat::kDb3;
  if (ext == ".bag" || EndsWith(path, kActive)) return DriveFormat::kRos1Bag;
  throw IoError(path,
                "not a recorded drive: the extension must be .mcap, .db3, .bag or .bag.active, or "
                "a ROS 2 bag folder");
}

std::unique_ptr<DriveReader> OpenDrive(const std::string& path, unsigned read_threads) {
  const DriveFormat format = DriveFormatOf(path);
  const unsigned threads = ReadThreads(read_threads);
  if (format == DriveFormat::kBagFolder) return OpenBagFolder(path, threads);
  if (format == DriveFormat::kMcap) return OpenMcap(path, threads);
  if (format == DriveFormat::kDb3) return OpenDb3(path);
  return OpenRos1Bag(path, threads);
}

Cloud DecodeDriveCloud(const std::string& where, const DriveMessage& message) {
  const PointCloud2 msg =
      message.encoding == MessageEncoding::kCdr
          ? ParseCdrPointCloud2(where, message.data.data(), message.data.size())
          : ParseRos1PointCloud2(where, message.data.data(), message.data.size());
  return CloudFromPointCloud2(where, msg);
}

}  // namespace lpir
