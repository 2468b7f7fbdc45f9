// The ROS 2 SQLite bag reader (host/drive/db3_reader.h) on bags written here with libsqlite3 in
// rosbag2's schemas: topics and counts, message order, the topic and format errors, files that
// are not bags, and truncated or corrupted databases (damage reported, never a crash).
#include <gtest/gtest.h>
#include <sqlite3.h>

#include <filesystem>
#include <string>
#include <vector>

#include "host/drive/db3_reader.h"
#include "host/io/io_error.h"
#include "tests/io_test_helpers.h"
#include "tests/test_util.h"

namespace lpir {
namespace {

using test::ReadRaw;
using test::ThrowsIoError;
using test::WriteRaw;

// The topics table of each rosbag2 generation.
enum class Schema { kDashing, kHumble, kJazzy };

// Writes a .db3 with libsqlite3: the topics, then messages appended in the order given.
class BagWriter {
 public:
  BagWriter(const std::string& path, Schema schema, bool timestamp_index = true) {
    EXPECT_EQ(sqlite3_open(path.c_str(), &db_), SQLITE_OK);
    Exec("PRAGMA page_size = 4096");
    if (schema == Schema::kDashing) {
      Exec(
          "CREATE TABLE topics(id INTEGER PRIMARY KEY, name TEXT NOT NULL, type TEXT NOT NULL, "
          "serialization_format TEXT NOT NULL)");
    } else if (schema == Schema::kHumble) {
      Exec(
          "CREATE TABLE topics(id INTEGER PRIMARY KEY, name TEXT NOT NULL, type TEXT NOT NULL, "
          "serialization_format TEXT NOT NULL, offered_qos_profiles TEXT NOT NULL)");
    } else {
      Exec("CREATE TABLE schema(schema_version INTEGER PRIMARY KEY, ros_distro TEXT NOT NULL)");
      Exec("INSERT INTO schema VALUES (4, 'jazzy')");
      Exec(
          "CREATE TABLE metadata(id INTEGER PRIMARY KEY, metadata_version INTEGER NOT NULL, "
          "metadata TEXT NOT NULL)");
      Exec(
          "CREATE TABLE topics(id INTEGER PRIMARY KEY, name TEXT NOT NULL, type TEXT NOT NULL, "
          "serialization_format TEXT NOT NULL, offered_qos_profiles TEXT NOT NULL, "
          "type_description_hash TEXT NOT NULL)");
    }
    Exec(
        "CREATE TABLE messages(id INTEGER PRIMARY KEY, topic_id INTEGER NOT NULL, "
        "timestamp INTEGER NOT NULL, data BLOB NOT NULL)");
    if (timestamp_index) Exec("CREATE INDEX timestamp_idx ON messages (timestamp ASC)");
    schema_ = schema;
  }
  ~BagWriter() { sqlite3_close(db_); }

  void Topic(int id, const std::string& name,
             const std::string& type = "sensor_msgs/msg/PointCloud2",
             const std::string& format = "cdr") {
    std::string sql = "INSERT INTO topics VALUES (" + std::to_string(id) + ", " + Q(name) + ", " +
                      Q(type) + ", " + Q(format);
    if (schema_ != Schema::kDashing) sql += ", ''";
    if (schema_ == Schema::kJazzy) sql += ", 'RIHS01_00'";
    Exec(sql + ")");
  }
  void Message(int topic_id, int64_t timestamp, const std::vector<uint8_t>& data) {
    sqlite3_stmt* stmt = nullptr;
    ASSERT_EQ(sqlite3_prepare_v2(db_,
                                 "INSERT INTO messages (topic_id, timestamp, data) VALUES "
                                 "(?1, ?2, ?3)",
                                 -1, &stmt, nullptr),
              SQLITE_OK);
    sqlite3_bind_int(stmt, 1, topic_id);
    sqlite3_bind_int64(stmt, 2, timestamp);
    sqlite3_bind_blob(stmt, 3, data.data(), int(data.size()), SQLITE_TRANSIENT);
    EXPECT_EQ(sqlite3_step(stmt), SQLITE_DONE) << sqlite3_errmsg(db_);
    sqlite3_finalize(stmt);
  }
  void Exec(const std::string& sql) {
    char* error = nullptr;
    EXPECT_EQ(sqlite3_exec(db_, sql.c_str(), nullptr, nullptr, &error), SQLITE_OK)
        << sql << ": " << (error ? error : "");
    sqlite3_free(error);
  }

 private:
  static std::string Q(const std::string& text) { return "'" + text + "'"; }
  sqlite3* db_ = nullptr;
  Schema schema_ = Schema::kHumble;
};

// Message bytes that say which message they are: a CDR_LE header, then `size` bytes from `tag`.
std::vector<uint8_t> Payload(int tag, size_t size = 16) {
  std::vector<uint8_t> data = {0x00, 0x01, 0x00, 0x00};
  for (size_t i = 0; i < size; ++i) data.push_back(uint8_t(tag * 31 + i * 7));
  return data;
}

struct Read {
  std::vector<DriveMessage> messages;
  std::vector<std::string> damage;
  bool ended = false;
};

// Next until kEnd (at most `limit` calls); a kDamage is recorded and reading goes on.
Read ReadAll(DriveReader* reader, size_t limit = 100000) {
  Read read;
  for (size_t call = 0; call < limit; ++call) {
    DriveMessage message;
    std::string problem;
    const DriveStep step = reader->Next(&message, &problem);
    if (step == DriveStep::kEnd) {
      read.ended = true;
      break;
    }
    if (step == DriveStep::kDamage) read.damage.push_back(problem);
    if (step == DriveStep::kMessage) read.messages.push_back(std::move(message));
  }
  return read;
}

class Db3Test : public ::testing::Test {
 protected:
  std::string Path(const std::string& name) const { return dir_.path + "/" + name; }
  test::ScopedDir dir_;
};

TEST_F(Db3Test, ListsTopicsWithTypesFormatsAndCounts) {
  for (Schema schema : {Schema::kDashing, Schema::kHumble, Schema::kJazzy}) {
    SCOPED_TRACE(int(schema));
    const std::string path = Path("bag" + std::to_string(int(schema)) + ".db3");
    {
      BagWriter bag(path, schema);
      bag.Topic(1, "/points");
      bag.Topic(2, "/imu", "sensor_msgs/msg/Imu");
      bag.Topic(3, "/empty", "std_msgs/msg/String");
      for (int i = 0; i < 5; ++i) bag.Message(1, 100 + i, Payload(i));
      for (int i = 0; i < 3; ++i) bag.Message(2, 50 + i, Payload(10 + i));
    }
    const auto reader = OpenDb3(path);
    const std::vector<DriveTopic> topics = reader->Topics();
    ASSERT_EQ(topics.size(), 3u);
    EXPECT_EQ(topics[0].name, "/points");
    EXPECT_EQ(topics[0].type, "sensor_msgs/msg/PointCloud2");
    EXPECT_EQ(topics[0].encoding, "cdr");
    EXPECT_EQ(topics[0].messages, 5u);
    EXPECT_EQ(topics[1].name, "/imu");
    EXPECT_EQ(topics[1].type, "sensor_msgs/msg/Imu");
    EXPECT_EQ(topics[1].messages, 3u);
    EXPECT_EQ(topics[2].messages, 0u);
    reader->SelectTopic("/empty");
    const Read empty = ReadAll(reader.get());
    EXPECT_TRUE(empty.ended);
    EXPECT_TRUE(empty.messages.empty());
  }
}

TEST_F(Db3Test, YieldsTheTopicsMessagesByTimestampThenId) {
  for (bool index : {true, false}) {
    SCOPED_TRACE(index ? "with timestamp_idx" : "without an index");
    const std::string path = Path(index ? "indexed.db3" : "plain.db3");
    // (timestamp, tag) in insertion (= id) order; equal timestamps keep id order.
    const std::vector<std::pair<int64_t, int>> logged = {
        {300, 0}, {100, 1}, {200, 2}, {100, 3}, {1700000000123456789, 4}, {0, 5}};
    {
      BagWriter bag(path, Schema::kHumble, index);
      bag.Topic(1, "/points");
      bag.Topic(2, "/other");
      for (const auto& [stamp, tag] : logged) {
        bag.Message(1, stamp, Payload(tag, size_t(tag) * 3));
        bag.Message(2, stamp + 1, Payload(100 + tag));
      }
    }
    const auto reader = OpenDb3(path);
    reader->SelectTopic("/points");
    const Read read = ReadAll(reader.get());
    EXPECT_TRUE(read.ended);
    EXPECT_TRUE(read.damage.empty());
    const std::vector<int> order = {5, 1, 3, 2, 0, 4};
    ASSERT_EQ(read.messages.size(), order.size());
    for (size_t i = 0; i < order.size(); ++i) {
      const DriveMessage& m = read.messages[i];
      EXPECT_EQ(m.sequence, i);
      EXPECT_EQ(m.log_time_ns, uint64_t(logged[size_t(order[i])].first));
      EXPECT_EQ(m.topic, "/points");
      EXPECT_EQ(m.encoding, MessageEncoding::kCdr);
      EXPECT_EQ(m.data, Payload(order[i], size_t(order[i]) * 3)) << i;
    }
    // Selecting again starts over, and another topic yields only its own.
    reader->SelectTopic("/other");
    const Read other = ReadAll(reader.get());
    ASSERT_EQ(other.messages.size(), logged.size());
    EXPECT_EQ(other.messages[0].data, Payload(105));
    EXPECT_EQ(other.messages[0].sequence, 0u);
  }
}

TEST_F(Db3Test, StreamsLargeMessagesThatSpanManyPages) {
  const std::string path = Path("large.db3");
  {
    BagWriter bag(path, Schema::kHumble);
    bag.Topic(1, "/points");
    bag.Exec("BEGIN");
    for (int i = 0; i < 20; ++i) bag.Message(1, i, Payload(i, 100000 + size_t(i)));
    bag.Exec("COMMIT");
  }
  const auto reader = OpenDb3(path);
  EXPECT_EQ(reader->Topics()[0].messages, 20u);
  reader->SelectTopic("/points");
  const Read read = ReadAll(reader.get());
  ASSERT_EQ(read.messages.size(), 20u);
  for (int i = 0; i < 20; ++i)
    EXPECT_EQ(read.messages[size_t(i)].data, Payload(i, 100000 + size_t(i)));
}

TEST_F(Db3Test, AMissingTopicListsTheBagsTopics) {
  const std::string path = Path("bag.db3");
  {
    BagWriter bag(path, Schema::kHumble);
    bag.Topic(1, "/points");
    bag.Topic(2, "/imu");
  }
  const auto reader = OpenDb3(path);
  EXPECT_TRUE(ThrowsIoError([&] { reader->SelectTopic("/velodyne_points"); }, path,
                            {"no topic '/velodyne_points'", "'/points', '/imu'"}));
  EXPECT_TRUE(ThrowsIoError(
      [&] {
        DriveMessage m;
        std::string p;
        reader->Next(&m, &p);
      },
      path, {"before SelectTopic"}));
}

TEST_F(Db3Test, AnotherSerializationFormatIsAnErrorAtSelectTopic) {
  const std::string path = Path("bag.db3");
  {
    BagWriter bag(path, Schema::kHumble);
    bag.Topic(1, "/points", "sensor_msgs/msg/PointCloud2", "json");
    bag.Message(1, 1, Payload(1));
  }
  const auto reader = OpenDb3(path);
  EXPECT_EQ(reader->Topics()[0].encoding, "json");
  EXPECT_TRUE(ThrowsIoError([&] { reader->SelectTopic("/points"); }, path,
                            {"serialization_format 'json'", "only 'cdr'"}));
}

TEST_F(Db3Test, FilesThatAreNotBagsAreIoErrorsNamingTheFile) {
  const std::string missing = Path("missing.db3");
  EXPECT_TRUE(ThrowsIoError([&] { OpenDb3(missing); }, missing, {"no such file"}));
  EXPECT_FALSE(std::filesystem::exists(missing)) << "opening must never create the file";
  EXPECT_TRUE(ThrowsIoError([&] { OpenDb3(dir_.path); }, dir_.path, {"folder"}));

  const std::string text = Path("text.db3");
  WriteRaw(text, std::string(5000, 'x'));
  EXPECT_TRUE(ThrowsIoError([&] { OpenDb3(text); }, text, {"not a database"}));
  const std::string empty = Path("empty.db3");
  WriteRaw(empty, "");
  EXPECT_TRUE(ThrowsIoError([&] { OpenDb3(empty); }, empty, {"empty file"}));
  const std::string short_file = Path("short.db3");
  WriteRaw(short_file, std::string("SQLite format 3\0", 16) + std::string(20, '\1'));
  EXPECT_TRUE(ThrowsIoError([&] { OpenDb3(short_file); }, short_file, {}));
  const std::string no_tables = Path("no_tables.db3");
  {
    sqlite3* db = nullptr;
    ASSERT_EQ(sqlite3_open(no_tables.c_str(), &db), SQLITE_OK);
    sqlite3_exec(db, "CREATE TABLE other(a INTEGER)", nullptr, nullptr, nullptr);
    sqlite3_close(db);
  }
  EXPECT_TRUE(ThrowsIoError([&] { OpenDb3(no_tables); }, no_tables, {"no 'topics' table"}));

  const std::string no_messages = Path("no_messages.db3");
  {
    sqlite3* db = nullptr;
    ASSERT_EQ(sqlite3_open(no_messages.c_str(), &db), SQLITE_OK);
    sqlite3_exec(db,
                 "CREATE TABLE topics(id INTEGER PRIMARY KEY, name TEXT, type TEXT, "
                 "serialization_format TEXT)",
                 nullptr, nullptr, nullptr);
    sqlite3_close(db);
  }
  EXPECT_TRUE(ThrowsIoError([&] { OpenDb3(no_messages); }, no_messages, {"no 'messages' table"}));

  const std::string no_format = Path("no_format.db3");
  {
    sqlite3* db = nullptr;
    ASSERT_EQ(sqlite3_open(no_format.c_str(), &db), SQLITE_OK);
    sqlite3_exec(db,
                 "CREATE TABLE topics(id INTEGER PRIMARY KEY, name TEXT, type TEXT); "
                 "CREATE TABLE messages(id INTEGER PRIMARY KEY, topic_id INTEGER, "
                 "timestamp INTEGER, data BLOB)",
                 nullptr, nullptr, nullptr);
    sqlite3_close(db);
  }
  EXPECT_TRUE(ThrowsIoError([&] { OpenDb3(no_format); }, no_format,
                            {"table 'topics' has no column 'serialization_format'"}));
}

TEST_F(Db3Test, PathsWithUriCharactersOpen) {
  const std::string path = Path("a ?b#c%41&d=1.db3");
  {
    BagWriter bag(path, Schema::kHumble);
    bag.Topic(1, "/points");
    bag.Message(1, 7, Payload(7));
  }
  const auto reader = OpenDb3(path);
  EXPECT_EQ(reader->Topics().at(0).messages, 1u);
  EXPECT_FALSE(std::filesystem::exists(Path("a "))) << "the path was cut at '?'";
}

TEST_F(Db3Test, ReadsAClosedWalModeBag) {
  const std::string path = Path("wal.db3");
  {
    BagWriter bag(path, Schema::kHumble);
    bag.Exec("PRAGMA journal_mode = WAL");
    bag.Topic(1, "/points");
    for (int i = 0; i < 4; ++i) bag.Message(1, i, Payload(i));
  }
  const auto reader = OpenDb3(path);
  reader->SelectTopic("/points");
  EXPECT_EQ(ReadAll(reader.get()).messages.size(), 4u);
}

TEST_F(Db3Test, MalformedRowsAreDamageNamingTheMessage) {
  const std::string path = Path("rows.db3");
  {
    BagWriter bag(path, Schema::kHumble);
    bag.Topic(1, "/points");
    bag.Topic(2, "/text");
    bag.Message(1, 1, Payload(1));
    bag.Message(1, 2, Payload(2));
    bag.Exec("INSERT INTO messages (topic_id, timestamp, data) VALUES (1, 3, 'not a blob')");
    bag.Message(1, 4, Payload(4));
    bag.Message(2, -5, Payload(5));
  }
  const auto reader = OpenDb3(path);
  reader->SelectTopic("/points");
  Read read = ReadAll(reader.get());
  EXPECT_TRUE(read.ended);
  ASSERT_EQ(read.messages.size(), 2u);
  ASSERT_EQ(read.damage.size(), 1u);
  EXPECT_NE(read.damage[0].find(path + ": message 2 of topic '/points'"), std::string::npos)
      << read.damage[0];
  EXPECT_NE(read.damage[0].find("not a BLOB"), std::string::npos) << read.damage[0];
  reader->SelectTopic("/text");
  read = ReadAll(reader.get());
  ASSERT_EQ(read.damage.size(), 1u);
  EXPECT_NE(read.damage[0].find("negative timestamp -5"), std::string::npos) << read.damage[0];
}

// A bag of `count` messages of `size` bytes each (spanning overflow pages), the message with tag i
// holding at byte 4 + size / 2 a marker that names it.
std::vector<std::vector<uint8_t>> WriteBigBag(const std::string& path, int count, size_t size) {
  std::vector<std::vector<uint8_t>> messages;
  BagWriter bag(path, Schema::kHumble);
  bag.Topic(1, "/points");
  bag.Exec("BEGIN");
  for (int i = 0; i < count; ++i) {
    std::vector<uint8_t> data = Payload(i, size);
    const std::string marker = "MARK" + std::to_string(1000 + i);
    std::copy(marker.begin(), marker.end(), data.begin() + 4 + long(size / 2));
    bag.Message(1, 1000 + i, data);
    messages.push_back(data);
  }
  bag.Exec("COMMIT");
  return messages;
}

TEST_F(Db3Test, ABrokenOverflowPageIsDamageAfterEveryMessageBeforeIt) {
  const std::string path = Path("broken.db3");
  const auto written = WriteBigBag(path, 12, 20000);
  std::string bytes = ReadRaw(path);
  const size_t at = bytes.find("MARK1005");
  ASSERT_NE(at, std::string::npos);
  // The overflow page holding message 5's marker points at a page past the end of the file.
  const size_t page = at / 4096 * 4096;
  bytes.replace(page, 4, std::string("\x7f\xff\xff\xff", 4));
  WriteRaw(path, bytes);
  const auto reader = OpenDb3(path);
  EXPECT_EQ(reader->Topics().at(0).messages, 12u);
  reader->SelectTopic("/points");
  const Read read = ReadAll(reader.get());
  EXPECT_TRUE(read.ended);
  ASSERT_EQ(read.messages.size(), 5u);
  for (size_t i = 0; i < 5; ++i) EXPECT_EQ(read.messages[i].data, written[i]);
  ASSERT_EQ(read.damage.size(), 1u);
  EXPECT_NE(read.damage[0].find(path + ": message 5 of topic '/points'"), std::string::npos)
      << read.damage[0];
}

TEST_F(Db3Test, TruncatedFilesYieldOnlyIntactMessagesThenStop) {
  const std::string path = Path("whole.db3");
  const auto written = WriteBigBag(path, 8, 9000);
  const std::string bytes = ReadRaw(path);
  const std::string cut = Path("cut.db3");
  size_t opened = 0, damaged = 0, truncated = 0;
  for (size_t size = 0; size < bytes.size(); size += 1021) {
    SCOPED_TRACE(size);
    WriteRaw(cut, bytes.substr(0, size));
    try {
      const auto reader = OpenDb3(cut);
      reader->SelectTopic("/points");
      ++opened;
      const Read read = ReadAll(reader.get());
      EXPECT_TRUE(read.ended);
      EXPECT_LE(read.damage.size(), 1u);
      damaged += read.damage.size();
      for (const std::string& problem : read.damage) {
        EXPECT_NE(problem.find(cut + ": message " + std::to_string(read.messages.size())),
                  std::string::npos)
            << problem;
        truncated += problem.find("truncated") != std::string::npos;
      }
      ASSERT_LE(read.messages.size(), written.size());
      for (size_t i = 0; i < read.messages.size(); ++i) {
        EXPECT_EQ(read.messages[i].data, written[i]) << i;
      }
      if (read.damage.empty()) {
        EXPECT_EQ(read.messages.size(), written.size());
      }
    } catch (const IoError& e) {
      EXPECT_NE(std::string(e.what()).find(cut), std::string::npos) << e.what();
    }
  }
  EXPECT_GT(opened, 0u);
  EXPECT_GT(damaged, 0u);
  EXPECT_GT(truncated, 0u);
}

TEST_F(Db3Test, CorruptingAnyPageNeverCrashes) {
  const std::string path = Path("whole.db3");
  WriteBigBag(path, 6, 6000);
  const std::string bytes = ReadRaw(path);
  const std::string bad = Path("bad.db3");
  size_t reports = 0;
  for (size_t page = 0; page < bytes.size() / 4096; ++page) {
    for (size_t offset : {0, 1, 8, 100, 2000}) {
      SCOPED_TRACE(::testing::Message() << "page " << page << " offset " << offset);
      std::string damaged = bytes;
      for (size_t k = 0; k < 8; ++k) damaged[page * 4096 + offset + k] ^= char(0xA5);
      WriteRaw(bad, damaged);
      EXPECT_TRUE(test::ReturnsOrThrowsIoError([&] {
        const auto reader = OpenDb3(bad);
        for (const DriveTopic& topic : reader->Topics()) {
          try {
            reader->SelectTopic(topic.name);
          } catch (const IoError&) {
            ++reports;
            continue;
          }
          const Read read = ReadAll(reader.get());
          EXPECT_TRUE(read.ended);
          reports += read.damage.size();
          for (size_t i = 0; i < read.messages.size(); ++i) EXPECT_EQ(read.messages[i].sequence, i);
        }
      }));
    }
  }
  EXPECT_GT(bytes.size() / 4096, 4u);
  EXPECT_GT(reports, 0u);
}

}  // namespace
}  // namespace lpir
