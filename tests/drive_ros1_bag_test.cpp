// The ROS 1 bag 2.0 reader (host/drive/ros1_bag_reader.h) and the ROS 1 serialization of
// PointCloud2 (host/drive/pointcloud2.h), on bags written here record by record (uncompressed,
// bz2 and lz4 chunks, indexed and as a recorder that died leaves them), then damaged: truncated
// at every byte, an unknown compression, corrupt bz2, huge lengths, a bad magic or version.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <functional>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include "host/drive/decompress.h"
#include "host/drive/pointcloud2.h"
#include "host/drive/ros1_bag_reader.h"
#include "host/io/io_error.h"
#include "tests/io_alloc_tracker.h"
#include "tests/io_test_helpers.h"
#include "tests/ros1_bag_bytes.h"

namespace lpir {
namespace {

namespace fs = std::filesystem;
using test::ThrowsIoError;
using test::WriteRaw;

using bag_bytes::Bz2;
using bag_bytes::Field;
using bag_bytes::Op;
using bag_bytes::Record;
using bag_bytes::U32;
using bag_bytes::U64;
std::string Time(uint32_t sec, uint32_t nsec) { return U32(sec) + U32(nsec); }
std::string Lz4(const std::string& in) {
  const auto out = CompressLz4Frame(reinterpret_cast<const uint8_t*>(in.data()), in.size());
  return std::string(out.begin(), out.end());
}

struct Conn {
  uint32_t id;
  std::string topic, type;
};
struct Msg {
  uint32_t conn;
  uint32_t sec, nsec;
  std::string data;
};
struct ChunkSpec {
  std::string compression;  // none, bz2, lz4 or any other name (its data is then left as is)
  std::vector<Msg> messages;
};

// Where the writer put every message: enough to say what a reader of a truncated copy must yield.
struct Placed {
  Msg msg;
  std::string topic;
  uint64_t record_end;  // the file byte after its message record (for an uncompressed chunk)
  uint64_t chunk_end;   // the file byte after its chunk record
  bool uncompressed;
};
struct Bag {
  std::string bytes;
  std::vector<uint64_t> boundaries;  // the file byte after each record outside the chunks
  std::vector<uint64_t> chunk_pos, chunk_data_pos;
  std::vector<Placed> messages;  // in file order
};

// A bag as rosbag writes one: the bag header padded to 4096 bytes; each chunk with the connection
// records of the connections it is first to use, then its index data records; then (indexed)
// every connection and a chunk info per chunk, with the bag header pointing there. Unindexed, the
// bag header holds index_pos 0 and no index follows, as a recorder that died leaves it.
Bag WriteBag(const std::vector<Conn>& conns, const std::vector<ChunkSpec>& chunks, bool indexed) {
  std::map<uint32_t, Conn> by_id;
  for (const Conn& c : conns) by_id[c.id] = c;
  auto connection = [&](const Conn& c) {
    return Record(Op(7) + Field("conn", U32(c.id)) + Field("topic", c.topic),
                  Field("topic", c.topic) + Field("type", c.type) +
                      Field("md5sum", "1158d486dd51d683ce2f1be655c3c181") +
                      Field("message_definition", "# a definition") +
                      Field("callerid", "/recorder" + std::to_string(c.id)) +
                      Field("latching", "0"));
  };
  Bag bag;
  bag.bytes = "#ROSBAG V2.0\n";
  const size_t header_at = bag.bytes.size();
  bag.bytes += std::string(4096, ' ');  // the bag header, written last
  bag.boundaries.push_back(bag.bytes.size());
  std::map<uint32_t, bool> written;
  struct Info {
    uint64_t pos;
    uint64_t start, end;
    std::map<uint32_t, uint32_t> counts;
  };
  std::vector<Info> infos;
  for (const ChunkSpec& spec : chunks) {
    std::string inner;
    std::map<uint32_t, std::vector<std::pair<uint64_t, uint32_t>>> index;  // conn -> (time, off)
    std::vector<std::pair<Msg, uint64_t>> ends;
    Info info{bag.bytes.size(), ~uint64_t(0), 0, {}};
    for (const Msg& m : spec.messages) {
      if (!written[m.conn]) {
        inner += connection(by_id.at(m.conn));
        written[m.conn] = true;
      }
      const uint64_t t = uint64_t(m.sec) * 1000000000 + m.nsec;
      index[m.conn].emplace_back(t, uint32_t(inner.size()));
      inner +=
          Record(Op(2) + Field("conn", U32(m.conn)) + Field("time", Time(m.sec, m.nsec)), m.data);
      ends.emplace_back(m, inner.size());
      info.start = std::min(info.start, t);
      info.end = std::max(info.end, t);
      ++info.counts[m.conn];
    }
    const std::string data = spec.compression == "bz2"   ? Bz2(inner)
                             : spec.compression == "lz4" ? Lz4(inner)
                                                         : inner;
    const std::string header =
        Op(5) + Field("compression", spec.compression) + Field("size", U32(uint32_t(inner.size())));
    bag.chunk_pos.push_back(bag.bytes.size());
    bag.chunk_data_pos.push_back(bag.bytes.size() + 8 + header.size());
    bag.bytes += Record(header, data);
    for (const auto& [m, end] : ends)
      bag.messages.push_back(Placed{m, by_id.at(m.conn).topic, bag.chunk_data_pos.back() + end,
                                    bag.bytes.size(), spec.compression == "none"});
    bag.boundaries.push_back(bag.bytes.size());
    for (const auto& [conn, entries] : index) {
      std::string d;
      for (const auto& [t, off] : entries)
        d += Time(uint32_t(t / 1000000000), uint32_t(t % 1000000000)) + U32(off);
      bag.bytes += Record(Op(4) + Field("ver", U32(1)) + Field("conn", U32(conn)) +
                              Field("count", U32(uint32_t(entries.size()))),
                          d);
      bag.boundaries.push_back(bag.bytes.size());
    }
    infos.push_back(info);
  }
  const uint64_t index_pos = bag.bytes.size();
  if (indexed) {
    for (const Conn& c : conns) {
      bag.bytes += connection(c);
      bag.boundaries.push_back(bag.bytes.size());
    }
    for (const Info& info : infos) {
      std::string d;
      for (const auto& [conn, n] : info.counts) d += U32(conn) + U32(n);
      bag.bytes +=
          Record(Op(6) + Field("ver", U32(1)) + Field("chunk_pos", U64(info.pos)) +
                     Field("start_time", U64(info.start)) + Field("end_time", U64(info.end)) +
                     Field("count", U32(uint32_t(info.counts.size()))),
                 d);
      bag.boundaries.push_back(bag.bytes.size());
    }
  }
  const std::string header = Op(3) + Field("index_pos", U64(indexed ? index_pos : 0)) +
                             Field("conn_count", U32(indexed ? uint32_t(conns.size()) : 0)) +
                             Field("chunk_count", U32(indexed ? uint32_t(chunks.size()) : 0));
  const std::string record = Record(header, std::string(4096 - 8 - header.size(), ' '));
  bag.bytes.replace(header_at, record.size(), record);
  return bag;
}

struct Step {
  DriveStep kind;
  DriveMessage message;
  std::string problem;
};
std::vector<std::string> StepLines(const std::vector<Step>& steps);

// Every step of `topic` up to and including kEnd (at most `limit`, so a loop cannot hang).
std::vector<Step> ReadAll(DriveReader* reader, const std::string& topic, size_t limit = 10000) {
  reader->SelectTopic(topic);
  std::vector<Step> steps;
  for (size_t k = 0; k < limit; ++k) {
    Step s;
    s.kind = reader->Next(&s.message, &s.problem);
    steps.push_back(s);
    if (s.kind == DriveStep::kEnd) break;
  }
  return steps;
}
std::vector<Step> Messages(const std::vector<Step>& steps) {
  std::vector<Step> out;
  for (const Step& s : steps)
    if (s.kind == DriveStep::kMessage) out.push_back(s);
  return out;
}
size_t Damages(const std::vector<Step>& steps) {
  return size_t(std::count_if(steps.begin(), steps.end(),
                              [](const Step& s) { return s.kind == DriveStep::kDamage; }));
}

// A small PointCloud2 whose bytes differ with `k`.
PointCloud2 SampleCloud(uint32_t k) {
  PointCloud2 c;
  c.seq = k;
  c.stamp_sec = int32_t(1000 + k);
  c.stamp_nanosec = 250000000u + k;
  c.frame_id = "velodyne";
  c.height = 1;
  c.width = 2;
  c.fields = {{"x", 0, kPfFloat32, 1},
              {"y", 4, kPfFloat32, 1},
              {"z", 8, kPfFloat32, 1},
              {"intensity", 12, kPfFloat32, 1},
              {"ring", 16, kPfUint16, 1}};
  c.point_step = 18;
  c.row_step = 36;
  for (uint32_t b = 0; b < 36; ++b) c.data.push_back(uint8_t(b * 7 + k));
  c.is_dense = k % 2 == 0;
  return c;
}
std::string CloudBytes(uint32_t k) {
  const auto bytes = SerializeRos1PointCloud2(SampleCloud(k));
  return std::string(bytes.begin(), bytes.end());
}

class Ros1BagTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    std::string name = "drive_ros1_bag_test_" + std::to_string(getpid()) + "_" +
                       info->test_suite_name() + "_" + info->name();
    std::replace(name.begin(), name.end(), '/', '_');
    dir_ = fs::temp_directory_path() / name;
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string Write(const std::string& name, const std::string& bytes) {
    const std::string path = (dir_ / name).string();
    WriteRaw(path, bytes);
    return path;
  }
  fs::path dir_;
};

// Two connections on /points (two publishers), one on /imu; three chunks whose receipt times
// interleave the connections, go backwards inside a chunk and tie across connections.
const std::vector<Conn> kConns = {{0, "/points", "sensor_msgs/PointCloud2"},
                                  {1, "/imu", "sensor_msgs/Imu"},
                                  {5, "/points", "sensor_msgs/PointCloud2"}};
std::vector<ChunkSpec> MixedChunks(const std::string& compression) {
  return {
      {compression,
       {{0, 10, 0, CloudBytes(0)},
        {1, 10, 5, "imu-a"},
        {5, 9, 999999999, CloudBytes(1)},
        {0, 11, 0, CloudBytes(2)}}},
      {compression, {{5, 11, 0, CloudBytes(3)}, {1, 12, 0, "imu-b"}, {0, 12, 1, CloudBytes(4)}}},
      {compression, {{0, 13, 0, CloudBytes(5)}, {5, 12, 2, CloudBytes(6)}}}};
}
// /points of MixedChunks by receipt time, ties (11.0 s) in file order: the cloud numbers.
const std::vector<uint32_t> kPointsOrder = {1, 0, 2, 3, 4, 6, 5};

class Ros1BagCompressionTest : public Ros1BagTest,
                               public ::testing::WithParamInterface<std::tuple<std::string, bool>> {
};

TEST_P(Ros1BagCompressionTest, TopicsAndReceiptOrderAcrossChunksAndConnections) {
  const auto [compression, indexed] = GetParam();
  const std::string path =
      Write("mixed.bag", WriteBag(kConns, MixedChunks(compression), indexed).bytes);
  auto reader = OpenRos1Bag(path);
  const std::vector<DriveTopic> topics = reader->Topics();
  ASSERT_EQ(topics.size(), 2u);
  EXPECT_EQ(topics[0].name, "/imu");
  EXPECT_EQ(topics[0].type, "sensor_msgs/Imu");
  EXPECT_EQ(topics[0].encoding, "ros1");
  EXPECT_EQ(topics[0].messages, 2u);
  EXPECT_EQ(topics[1].name, "/points");
  EXPECT_EQ(topics[1].type, "sensor_msgs/PointCloud2");
  EXPECT_EQ(topics[1].messages, 7u);

  const std::vector<Step> steps = ReadAll(reader.get(), "/points");
  ASSERT_EQ(steps.size(), kPointsOrder.size() + 1) << steps[0].problem;
  for (size_t i = 0; i < kPointsOrder.size(); ++i) {
    ASSERT_EQ(steps[i].kind, DriveStep::kMessage) << steps[i].problem;
    const DriveMessage& m = steps[i].message;
    EXPECT_EQ(m.sequence, i);
    EXPECT_EQ(m.topic, "/points");
    EXPECT_EQ(m.encoding, MessageEncoding::kRos1);
    const std::string want = CloudBytes(kPointsOrder[i]);
    EXPECT_EQ(std::string(m.data.begin(), m.data.end()), want) << "message " << i;
    const PointCloud2 cloud = ParseRos1PointCloud2("m", m.data.data(), m.data.size());
    EXPECT_EQ(cloud.seq, kPointsOrder[i]);
    if (i > 0) {
      EXPECT_GE(m.log_time_ns, steps[i - 1].message.log_time_ns);
    }
  }
  EXPECT_EQ(steps[0].message.log_time_ns, 9999999999u);
  EXPECT_EQ(steps.back().kind, DriveStep::kEnd);
  DriveMessage m;
  std::string problem;
  EXPECT_EQ(reader->Next(&m, &problem), DriveStep::kEnd);

  // Selecting again starts over; another topic has its own messages.
  const std::vector<Step> imu = ReadAll(reader.get(), "/imu");
  ASSERT_EQ(imu.size(), 3u);
  EXPECT_EQ(std::string(imu[0].message.data.begin(), imu[0].message.data.end()), "imu-a");
  EXPECT_EQ(std::string(imu[1].message.data.begin(), imu[1].message.data.end()), "imu-b");
  EXPECT_EQ(imu[1].message.sequence, 1u);
  EXPECT_EQ(Messages(ReadAll(reader.get(), "/points")).size(), 7u);
}

INSTANTIATE_TEST_SUITE_P(Chunks, Ros1BagCompressionTest,
                         ::testing::Combine(::testing::Values("none", "bz2", "lz4"),
                                            ::testing::Bool()));

TEST_F(Ros1BagTest, UnknownTopicNamesTheTopicsThere) {
  const std::string path = Write("a.bag", WriteBag(kConns, MixedChunks("none"), true).bytes);
  auto reader = OpenRos1Bag(path);
  EXPECT_TRUE(
      ThrowsIoError([&] { reader->SelectTopic("/lidar"); }, path, {"/lidar", "/imu", "/points"}));
}

TEST_F(Ros1BagTest, EmptyBagHasNoTopics) {
  for (bool indexed : {true, false}) {
    const std::string path = Write("empty.bag", WriteBag({}, {}, indexed).bytes);
    auto reader = OpenRos1Bag(path);
    EXPECT_TRUE(reader->Topics().empty());
    EXPECT_TRUE(ThrowsIoError([&] { reader->SelectTopic("/points"); }, path, {"none"}));
  }
}

TEST_F(Ros1BagTest, BadMagicVersionOrBagHeaderIsAnIoError) {
  const std::string good = WriteBag(kConns, MixedChunks("none"), true).bytes;
  std::string v12 = good;
  v12.replace(0, 13, "#ROSBAG V1.2\n");
  EXPECT_TRUE(
      ThrowsIoError([&] { OpenRos1Bag(Write("v12.bag", v12)); }, "v12.bag", {"version", "1.2"}));
  EXPECT_TRUE(ThrowsIoError([&] { OpenRos1Bag(Write("pcd.bag", "# .PCD v0.7\nVERSION .7\n")); },
                            "pcd.bag", {"not a ROS bag"}));
  EXPECT_TRUE(
      ThrowsIoError([&] { OpenRos1Bag(Write("empty.bag", "")); }, "empty.bag", {"not a ROS bag"}));
  EXPECT_TRUE(ThrowsIoError([&] { OpenRos1Bag((dir_ / "missing.bag").string()); }, "missing.bag",
                            {"no such file"}));
  EXPECT_TRUE(ThrowsIoError([&] { OpenRos1Bag(dir_.string()); }, dir_.string(), {"folder"}));
  // The first record is not a bag header (op 5), or lacks index_pos, or is cut short.
  std::string wrong_op = good;
  const size_t op_at = wrong_op.find("op=\x03");
  ASSERT_NE(op_at, std::string::npos);
  wrong_op[op_at + 3] = 5;
  EXPECT_TRUE(ThrowsIoError([&] { OpenRos1Bag(Write("op.bag", wrong_op)); }, "op.bag",
                            {"bag header", "op is 5"}));
  std::string no_index = good;
  no_index.replace(no_index.find("index_pos"), 9, "index_qos");
  EXPECT_TRUE(ThrowsIoError([&] { OpenRos1Bag(Write("noindex.bag", no_index)); }, "noindex.bag",
                            {"bag header", "index_pos"}));
  for (size_t cut : {size_t(13), size_t(15), size_t(60), size_t(4108)})
    EXPECT_TRUE(ThrowsIoError([&] { OpenRos1Bag(Write("cut.bag", good.substr(0, cut))); },
                              "cut.bag", {"bag header"}))
        << cut;
}

// Cut at every byte after the bag header: no crash; exactly the messages whose records are whole
// (every message of earlier chunks, and of an uncompressed chunk those before the cut); one
// damage unless the cut falls between the records of an unindexed bag; then the end.
TEST_F(Ros1BagTest, TruncatedAtEveryByte) {
  for (const char* compression : {"none", "bz2", "lz4"}) {
    for (bool indexed : {true, false}) {
      // Times rise in file order, so what survives a cut is a prefix.
      std::vector<ChunkSpec> chunks = {
          {compression, {{0, 1, 0, "p0"}, {1, 1, 5, "imu"}, {0, 2, 0, "p1"}}},
          {compression, {{5, 3, 0, "p2"}, {0, 4, 0, "p3"}}},
          {compression, {{0, 5, 0, "p4"}, {1, 5, 1, "imu"}, {5, 6, 0, "p5"}}}};
      const Bag bag = WriteBag(kConns, chunks, indexed);
      const std::string path = (dir_ / "cut.bag").string();
      for (size_t cut = 4109; cut < bag.bytes.size(); ++cut) {
        SCOPED_TRACE(std::string(compression) + (indexed ? " indexed" : " unindexed") +
                     ", cut at " + std::to_string(cut));
        WriteRaw(path, bag.bytes.substr(0, cut));
        std::vector<std::string> want;
        for (const Placed& p : bag.messages)
          if (p.topic == "/points" &&
              (p.chunk_end <= cut || (p.uncompressed && p.record_end <= cut)))
            want.push_back(p.msg.data);
        const bool at_boundary =
            std::find(bag.boundaries.begin(), bag.boundaries.end(), cut) != bag.boundaries.end();
        auto reader = OpenRos1Bag(path);
        reader->Topics();
        std::vector<Step> steps;
        try {
          steps = ReadAll(reader.get(), "/points");
        } catch (const IoError& e) {
          // The connection records were lost with the first chunk: the error says why.
          EXPECT_TRUE(want.empty()) << e.what();
          if (indexed || !at_boundary) {
            EXPECT_NE(std::string(e.what()).find("its first damage: "), std::string::npos)
                << e.what();
          }
          continue;
        }
        ASSERT_EQ(steps.back().kind, DriveStep::kEnd);
        {  // three workers decompressing ahead give the same steps, damage included
          auto ahead = OpenRos1Bag(path, 3);
          ahead->Topics();
          EXPECT_EQ(StepLines(ReadAll(ahead.get(), "/points")), StepLines(steps));
        }
        std::vector<std::string> got;
        for (const Step& s : Messages(steps))
          got.emplace_back(s.message.data.begin(), s.message.data.end());
        EXPECT_EQ(got, want);
        EXPECT_EQ(Damages(steps), !indexed && at_boundary ? 0u : 1u);
        for (const Step& s : steps) {
          if (s.kind == DriveStep::kDamage) {
            EXPECT_NE(s.problem.find(path), std::string::npos);
          }
        }
        // The damage comes after every message.
        if (Damages(steps) == 1) {
          EXPECT_EQ(steps[steps.size() - 2].kind, DriveStep::kDamage);
        }
      }
    }
  }
}

TEST_F(Ros1BagTest, CutMidChunkNamesTheChunk) {
  const Bag bag = WriteBag(kConns, MixedChunks("bz2"), false);
  const size_t cut = bag.chunk_data_pos[2] + 10;
  const std::string path = Write("cut.bag", bag.bytes.substr(0, cut));
  auto reader = OpenRos1Bag(path);
  const std::vector<Step> steps = ReadAll(reader.get(), "/points");
  ASSERT_EQ(steps.size(), 5u + 1 + 1);
  const std::string& problem = steps[5].problem;
  EXPECT_EQ(steps[5].kind, DriveStep::kDamage);
  EXPECT_NE(problem.find("chunk 3 at byte " + std::to_string(bag.chunk_pos[2])), std::string::npos)
      << problem;
  EXPECT_NE(problem.find("truncated"), std::string::npos) << problem;
}

// A chunk of unknown compression, or whose bz2 is corrupt, or whose lz4 decompresses to another
// size than its header says, is one damage; the chunks after it are read (from the chunk infos,
// or after the damaged record whose lengths are intact).
TEST_F(Ros1BagTest, DamagedChunkIsReportedAndReadingGoesOn) {
  struct Case {
    const char* name;
    std::string compression;
    std::function<void(Bag*, std::string*)> damage;
    const char* words;
  };
  const std::vector<Case> cases = {
      {"unknown", "none",
       [](Bag* bag, std::string* bytes) {
         const size_t at = bytes->find("compression=none", bag->chunk_pos[1]);
         bytes->replace(at, 16, "compression=zstd");
       },
       "unknown compression 'zstd'"},
      {"corrupt bz2", "bz2",
       [](Bag* bag, std::string* bytes) {
         for (size_t k = 20; k < 40; ++k) (*bytes)[bag->chunk_data_pos[1] + k] ^= 0x5A;
       },
       "bz2"},
      {"lz4 size", "lz4",
       [](Bag* bag, std::string* bytes) {
         const size_t at = bytes->find("size=", bag->chunk_pos[1]) + 5;
         (*bytes)[at] = char((*bytes)[at] + 1);
       },
       "lz4"},
      {"none size", "none",
       [](Bag* bag, std::string* bytes) {
         const size_t at = bytes->find("size=", bag->chunk_pos[1]) + 5;
         (*bytes)[at] = char((*bytes)[at] + 1);
       },
       "size field"},
  };
  for (const Case& c : cases) {
    for (bool indexed : {true, false}) {
      SCOPED_TRACE(std::string(c.name) + (indexed ? " indexed" : " unindexed"));
      Bag bag = WriteBag(kConns, MixedChunks(c.compression), indexed);
      std::string bytes = bag.bytes;
      c.damage(&bag, &bytes);
      const std::string path = Write("damaged.bag", bytes);
      auto reader = OpenRos1Bag(path);
      const std::vector<Step> steps = ReadAll(reader.get(), "/points");
      // Chunk 0 holds clouds 0, 1, 2 and chunk 2 clouds 5, 6; chunk 1 (3, 4) is lost.
      std::vector<uint32_t> got;
      for (const Step& s : Messages(steps))
        got.push_back(ParseRos1PointCloud2("m", s.message.data.data(), s.message.data.size()).seq);
      EXPECT_EQ(got, (std::vector<uint32_t>{1, 0, 2, 6, 5}));
      ASSERT_EQ(Damages(steps), 1u);
      const auto damage = std::find_if(steps.begin(), steps.end(),
                                       [](const Step& s) { return s.kind == DriveStep::kDamage; });
      EXPECT_EQ(damage - steps.begin(), 3) << "after chunk 0's messages, before chunk 2's";
      EXPECT_NE(damage->problem.find(path), std::string::npos) << damage->problem;
      EXPECT_NE(damage->problem.find("chunk 2 at byte " + std::to_string(bag.chunk_pos[1])),
                std::string::npos)
          << damage->problem;
      EXPECT_NE(damage->problem.find(c.words), std::string::npos) << damage->problem;
      EXPECT_NE(damage->problem.find("(after 3 messages of /points)"), std::string::npos)
          << damage->problem;
      EXPECT_EQ(steps.back().kind, DriveStep::kEnd);
    }
  }
}

// With the index a reader only opens the chunks holding the topic: a damaged chunk of /imu alone
// is never read for /points. A scan cannot know and reports it.
TEST_F(Ros1BagTest, IndexSkipsChunksWithoutTheTopic) {
  const std::vector<ChunkSpec> chunks = {{"bz2", {{0, 1, 0, "p0"}, {1, 1, 1, "imu0"}}},
                                         {"bz2", {{1, 2, 0, "imu1"}}},
                                         {"bz2", {{0, 3, 0, "p1"}}}};
  for (bool indexed : {true, false}) {
    Bag bag = WriteBag(kConns, chunks, indexed);
    for (size_t k = 20; k < 30; ++k) bag.bytes[bag.chunk_data_pos[1] + k] ^= 0x33;
    auto reader = OpenRos1Bag(Write("imu.bag", bag.bytes));
    const std::vector<Step> steps = ReadAll(reader.get(), "/points");
    EXPECT_EQ(Messages(steps).size(), 2u);
    EXPECT_EQ(Damages(steps), indexed ? 0u : 1u);
  }
}

// Index data that disagrees with the chunk info, or a chunk info pointing at no chunk: the
// messages come from a scan of the chunk, or the chunk is damage; the other chunks are read.
TEST_F(Ros1BagTest, BrokenIndexDataFallsBackToTheChunk) {
  Bag bag = WriteBag(kConns, MixedChunks("lz4"), true);
  // The first index data record after chunk 1: its count goes from 2 (or 1) to 7.
  const size_t at = bag.bytes.find("count=", bag.chunk_data_pos[1]) + 6;
  bag.bytes[at] = 7;
  auto reader = OpenRos1Bag(Write("index.bag", bag.bytes));
  const std::vector<Step> steps = ReadAll(reader.get(), "/points");
  ASSERT_EQ(Messages(steps).size(), 7u);
  EXPECT_EQ(Damages(steps), 0u);
  for (size_t i = 0; i < kPointsOrder.size(); ++i)
    EXPECT_EQ(std::string(steps[i].message.data.begin(), steps[i].message.data.end()),
              CloudBytes(kPointsOrder[i]));

  // Chunk info 1's chunk_pos moved by one byte: chunk 1 cannot be read, the rest can.
  Bag moved = WriteBag(kConns, MixedChunks("lz4"), true);
  const std::string pos_field = "chunk_pos=" + U64(moved.chunk_pos[1]);
  const size_t info = moved.bytes.rfind(pos_field);
  ASSERT_NE(info, std::string::npos);
  moved.bytes.replace(info, pos_field.size(), "chunk_pos=" + U64(moved.chunk_pos[1] + 1));
  auto reader2 = OpenRos1Bag(Write("moved.bag", moved.bytes));
  const std::vector<Step> steps2 = ReadAll(reader2.get(), "/points");
  EXPECT_EQ(Messages(steps2).size(), 5u);
  EXPECT_EQ(Damages(steps2), 1u);

  // Chunk info 1 claims 3 messages of connection 0, its chunk holds 1: the chunk's messages are
  // read and the disagreement is one damage.
  Bag counted = WriteBag(kConns, MixedChunks("bz2"), true);
  const size_t info1 = counted.bytes.rfind("chunk_pos=" + U64(counted.chunk_pos[1]));
  const size_t pair = counted.bytes.find(U32(0) + U32(1), info1);
  ASSERT_NE(pair, std::string::npos);
  counted.bytes.replace(pair, 8, U32(0) + U32(3));
  const std::string path3 = Write("counted.bag", counted.bytes);
  auto reader3 = OpenRos1Bag(path3);
  EXPECT_EQ(reader3->Topics()[1].messages, 9u);
  const std::vector<Step> steps3 = ReadAll(reader3.get(), "/points");
  EXPECT_EQ(Messages(steps3).size(), 7u);
  ASSERT_EQ(Damages(steps3), 1u);
  for (const Step& s : steps3) {
    if (s.kind == DriveStep::kDamage) {
      EXPECT_NE(s.problem.find("lists 3 messages of connection 0, the chunk holds 1"),
                std::string::npos)
          << s.problem;
    }
  }
}

// An index the bag header points at that is not whole (the file ends inside it): the chunks are
// scanned, every message is read, and the lost index is one damage at the end.
TEST_F(Ros1BagTest, UnusableIndexIsScannedAndReported) {
  const Bag bag = WriteBag(kConns, MixedChunks("bz2"), true);
  const std::string path = Write("noindex.bag", bag.bytes.substr(0, bag.bytes.size() - 3));
  auto reader = OpenRos1Bag(path);
  EXPECT_EQ(reader->Topics()[1].messages, 7u);
  const std::vector<Step> steps = ReadAll(reader.get(), "/points");
  ASSERT_EQ(steps.size(), 7u + 2);
  EXPECT_EQ(steps[7].kind, DriveStep::kDamage);
  EXPECT_NE(steps[7].problem.find(path), std::string::npos);
}

// Lengths that claim gigabytes (a record header, a record's data, a chunk's uncompressed size,
// an index count) are checked against the bytes there before anything is allocated.
TEST_F(Ros1BagTest, HugeLengthsAllocateNothing) {
  const Bag bag = WriteBag(kConns, MixedChunks("bz2"), true);
  std::vector<std::string> hostile;
  std::string header_len = bag.bytes;
  header_len.replace(bag.chunk_pos[1], 4, U32(0xFFFFFFF0u));
  hostile.push_back(header_len);
  std::string data_len = bag.bytes;
  data_len.replace(bag.chunk_data_pos[1] - 4, 4, U32(0xFFFFFFF0u));
  hostile.push_back(data_len);
  std::string size = bag.bytes;
  size.replace(size.find("size=", bag.chunk_pos[1]) + 5, 4, U32(0xFFFFFFFFu));
  hostile.push_back(size);
  std::string count = bag.bytes;
  count.replace(count.find("count=", bag.chunk_data_pos[1]) + 6, 4, U32(0xFFFFFFFFu));
  hostile.push_back(count);
  std::string index_pos = bag.bytes;
  index_pos.replace(index_pos.find("index_pos=") + 10, 8, U64(~uint64_t(0)));
  hostile.push_back(index_pos);
  for (size_t k = 0; k < hostile.size(); ++k) {
    const std::string path = Write("huge.bag", hostile[k]);
    std::vector<Step> steps;
    const size_t largest = test::LargestAllocationDuring([&] {
      auto reader = OpenRos1Bag(path);
      reader->Topics();
      steps = ReadAll(reader.get(), "/points");
    });
    EXPECT_LT(largest, size_t(4) << 20) << "case " << k;
    EXPECT_EQ(steps.back().kind, DriveStep::kEnd) << "case " << k;
    EXPECT_GE(Messages(steps).size(), 3u) << "case " << k;  // chunk 0 is whole in every case
  }
}

// The reader holds a chunk at a time, never the file.
TEST_F(Ros1BagTest, ReadsAChunkAtATime) {
  std::vector<ChunkSpec> chunks;
  for (uint32_t c = 0; c < 6; ++c)
    chunks.push_back({"none", {{0, c, 0, std::string(100000, char('a' + c))}}});
  const Bag bag = WriteBag(kConns, chunks, true);
  const std::string path = Write("big.bag", bag.bytes);
  size_t messages = 0;
  const size_t largest = test::LargestAllocationDuring([&] {
    auto reader = OpenRos1Bag(path);
    messages = Messages(ReadAll(reader.get(), "/points")).size();
  });
  EXPECT_EQ(messages, 6u);
  EXPECT_LT(largest, bag.bytes.size() / 3);
}

// --- decompression ahead (several workers) and chunk ranges ---

// 40 chunks of bz2, lz4 and none, three /points messages each (one of them /imu every other
// chunk), receipt times that step back across chunk boundaries so that the yield order visits
// some chunks twice.
std::vector<ChunkSpec> ManyChunks() {
  std::vector<ChunkSpec> chunks;
  const char* kinds[] = {"bz2", "lz4", "none"};
  uint32_t k = 0;
  for (uint32_t c = 0; c < 40; ++c) {
    ChunkSpec spec{kinds[c % 3], {}};
    for (uint32_t m = 0; m < 3; ++m, ++k) {
      // times 10c, 10c+4, 10c+11: the last one after the next chunk's first
      spec.messages.push_back(
          {m == 1 ? 5u : 0u, 100 + 10 * c + (m == 2 ? 11 : 4 * m), 0, CloudBytes(k % 250)});
    }
    if (c % 2) spec.messages.push_back({1, 100 + 10 * c + 1, 0, "imu"});
    chunks.push_back(spec);
  }
  return chunks;
}

// The steps as text: kind, sequence, time and data (or the problem), one line each.
std::vector<std::string> StepLines(const std::vector<Step>& steps) {
  std::vector<std::string> lines;
  for (const Step& s : steps) {
    if (s.kind == DriveStep::kMessage)
      lines.push_back("message " + std::to_string(s.message.sequence) + " " +
                      std::to_string(s.message.log_time_ns) + " " +
                      std::string(s.message.data.begin(), s.message.data.end()));
    else
      lines.push_back(s.kind == DriveStep::kDamage ? "damage " + s.problem : "end");
  }
  return lines;
}

// Several workers yield exactly the steps one does: every message in order, a damaged chunk in
// the middle once and at its place (after every message before it), indexed or scanned.
TEST_F(Ros1BagTest, SeveralWorkersYieldWhatOneYields) {
  for (bool indexed : {true, false}) {
    for (bool damaged : {false, true}) {
      SCOPED_TRACE(std::string(indexed ? "indexed" : "unindexed") + (damaged ? " damaged" : ""));
      Bag bag = WriteBag(kConns, ManyChunks(), indexed);
      if (damaged)  // chunk 22 (index 21, bz2) corrupted
        for (size_t k = 12; k < 30; ++k) bag.bytes[bag.chunk_data_pos[21] + k] ^= 0x5A;
      const std::string path = Write("many.bag", bag.bytes);
      const std::vector<std::string> one =
          StepLines(ReadAll(OpenRos1Bag(path, 1).get(), "/points"));
      ASSERT_EQ(one.back(), "end");
      size_t damages = 0;
      for (const std::string& line : one) damages += line.rfind("damage", 0) == 0;
      EXPECT_EQ(damages, damaged ? 1u : 0u);
      EXPECT_EQ(one.size(), damaged ? 120u - 3 + 2 : 121u);
      if (damaged) {
        // Indexed, the damage is found when chunk 22's first message (time 310) is due: the 62
        // messages before it by time (chunk 21's last, at 311, comes after). Scanned, it is placed
        // after every message lying before it in the file: chunks 1..21's 63.
        const size_t at =
            size_t(std::find_if(one.begin(), one.end(),
                                [](const std::string& l) { return l.rfind("damage", 0) == 0; }) -
                   one.begin());
        EXPECT_EQ(at, indexed ? 62u : 63u);
        EXPECT_NE(one[at].find("chunk 22 at byte " + std::to_string(bag.chunk_pos[21])),
                  std::string::npos)
            << one[at];
      }
      for (unsigned workers : {2u, 3u, 8u}) {
        auto reader = OpenRos1Bag(path, workers);
        EXPECT_EQ(StepLines(ReadAll(reader.get(), "/points")), one) << workers << " workers";
        EXPECT_EQ(StepLines(ReadAll(reader.get(), "/points")), one) << "selected again";
      }
    }
  }
}

// A reader destroyed in the middle of a drive, with workers decompressing ahead, leaves no thread
// behind (the test would hang at the join, or LeakSanitizer name the buffers).
TEST_F(Ros1BagTest, DestroyedInTheMiddleWithWorkersAhead) {
  const Bag bag = WriteBag(kConns, ManyChunks(), true);
  const std::string path = Write("many.bag", bag.bytes);
  for (size_t stop : {0u, 1u, 7u, 60u}) {
    auto reader = OpenRos1Bag(path, 4);
    reader->SelectTopic("/points");
    DriveMessage m;
    std::string problem;
    for (size_t k = 0; k < stop; ++k) ASSERT_EQ(reader->Next(&m, &problem), DriveStep::kMessage);
    reader->SelectTopic("/imu");  // stops the pool mid-way, starts another
    ASSERT_EQ(reader->Next(&m, &problem), DriveStep::kMessage);
    EXPECT_EQ(std::string(m.data.begin(), m.data.end()), "imu");
  }
}

// The ranges of a partition of the chunks yield together what the whole run yields, each
// message with its whole-run sequence: MixedChunks, whose receipt times interleave the chunks.
TEST_F(Ros1BagTest, ChunkRangesTogetherYieldTheWholeRun) {
  const std::vector<std::vector<std::pair<uint64_t, uint64_t>>> partitions = {
      {{1, 1}, {2, 2}, {3, 3}}, {{1, 2}, {3, 3}}, {{1, 1}, {2, 3}}, {{1, 3}}};
  for (bool indexed : {true, false}) {
    for (unsigned workers : {1u, 3u}) {
      SCOPED_TRACE(std::string(indexed ? "indexed " : "unindexed ") + std::to_string(workers));
      const Bag bag = WriteBag(kConns, MixedChunks("bz2"), indexed);
      const std::string path = Write("mixed.bag", bag.bytes);
      auto reader = OpenRos1Bag(path, workers);
      EXPECT_EQ(reader->ChunkCount(), 3u);
      EXPECT_EQ(reader->ChunksIndexed(), indexed);
      std::vector<std::string> whole = StepLines(ReadAll(reader.get(), "/points"));
      whole.pop_back();  // "end"
      std::sort(whole.begin(), whole.end());
      for (const auto& partition : partitions) {
        std::vector<std::string> together;
        for (const auto& [first, last] : partition) {
          reader->SelectTopic("/points");
          reader->SelectChunks(first, last);
          DriveMessage m;
          std::string problem;
          for (DriveStep step; (step = reader->Next(&m, &problem)) != DriveStep::kEnd;) {
            ASSERT_EQ(step, DriveStep::kMessage) << problem;
            const PointCloud2 cloud = ParseRos1PointCloud2("m", m.data.data(), m.data.size());
            const uint32_t chunk = cloud.seq == 0 || cloud.seq == 1 || cloud.seq == 2 ? 1
                                   : cloud.seq == 3 || cloud.seq == 4                 ? 2
                                                                                      : 3;
            EXPECT_GE(chunk, first);
            EXPECT_LE(chunk, last);
            together.push_back(StepLines({Step{step, m, ""}})[0]);
          }
        }
        std::sort(together.begin(), together.end());
        EXPECT_EQ(together, whole);
      }
      EXPECT_TRUE(ThrowsIoError([&] { reader->SelectChunks(2, 4); }, "mixed.bag", {"has 3"}));
      EXPECT_TRUE(ThrowsIoError([&] { reader->SelectChunks(0, 1); }, "mixed.bag", {"from 1"}));
      EXPECT_TRUE(ThrowsIoError([&] { reader->SelectChunks(3, 2); }, "mixed.bag", {"3 to 2"}));
    }
  }
}

// An indexed bag's range skips the chunks before it without decompressing them: a corrupt chunk
// 1 is neither reported nor missed in the sequence numbers of chunks 2..3; the range holding it
// reports it once.
TEST_F(Ros1BagTest, ARangeSkipsTheChunksBeforeItAndOwnsItsDamage) {
  Bag bag = WriteBag(kConns, MixedChunks("bz2"), true);
  for (size_t k = 20; k < 40; ++k) bag.bytes[bag.chunk_data_pos[0] + k] ^= 0x5A;
  const std::string path = Write("bad1.bag", bag.bytes);
  auto reader = OpenRos1Bag(path, 2);
  reader->SelectTopic("/points");
  reader->SelectChunks(2, 3);
  std::vector<uint64_t> sequences;
  DriveMessage m;
  std::string problem;
  for (DriveStep step; (step = reader->Next(&m, &problem)) != DriveStep::kEnd;) {
    ASSERT_EQ(step, DriveStep::kMessage) << problem;
    sequences.push_back(m.sequence);
  }
  // kPointsOrder = 1 0 2 | 3 4 6 5: chunks 2 and 3 hold sequences 3..6
  EXPECT_EQ(sequences, (std::vector<uint64_t>{3, 4, 5, 6}));
  reader->SelectTopic("/points");
  reader->SelectChunks(1, 1);
  size_t damages = 0, messages = 0;
  for (DriveStep step; (step = reader->Next(&m, &problem)) != DriveStep::kEnd;) {
    damages += step == DriveStep::kDamage;
    messages += step == DriveStep::kMessage;
    if (step == DriveStep::kDamage) {
      EXPECT_NE(problem.find("chunk 1 at byte"), std::string::npos) << problem;
    }
  }
  EXPECT_EQ(damages, 1u);
  EXPECT_EQ(messages, 0u);
}

// --- ROS 1 PointCloud2 ---

// The bytes of SampleCloud(3) by the layout of the message definition, written out field by
// field (independent of SerializeRos1PointCloud2).
std::string HandSerialized() {
  const PointCloud2 c = SampleCloud(3);
  std::string s =
      U32(3) + U32(1003) + U32(250000003) + U32(8) + "velodyne" + U32(1) + U32(2) + U32(5);
  const char* names[] = {"x", "y", "z", "intensity", "ring"};
  const uint32_t offsets[] = {0, 4, 8, 12, 16};
  const uint8_t types[] = {7, 7, 7, 7, 4};
  for (int f = 0; f < 5; ++f)
    s += U32(uint32_t(std::strlen(names[f]))) + names[f] + U32(offsets[f]) +
         std::string(1, char(types[f])) + U32(1);
  s += std::string(1, '\0') + U32(18) + U32(36) + U32(36) +
       std::string(c.data.begin(), c.data.end()) + std::string(1, '\0');
  return s;
}

TEST(PointCloud2Ros1Test, SerializesByTheMessageLayoutAndReadsBack) {
  const std::string hand = HandSerialized();
  EXPECT_EQ(CloudBytes(3), hand);
  const PointCloud2 want = SampleCloud(3);
  const PointCloud2 got =
      ParseRos1PointCloud2("m", reinterpret_cast<const uint8_t*>(hand.data()), hand.size());
  EXPECT_EQ(got.seq, want.seq);
  EXPECT_EQ(got.stamp_sec, want.stamp_sec);
  EXPECT_EQ(got.stamp_nanosec, want.stamp_nanosec);
  EXPECT_EQ(got.frame_id, want.frame_id);
  EXPECT_EQ(got.height, want.height);
  EXPECT_EQ(got.width, want.width);
  ASSERT_EQ(got.fields.size(), want.fields.size());
  for (size_t f = 0; f < got.fields.size(); ++f) {
    EXPECT_EQ(got.fields[f].name, want.fields[f].name);
    EXPECT_EQ(got.fields[f].offset, want.fields[f].offset);
    EXPECT_EQ(got.fields[f].datatype, want.fields[f].datatype);
    EXPECT_EQ(got.fields[f].count, want.fields[f].count);
  }
  EXPECT_EQ(got.is_bigendian, want.is_bigendian);
  EXPECT_EQ(got.point_step, want.point_step);
  EXPECT_EQ(got.row_step, want.row_step);
  EXPECT_EQ(got.data, want.data);
  EXPECT_EQ(got.is_dense, want.is_dense);
  const auto again = SerializeRos1PointCloud2(got);
  EXPECT_EQ(std::string(again.begin(), again.end()), hand);
}

TEST(PointCloud2Ros1Test, TruncatedAtEveryLengthOrTrailingBytesIsAnIoError) {
  const std::string bytes = HandSerialized();
  for (size_t n = 0; n < bytes.size(); ++n)
    EXPECT_TRUE(ThrowsIoError(
        [&] {
          ParseRos1PointCloud2("frame.bag: message 4",
                               reinterpret_cast<const uint8_t*>(bytes.data()), n);
        },
        "frame.bag: message 4", {"PointCloud2"}))
        << n;
  const std::string longer = bytes + "x";
  EXPECT_TRUE(ThrowsIoError(
      [&] {
        ParseRos1PointCloud2("w", reinterpret_cast<const uint8_t*>(longer.data()), longer.size());
      },
      "w", {"1 bytes after"}));
}

TEST(PointCloud2Ros1Test, BadBoolsStampsAndHugeLengthsAreIoErrors) {
  auto parse = [](const std::string& s) {
    ParseRos1PointCloud2("w", reinterpret_cast<const uint8_t*>(s.data()), s.size());
  };
  std::string dense = HandSerialized();
  dense.back() = 2;
  EXPECT_TRUE(ThrowsIoError([&] { parse(dense); }, "w", {"is_dense", "bool"}));
  std::string stamp = HandSerialized();
  stamp.replace(4, 4, U32(0x80000000u));
  EXPECT_TRUE(ThrowsIoError([&] { parse(stamp); }, "w", {"stamp", "INT32_MAX"}));
  std::string frame = HandSerialized();
  frame.replace(12, 4, U32(0xFFFFFFFFu));
  std::string fields = HandSerialized();
  fields.replace(32, 4, U32(0xFFFFFFFFu));
  for (const std::string& s : {frame, fields}) {
    const size_t largest = test::LargestAllocationDuring(
        [&] { EXPECT_TRUE(ThrowsIoError([&] { parse(s); }, "w", {"claims"})); });
    EXPECT_LT(largest, size_t(1) << 16);
  }
  PointCloud2 negative = SampleCloud(0);
  negative.stamp_sec = -1;
  EXPECT_THROW(SerializeRos1PointCloud2(negative), std::invalid_argument);
}

}  // namespace
}  // namespace lpir
