// The ROS 2 SQLite bag reader: libsqlite3 on the file opened read-only and immutable (no
// locks, no journal or WAL read, nothing ever created), queries prepared once, messages stepped
// one row at a time.
#include "host/drive/db3_reader.h"

#include <sqlite3.h>
#include <sys/stat.h>

#include <algorithm>
#include <cerrno>
#include <climits>
#include <cstring>
#include <deque>
#include <map>
#include <set>
#include <unordered_map>

#include "host/drive/drive_content.h"
#include "host/drive/mcap_writer.h"
#include "host/io/io_error.h"
#include "host/io/point_fields.h"

namespace lpir {

namespace {

// `path` as an SQLite URI ("file:" + the path, every byte but unreserved ones and '/'
// percent-encoded) with immutable=1: the bag is read as it is on disk.
std::string ImmutableUri(const std::string& path) {
  static const char kHex[] = "0123456789ABCDEF";
  std::string uri = "file:";
  for (unsigned char c : path) {
    if ((c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '/' ||
        c == '-' || c == '_' || c == '.' || c == '~') {
      uri += char(c);
    } else {
      uri += '%';
      uri += kHex[c >> 4];
      uri += kHex[c & 15];
    }
  }
  return uri + "?immutable=1";
}

// The VFS every bag is opened through: the default one, except that a read running past the end
// of the file fails (SQLITE_IOERR_READ) instead of returning zeros. SQLite takes the zeros of a
// page cut off by truncation for data (the last page of a message's overflow chain reads as a
// message ending in zeros); failing the read makes it damage. File methods version 1: no shared
// memory, no memory mapping, so every page goes through Read.
struct StrictFile {
  sqlite3_file base;
  int64_t short_read_at;  // offset of the first read that ran past the end; -1 when none
  sqlite3_file* inner() { return reinterpret_cast<sqlite3_file*>(this + 1); }
};

sqlite3_vfs* StrictVfs();
sqlite3_vfs* DefaultVfs() { return static_cast<sqlite3_vfs*>(StrictVfs()->pAppData); }
StrictFile* Strict(sqlite3_file* file) { return reinterpret_cast<StrictFile*>(file); }
sqlite3_file* Inner(sqlite3_file* file) { return Strict(file)->inner(); }

int StrictClose(sqlite3_file* f) { return Inner(f)->pMethods->xClose(Inner(f)); }
int StrictRead(sqlite3_file* f, void* out, int n, sqlite3_int64 offset) {
  const int rc = Inner(f)->pMethods->xRead(Inner(f), out, n, offset);
  // The 100-byte header read of a file shorter than that stays a short read: SQLite then reads
  // the zeros as "not a database" (or, for an empty file, an empty one).
  if (rc != SQLITE_IOERR_SHORT_READ || (offset == 0 && n <= 100)) return rc;
  if (Strict(f)->short_read_at < 0) Strict(f)->short_read_at = offset;
  return SQLITE_IOERR_READ;
}
int StrictWrite(sqlite3_file* f, const void* in, int n, sqlite3_int64 offset) {
  return Inner(f)->pMethods->xWrite(Inner(f), in, n, offset);
}
int StrictTruncate(sqlite3_file* f, sqlite3_int64 size) {
  return Inner(f)->pMethods->xTruncate(Inner(f), size);
}
int StrictSync(sqlite3_file* f, int flags) { return Inner(f)->pMethods->xSync(Inner(f), flags); }
int StrictFileSize(sqlite3_file* f, sqlite3_int64* size) {
  return Inner(f)->pMethods->xFileSize(Inner(f), size);
}
int StrictLock(sqlite3_file* f, int level) { return Inner(f)->pMethods->xLock(Inner(f), level); }
int StrictUnlock(sqlite3_file* f, int level) {
  return Inner(f)->pMethods->xUnlock(Inner(f), level);
}
int StrictCheckReservedLock(sqlite3_file* f, int* out) {
  return Inner(f)->pMethods->xCheckReservedLock(Inner(f), out);
}
int StrictFileControl(sqlite3_file* f, int op, void* arg) {
  return Inner(f)->pMethods->xFileControl(Inner(f), op, arg);
}
int StrictSectorSize(sqlite3_file* f) { return Inner(f)->pMethods->xSectorSize(Inner(f)); }
int StrictDeviceCharacteristics(sqlite3_file* f) {
  return Inner(f)->pMethods->xDeviceCharacteristics(Inner(f));
}

const sqlite3_io_methods kStrictMethods = {1,
                                           StrictClose,
                                           StrictRead,
                                           StrictWrite,
                                           StrictTruncate,
                                           StrictSync,
                                           StrictFileSize,
                                           StrictLock,
                                           StrictUnlock,
                                           StrictCheckReservedLock,
                                           StrictFileControl,
                                           StrictSectorSize,
                                           StrictDeviceCharacteristics,
                                           nullptr,
                                           nullptr,
                                           nullptr,
                                           nullptr,
                                           nullptr,
                                           nullptr};

int StrictOpen(sqlite3_vfs*, sqlite3_filename name, sqlite3_file* file, int flags, int* out_flags) {
  StrictFile* strict = Strict(file);
  strict->base.pMethods = nullptr;
  strict->short_read_at = -1;
  sqlite3_file* inner = strict->inner();
  inner->pMethods = nullptr;
  const int rc = DefaultVfs()->xOpen(DefaultVfs(), name, inner, flags, out_flags);
  if (rc != SQLITE_OK) {
    if (inner->pMethods) inner->pMethods->xClose(inner);
    return rc;
  }
  strict->base.pMethods = &kStrictMethods;
  return SQLITE_OK;
}
int StrictDelete(sqlite3_vfs*, const char* name, int sync) {
  return DefaultVfs()->xDelete(DefaultVfs(), name, sync);
}
int StrictAccess(sqlite3_vfs*, const char* name, int flags, int* out) {
  return DefaultVfs()->xAccess(DefaultVfs(), name, flags, out);
}
int StrictFullPathname(sqlite3_vfs*, const char* name, int n, char* out) {
  return DefaultVfs()->xFullPathname(DefaultVfs(), name, n, out);
}
int StrictRandomness(sqlite3_vfs*, int n, char* out) {
  return DefaultVfs()->xRandomness(DefaultVfs(), n, out);
}
int StrictSleep(sqlite3_vfs*, int microseconds) {
  return DefaultVfs()->xSleep(DefaultVfs(), microseconds);
}
int StrictCurrentTime(sqlite3_vfs*, double* out) {
  return DefaultVfs()->xCurrentTime(DefaultVfs(), out);
}
int StrictGetLastError(sqlite3_vfs*, int n, char* out) {
  return DefaultVfs()->xGetLastError ? DefaultVfs()->xGetLastError(DefaultVfs(), n, out) : 0;
}

// Registered (not as the default) on first use.
sqlite3_vfs* StrictVfs() {
  static sqlite3_vfs* const vfs = [] {
    sqlite3_initialize();
    sqlite3_vfs* inner = sqlite3_vfs_find(nullptr);
    static sqlite3_vfs strict = {};
    strict.iVersion = 1;
    strict.szOsFile = int(sizeof(StrictFile)) + inner->szOsFile;
    strict.mxPathname = inner->mxPathname;
    strict.zName = "lpir-strict-read";
    strict.pAppData = inner;
    strict.xOpen = StrictOpen;
    strict.xDelete = StrictDelete;
    strict.xAccess = StrictAccess;
    strict.xFullPathname = StrictFullPathname;
    strict.xRandomness = StrictRandomness;
    strict.xSleep = StrictSleep;
    strict.xCurrentTime = StrictCurrentTime;
    strict.xGetLastError = StrictGetLastError;
    strict.xDlOpen = inner->xDlOpen;  // never used: extensions are not loaded
    strict.xDlError = inner->xDlError;
    strict.xDlSym = inner->xDlSym;
    strict.xDlClose = inner->xDlClose;
    sqlite3_vfs_register(&strict, 0);
    return &strict;
  }();
  return vfs;
}

class Statement {
 public:
  Statement() = default;
  Statement(const Statement&) = delete;
  Statement& operator=(const Statement&) = delete;
  ~Statement() { sqlite3_finalize(stmt_); }
  sqlite3_stmt** out() {
    sqlite3_finalize(stmt_);
    stmt_ = nullptr;
    return &stmt_;
  }
  sqlite3_stmt* get() const { return stmt_; }

 private:
  sqlite3_stmt* stmt_ = nullptr;
};

// Owns the connection; closed after every statement (declared after it) is finalized.
struct Database {
  sqlite3* db = nullptr;
  Database() = default;
  Database(const Database&) = delete;
  Database& operator=(const Database&) = delete;
  ~Database() { sqlite3_close_v2(db); }
};

// The bag opened as OpenDb3 opens it, and the statement helpers both readers of it use (the
// topic reader, Db3Reader, and the whole-drive one, Db3Content).
class Db3File {
 protected:
  explicit Db3File(const std::string& path) : path_(path) {
    struct stat info;
    if (stat(path.c_str(), &info) != 0) {
      const int error = errno;
      throw IoError(path,
                    error == ENOENT ? std::string("no such file")
                                    : std::string("cannot open: ") + std::strerror(error),
                    error);
    }
    if (S_ISDIR(info.st_mode)) throw IoError(path, "is a folder, not a .db3 file", EISDIR);
    if (info.st_size == 0) throw IoError(path, "empty file, not a ROS 2 bag");
    const int rc = sqlite3_open_v2(ImmutableUri(path).c_str(), &database_.db,
                                   SQLITE_OPEN_READONLY | SQLITE_OPEN_URI | SQLITE_OPEN_NOMUTEX,
                                   StrictVfs()->zName);
    db_ = database_.db;
    if (rc != SQLITE_OK) {
      throw IoError(path, "cannot open as SQLite: " +
                              std::string(db_ ? sqlite3_errmsg(db_) : sqlite3_errstr(rc)));
    }
    // No row in the file can be longer than the file: a larger length is corruption, reported
    // (SQLITE_TOOBIG) before SQLite allocates it.
    const long long cap = std::max<long long>(info.st_size, 1 << 20);
    sqlite3_limit(db_, SQLITE_LIMIT_LENGTH, int(std::min<long long>(cap, INT_MAX)));
    // Checks each page's cell sizes as it is read: damage is found, not read past.
    sqlite3_exec(db_, "PRAGMA cell_size_check = ON", nullptr, nullptr, nullptr);
    CheckSchema();
  }

  // SQLite's message for the last error, saying so when it came from the file ending early.
  std::string Error() const {
    std::string error = sqlite3_errmsg(db_);
    sqlite3_file* file = nullptr;
    if (sqlite3_file_control(db_, "main", SQLITE_FCNTL_FILE_POINTER, &file) == SQLITE_OK && file &&
        file->pMethods == &kStrictMethods) {
      const int64_t at = Strict(file)->short_read_at;
      if (at >= 0) {
        error +=
            " (the file is truncated: a page at byte " + std::to_string(at) + " runs past its end)";
      }
    }
    return error;
  }

  // IoError naming the file unless it is SQLite with the tables and columns read here.
  void CheckSchema() {
    const struct {
      const char* table;
      std::vector<const char*> columns;
    } kTables[] = {{"topics", {"id", "name", "type", "serialization_format"}},
                   {"messages", {"id", "topic_id", "timestamp", "data"}}};
    for (const auto& table : kTables) {
      const std::set<std::string> columns = Columns(table.table);
      if (columns.empty()) {
        throw IoError(path_, std::string("not a ROS 2 bag: no '") + table.table + "' table");
      }
      for (const char* column : table.columns) {
        if (!columns.count(column)) {
          throw IoError(path_, std::string("not a ROS 2 bag: table '") + table.table +
                                   "' has no column '" + column + "'");
        }
      }
    }
  }

  // The columns of `table` (none when there is no such table).
  std::set<std::string> Columns(const char* table) {
    Statement info;
    Prepare(&info, std::string("PRAGMA table_info(") + table + ")");
    std::set<std::string> columns;
    while (Step(info, "reading the schema")) columns.insert(Text(info, 1));
    return columns;
  }

  void Prepare(Statement* statement, const std::string& sql) {
    if (sqlite3_prepare_v2(db_, sql.c_str(), -1, statement->out(), nullptr) != SQLITE_OK) {
      throw IoError(path_, "not a readable ROS 2 bag: " + Error());
    }
  }
  // One row (true) or the end (false); IoError naming the file and `doing` on an error.
  bool Step(const Statement& statement, const char* doing) {
    const int rc = sqlite3_step(statement.get());
    if (rc == SQLITE_ROW) return true;
    if (rc == SQLITE_DONE) return false;
    throw IoError(path_, std::string(doing) + ": " + Error());
  }
  static std::string Text(const Statement& statement, int column) {
    const auto* text = sqlite3_column_text(statement.get(), column);
    const int size = sqlite3_column_bytes(statement.get(), column);
    return text ? std::string(reinterpret_cast<const char*>(text), size_t(size)) : std::string();
  }

  // A message row: `scan` selects id, timestamp (an integer >= 0) and topic_id in the order
  // wanted; `fetch` selects the data (a BLOB) of the row whose id is bound as ?1.
  struct Row {
    int64_t id = 0, timestamp = 0, topic_id = 0;
    std::vector<uint8_t> data;
    std::string problem, where;  // kBad: what is wrong, and "row id N" when the row is known
  };
  enum class RowStep { kRow, kEnd, kBad };
  // The next row of `scan` with its data, the end, or a row (or page) that cannot be read.
  RowStep NextRow(const Statement& scan, const Statement& fetch, Row* row) {
    const int rc = sqlite3_step(scan.get());
    if (rc == SQLITE_DONE) return RowStep::kEnd;
    if (rc != SQLITE_ROW) return Bad(row, Error());
    row->id = sqlite3_column_int64(scan.get(), 0);
    row->where = "row id " + std::to_string(row->id);
    if (sqlite3_column_type(scan.get(), 1) != SQLITE_INTEGER)
      return Bad(row, "the timestamp is not an integer");
    row->timestamp = sqlite3_column_int64(scan.get(), 1);
    if (row->timestamp < 0) return Bad(row, "negative timestamp " + std::to_string(row->timestamp));
    row->topic_id = sqlite3_column_int64(scan.get(), 2);
    sqlite3_reset(fetch.get());
    sqlite3_bind_int64(fetch.get(), 1, row->id);
    const int fetched = sqlite3_step(fetch.get());
    if (fetched != SQLITE_ROW)
      return Bad(row, fetched == SQLITE_DONE ? "the row vanished" : Error());
    if (sqlite3_column_type(fetch.get(), 0) != SQLITE_BLOB)
      return Bad(row, "the data is not a BLOB");
    const auto* data = static_cast<const uint8_t*>(sqlite3_column_blob(fetch.get(), 0));
    const int size = sqlite3_column_bytes(fetch.get(), 0);
    if (size > 0 && !data) return Bad(row, Error());
    row->data.assign(data, data + size);
    sqlite3_reset(fetch.get());
    return RowStep::kRow;
  }
  static RowStep Bad(Row* row, const std::string& problem) {
    row->problem = problem;
    return RowStep::kBad;
  }

  std::string path_;
  Database database_;
  sqlite3* db_ = nullptr;  // database_.db
};

class Db3Reader : public DriveReader, private Db3File {
 public:
  explicit Db3Reader(const std::string& path) : Db3File(path) {}

  std::vector<DriveTopic> Topics() override {
    Statement topics, counts;
    Prepare(&topics, "SELECT id, name, type, serialization_format FROM topics ORDER BY id");
    std::vector<DriveTopic> out;
    std::unordered_map<int64_t, size_t> index;  // topic id -> entry of out
    while (Step(topics, "reading the topics table")) {
      DriveTopic topic;
      topic.name = Text(topics, 1);
      topic.type = Text(topics, 2);
      topic.encoding = Text(topics, 3);
      index.emplace(sqlite3_column_int64(topics.get(), 0), out.size());
      out.push_back(std::move(topic));
    }
    Prepare(&counts, "SELECT topic_id, COUNT(*) FROM messages GROUP BY topic_id");
    while (Step(counts, "counting the messages")) {
      const auto entry = index.find(sqlite3_column_int64(counts.get(), 0));
      if (entry != index.end()) {
        out[entry->second].messages = uint64_t(sqlite3_column_int64(counts.get(), 1));
      }
    }
    return out;
  }

  void SelectTopic(const std::string& topic) override {
    Statement formats;
    Prepare(&formats, "SELECT DISTINCT serialization_format FROM topics WHERE name = ?1");
    sqlite3_bind_text(formats.get(), 1, topic.c_str(), int(topic.size()), SQLITE_TRANSIENT);
    std::set<std::string> found;
    while (Step(formats, "reading the topics table")) found.insert(Text(formats, 0));
    if (found.empty()) {
      std::string names;
      for (const std::string& name : TopicNames())
        names += (names.empty() ? "" : ", ") + Quote(name);
      throw IoError(path_, "no topic " + Quote(topic) + "; the bag has " +
                               (names.empty() ? std::string("no topics") : names));
    }
    for (const std::string& format : found) {
      if (format != "cdr") {
        throw IoError(path_, "topic " + Quote(topic) + " has serialization_format " +
                                 Quote(format) + "; only 'cdr' is read");
      }
    }
    // Ids and timestamps only in the ordering (a sort, when no index serves it, holds no
    // message data); each message's data is fetched by id as it is yielded.
    Prepare(&scan_,
            "SELECT id, timestamp, topic_id FROM messages WHERE topic_id IN "
            "(SELECT id FROM topics WHERE name = ?1) ORDER BY timestamp, id");
    sqlite3_bind_text(scan_.get(), 1, topic.c_str(), int(topic.size()), SQLITE_TRANSIENT);
    Prepare(&fetch_, "SELECT data FROM messages WHERE id = ?1");
    topic_ = topic;
    sequence_ = 0;
    ended_ = false;
  }

  // SQLite pages are no chunks: a .db3 is read whole.
  uint64_t ChunkCount() override { return 0; }
  bool ChunksIndexed() override { return false; }
  void SelectChunks(uint64_t first, uint64_t last) override {
    throw IoError(path_, "a .db3 has no chunks: chunks " + std::to_string(first) + " to " +
                             std::to_string(last) + " cannot be chosen; read it whole");
  }

  DriveStep Next(DriveMessage* message, std::string* problem) override {
    if (!scan_.get()) throw IoError(path_, "Next before SelectTopic");
    if (ended_) return DriveStep::kEnd;
    Row row;
    const RowStep step = NextRow(scan_, fetch_, &row);
    if (step == RowStep::kEnd) {
      ended_ = true;
      return DriveStep::kEnd;
    }
    if (step == RowStep::kBad) return Damage(problem, row.problem, row.where);
    message->sequence = sequence_++;
    message->log_time_ns = uint64_t(row.timestamp);
    message->topic = topic_;
    message->encoding = MessageEncoding::kCdr;
    message->data = std::move(row.data);
    return DriveStep::kMessage;
  }

 private:
  // Reports the message the scan was at as damaged; the next call returns kEnd (SQLite cannot
  // tell which rows a damaged page held).
  DriveStep Damage(std::string* problem, const std::string& what, const std::string& row) {
    ended_ = true;
    *problem = path_ + ": message " + std::to_string(sequence_) + " of topic " + Quote(topic_) +
               (row.empty() ? std::string() : " (" + row + ")") + ": " + what;
    return DriveStep::kDamage;
  }

  std::vector<std::string> TopicNames() {
    Statement names;
    Prepare(&names, "SELECT name FROM topics ORDER BY id");
    std::vector<std::string> out;
    while (Step(names, "reading the topics table")) out.push_back(Text(names, 0));
    return out;
  }

  Statement scan_, fetch_;
  std::string topic_;
  uint64_t sequence_ = 0;
  bool ended_ = false;
};

// The bag's whole content (drive_content.h): a schema per type and a channel per topic row, then
// every message by timestamp, then row id. A damaged row ends it, as it ends Db3Reader.
class Db3Content : public DriveContent, private Db3File {
 public:
  explicit Db3Content(const std::string& path) : Db3File(path) {
    const std::map<std::string, std::pair<std::string, std::string>> definitions = Definitions();
    const bool qos = Columns("topics").count("offered_qos_profiles") > 0;
    Statement topics;
    Prepare(&topics, std::string("SELECT id, name, type, serialization_format") +
                         (qos ? ", offered_qos_profiles" : "") + " FROM topics ORDER BY id");
    std::map<std::string, uint16_t> schema_ids;  // type -> id
    while (Step(topics, "reading the topics table")) {
      if (channels_.size() >= UINT16_MAX)
        throw IoError(path_, "more than 65535 topics; MCAP's channel ids are 16 bits");
      DriveChannel c;
      c.id = uint16_t(channels_.size() + 1);
      c.topic = Text(topics, 1);
      const std::string type = Text(topics, 2);
      c.message_encoding = Text(topics, 3);
      if (qos) c.metadata.emplace_back("offered_qos_profiles", Text(topics, 4));
      auto [schema, fresh] = schema_ids.emplace(type, uint16_t(schema_ids.size() + 1));
      if (fresh) {
        const auto known = definitions.find(type);
        DriveSchema s{schema->second, type, "", ""};
        if (known != definitions.end()) {
          s.encoding = known->second.first;
          s.data = known->second.second;
        } else if (type == "sensor_msgs/msg/PointCloud2") {
          s.encoding = "ros2msg";
          s.data = PointCloud2Ros2MsgDefinition();
        }
        queue_.push_back(std::move(s));
      }
      c.schema_id = schema->second;
      channels_.emplace(sqlite3_column_int64(topics.get(), 0), Channel{c.id, 0});
      queue_.push_back(std::move(c));
    }
    Prepare(&scan_, "SELECT id, timestamp, topic_id FROM messages ORDER BY timestamp, id");
    Prepare(&fetch_, "SELECT data FROM messages WHERE id = ?1");
  }

  const std::string& profile() const override { return profile_; }

  ContentStep Next(DriveRecord* record, std::string* problem) override {
    if (!queue_.empty()) {
      *record = std::move(queue_.front());
      queue_.pop_front();
      return ContentStep::kRecord;
    }
    for (;;) {
      if (ended_) return ContentStep::kEnd;
      Row row;
      const RowStep step = NextRow(scan_, fetch_, &row);
      if (step == RowStep::kEnd) ended_ = true;
      if (step == RowStep::kBad) {
        ended_ = true;
        *problem = path_ + ": " + row.where + (row.where.empty() ? "" : ": ") + row.problem;
        return ContentStep::kDamage;
      }
      if (step != RowStep::kRow) continue;
      const auto channel = channels_.find(row.topic_id);
      if (channel == channels_.end()) {
        if (!orphans_.insert(row.topic_id).second) continue;
        *problem = path_ + ": " + row.where + ": a message of topic id " +
                   std::to_string(row.topic_id) +
                   ", which the topics table lacks, left out with every later one of it";
        return ContentStep::kDamage;
      }
      DriveRecordMessage m;
      m.channel_id = channel->second.id;
      m.sequence = channel->second.messages++;
      m.log_time_ns = m.publish_time_ns = uint64_t(row.timestamp);
      m.data = std::move(row.data);
      *record = std::move(m);
      return ContentStep::kRecord;
    }
  }

 private:
  struct Channel {
    uint16_t id;
    uint32_t messages;  // yielded so far: the next one's sequence
  };

  // type -> (encoding, definition) from rosbag2's message_definitions table (Iron and later), when
  // the bag has it and the encoding is ros2msg or ros2idl.
  std::map<std::string, std::pair<std::string, std::string>> Definitions() {
    std::map<std::string, std::pair<std::string, std::string>> out;
    const std::set<std::string> columns = Columns("message_definitions");
    if (!columns.count("topic_type") || !columns.count("encoding") ||
        !columns.count("encoded_message_definition"))
      return out;
    Statement rows;
    Prepare(&rows,
            "SELECT topic_type, encoding, encoded_message_definition FROM message_definitions");
    while (Step(rows, "reading the message_definitions table")) {
      const std::string encoding = Text(rows, 1);
      if (encoding == "ros2msg" || encoding == "ros2idl")
        out.emplace(Text(rows, 0), std::make_pair(encoding, Text(rows, 2)));
    }
    return out;
  }

  const std::string profile_ = "ros2";
  std::map<int64_t, Channel> channels_;  // topic row id -> its channel
  std::set<int64_t> orphans_;            // topic ids of messages without a topic row, reported
  std::deque<DriveRecord> queue_;        // the schemas and channels, first
  Statement scan_, fetch_;
  bool ended_ = false;
};

}  // namespace

std::unique_ptr<DriveReader> OpenDb3(const std::string& path) {
  return std::make_unique<Db3Reader>(path);
}

std::unique_ptr<DriveContent> OpenDb3Content(const std::string& path) {
  return std::make_unique<Db3Content>(path);
}

}  // namespace lpir
