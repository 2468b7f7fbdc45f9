// ROS 2 SQLite bags (.db3, rosbag2_storage_default_plugins' sqlite3 storage, every schema from
// Dashing's to Jazzy's): tables topics (id, name, type, serialization_format) and messages (id,
// topic_id, timestamp, data), read through libsqlite3 with the file opened read-only and
// immutable (nothing is created or locked; a -wal file left by a recorder that crashed is not
// read). Messages come ordered by timestamp, then id, one row at a time.
//
// OpenDb3: IoError naming the file when it is missing, empty, a folder, not SQLite, or lacks
// those tables or columns. Topics: IoError when the topics cannot be read or the messages
// counted (a damaged page among them included). SelectTopic: IoError for a topic the bag lacks
// (the bag's topics listed) or a serialization_format other than "cdr". Next: a damaged page
// (SQLite's SQLITE_CORRUPT, a page cut off by truncation), a timestamp that is not an integer
// >= 0 or data that is not a BLOB is kDamage naming the file, the message's sequence, its row
// id and the problem, and the next call returns kEnd: SQLite cannot tell which rows a damaged
// page held.
#pragma once
#include <memory>
#include <string>

#include "host/drive/drive.h"

namespace lpir {

std::unique_ptr<DriveReader> OpenDb3(const std::string& path);

}  // namespace lpir
