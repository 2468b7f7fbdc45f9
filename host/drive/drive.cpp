#include "host/drive/drive.h"

#include <filesystem>

#include "host/drive/chunk_pool.h"
#include "host/drive/db3_reader.h"
#include "host/drive/mcap_reader.h"
#include "host/drive/pointcloud2.h"
#include "host/drive/ros1_bag_reader.h"
#include "host/io/io_error.h"

namespace lpir {

bool IsDriveFile(const std::string& path) {
  const std::string ext = std::filesystem::path(path).extension().string();
  return ext == ".mcap" || ext == ".db3" || ext == ".bag";
}

DriveFormat DriveFormatOf(const std::string& path) {
  const std::string ext = std::filesystem::path(path).extension().string();
  if (ext == ".mcap") return DriveFormat::kMcap;
  if (ext == ".db3") return DriveFormat::kDb3;
  if (ext == ".bag") return DriveFormat::kRos1Bag;
  throw IoError(path, "not a recorded drive: the extension must be .mcap, .db3 or .bag");
}

std::unique_ptr<DriveReader> OpenDrive(const std::string& path, unsigned read_threads) {
  const DriveFormat format = DriveFormatOf(path);
  const unsigned threads = ReadThreads(read_threads);
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
