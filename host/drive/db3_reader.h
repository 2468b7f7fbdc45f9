// ROS 2 SQLite bags (.db3, rosbag2_storage_default_plugins' sqlite3 storage): tables topics
// (id, name, type, serialization_format) and messages (topic_id, timestamp, data), read through
// libsqlite3 opened read-only. Messages come ordered by timestamp, then id.
#pragma once
#include <memory>
#include <string>

#include "host/drive/drive.h"

namespace lpir {

std::unique_ptr<DriveReader> OpenDb3(const std::string& path);

}  // namespace lpir
