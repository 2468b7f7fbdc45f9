// The MCAP reader and writer (host/drive/mcap_reader.h, mcap_writer.h): writer -> reader round
// trips for every compression with several channels over several chunks, the summary's counts and
// chunk order, files built byte by byte here (no summary, messages outside chunks, unknown records,
// other encodings), and every damage case: cuts at many offsets, CRC flips, unknown compression,
// bad magic, huge lengths, a broken summary. Message data is treated as opaque bytes.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <string>
#include <vector>

#include "host/drive/decompress.h"
#include "host/drive/mcap_reader.h"
#include "host/drive/mcap_writer.h"
#include "tests/io_alloc_tracker.h"
#include "tests/io_test_helpers.h"
#include "tests/test_util.h"

namespace lpir {
namespace {

using test::ReadRaw;
using test::ThrowsIoError;
using test::WriteRaw;

// ---- MCAP bytes by hand (little-endian, as the specification lays them out) ----

struct Bin {
  std::string b;
  Bin& U8(uint8_t v) { return Le(v, 1); }
  Bin& U16(uint16_t v) { return Le(v, 2); }
  Bin& U32(uint32_t v) { return Le(v, 4); }
  Bin& U64(uint64_t v) { return Le(v, 8); }
  Bin& Str(const std::string& s) {
    U32(uint32_t(s.size()));
    b += s;
    return *this;
  }
  Bin& Raw(const std::string& s) {
    b += s;
    return *this;
  }
  Bin& Le(uint64_t v, int n) {
    for (int i = 0; i < n; ++i) b.push_back(char(uint8_t(v >> (8 * i))));
    return *this;
  }
};

const std::string kMagic("\x89MCAP0\r\n", 8);

std::string Rec(uint8_t op, const std::string& content) {
  return Bin().U8(op).U64(content.size()).Raw(content).b;
}
std::string HeaderRec() { return Rec(0x01, Bin().Str("ros2").Str("hand").b); }
std::string SchemaRec(uint16_t id, const std::string& name) {
  return Rec(0x03, Bin().U16(id).Str(name).Str("ros2msg").Str("uint8 x\n").b);
}
std::string ChannelRec(uint16_t id, uint16_t schema, const std::string& topic,
                       const std::string& encoding = "cdr") {
  return Rec(0x04, Bin().U16(id).U16(schema).Str(topic).Str(encoding).U32(0).b);
}
std::string MessageRec(uint16_t channel, uint64_t log_time, const std::string& data) {
  return Rec(0x05, Bin().U16(channel).U32(7).U64(log_time).U64(log_time + 1).Raw(data).b);
}
std::string Compress(const std::string& plain, const std::string& compression) {
  const auto* p = reinterpret_cast<const uint8_t*>(plain.data());
  std::vector<uint8_t> packed;
  if (compression == "zstd") packed = CompressZstd(p, plain.size());
  if (compression == "lz4") packed = CompressLz4Frame(p, plain.size());
  if (compression != "zstd" && compression != "lz4") return plain;
  return std::string(packed.begin(), packed.end());
}
// A chunk of `records`; `crc` 1 writes the records' CRC, 0 leaves it unset.
std::string ChunkRec(const std::string& records, const std::string& compression, bool crc = true) {
  const std::string stored = Compress(records, compression);
  const uint32_t c =
      crc ? Crc32(reinterpret_cast<const uint8_t*>(records.data()), records.size()) : 0;
  return Rec(0x06, Bin()
                       .U64(0)
                       .U64(0)
                       .U64(records.size())
                       .U32(c)
                       .Str(compression)
                       .U64(stored.size())
                       .Raw(stored)
                       .b);
}
std::string DataEndRec() { return Rec(0x0F, Bin().U32(0).b); }
std::string FooterAndMagic() { return Rec(0x02, Bin().U64(0).U64(0).U32(0).b) + kMagic; }

// A message the tests expect, with where its bytes end in the file: its own record's end, or
// (compressed chunk) its chunk record's end.
struct Expected {
  uint64_t log_time;
  std::string data;
  size_t complete_at;
};

// A hand-made file without summary, with its expected messages on /points (channel 1).
struct HandFile {
  std::string bytes;
  std::vector<Expected> points;
  size_t channel_end = 0;  // where /points' channel record ends
  size_t data_end = 0;     // where the data end record ends
};

std::string Payload(int i, size_t n) {
  std::string s(n, char('a' + i % 26));
  s[0] = char(i);
  return s;
}

// Header, schema, two channels, then: a message outside chunks, an uncompressed chunk, a zstd
// chunk, a message outside chunks, an lz4 chunk with an unknown record, and an uncompressed chunk
// whose log times are out of order (ties included); /other (channel 2) messages interleaved.
HandFile MakeHandFile() {
  HandFile f;
  f.bytes = kMagic + HeaderRec() + SchemaRec(1, "sensor_msgs/msg/PointCloud2") +
            ChannelRec(1, 1, "/points") + ChannelRec(2, 1, "/other");
  f.channel_end = f.bytes.size();
  int n = 0;
  auto loose = [&](uint64_t t) {
    f.bytes += MessageRec(2, t, "other");
    f.bytes += MessageRec(1, t, Payload(n, 40));
    f.points.push_back({t, Payload(n++, 40), f.bytes.size()});
  };
  auto chunk = [&](const std::string& compression, std::vector<uint64_t> times, bool unknown) {
    std::string records;
    std::vector<Expected> in_chunk;
    if (unknown) records += Rec(0x99, "opaque extension record");
    for (uint64_t t : times) {
      records += MessageRec(2, t, "other");
      const size_t at = records.size();
      const std::string data = Payload(n, 100 + 13 * size_t(n));
      ++n;
      records += MessageRec(1, t, data);
      in_chunk.push_back({t, data, records.size() - at});  // record size, made absolute below
    }
    const std::string rec = ChunkRec(records, compression);
    const size_t content = f.bytes.size() + rec.size() - Compress(records, compression).size();
    // Positions of each /points record's end inside `records`.
    std::vector<size_t> ends;
    for (size_t pos = 0; pos < records.size();) {
      uint64_t len = 0;
      for (int i = 0; i < 8; ++i) len |= uint64_t(uint8_t(records[pos + 1 + i])) << (8 * i);
      const bool point = records[pos] == 0x05 && records[pos + 9] == 1;
      pos += 9 + len;
      if (point) ends.push_back(pos);
    }
    f.bytes += rec;
    for (size_t i = 0; i < in_chunk.size(); ++i) {
      in_chunk[i].complete_at = compression.empty() ? content + ends[i] : f.bytes.size();
    }
    // In log-time order (stable), as the reader yields a chunk.
    std::stable_sort(in_chunk.begin(), in_chunk.end(),
                     [](const Expected& a, const Expected& b) { return a.log_time < b.log_time; });
    for (Expected& e : in_chunk) f.points.push_back(e);
  };
  loose(5);
  chunk("", {10, 11, 12, 13}, false);
  chunk("zstd", {20, 21, 22}, false);
  loose(25);
  chunk("lz4", {30, 31, 32}, true);
  chunk("", {45, 41, 43, 41, 40}, false);
  f.bytes += Rec(0x80, "application record");
  f.bytes += DataEndRec();
  f.data_end = f.bytes.size();
  f.bytes += FooterAndMagic();
  return f;
}

// ---- walking a reader ----

struct Walk;
std::vector<std::string> WalkLines(const Walk& w);

struct Walk {
  std::vector<DriveMessage> messages;
  std::vector<std::string> damages;
  std::vector<size_t> damage_after;  // how many messages came before each damage
};

// Next until kEnd (a bound guards against a reader that never ends).
Walk WalkTopic(DriveReader* reader, const std::string& topic) {
  Walk w;
  reader->SelectTopic(topic);
  DriveMessage m;
  std::string problem;
  for (int guard = 0; guard < 100000; ++guard) {
    const DriveStep step = reader->Next(&m, &problem);
    if (step == DriveStep::kEnd) {
      // kEnd stays kEnd.
      EXPECT_EQ(reader->Next(&m, &problem), DriveStep::kEnd);
      return w;
    }
    if (step == DriveStep::kMessage) w.messages.push_back(m);
    if (step == DriveStep::kDamage) {
      w.damages.push_back(problem);
      w.damage_after.push_back(w.messages.size());
    }
  }
  ADD_FAILURE() << "Next never returned kEnd";
  return w;
}

std::string Str(const std::vector<uint8_t>& v) { return std::string(v.begin(), v.end()); }

std::map<std::string, DriveTopic> TopicMap(DriveReader* reader) {
  std::map<std::string, DriveTopic> out;
  for (const DriveTopic& t : reader->Topics()) out[t.name] = t;
  return out;
}

std::string Make(const std::string& bytes, const std::string& name = "d.mcap") {
  const std::string path = test::TempDir() + "/" + name;
  WriteRaw(path, bytes);
  return path;
}

// ---- writer-made drives ----

// Payloads that do not compress (an LCG), so that chunks fill at the writer's 4 MiB also when
// compressed; the first bytes name the channel and the index.
std::string Noise(int channel, int i, size_t n) {
  std::string s(n, '\0');
  uint32_t x = uint32_t(channel * 7919 + i * 104729 + 1);
  for (size_t k = 0; k < n; ++k) {
    x = x * 1664525u + 1013904223u;
    s[k] = char(x >> 24);
  }
  s[0] = char(channel);
  s[1] = char(i);
  return s;
}

struct Written {
  std::string path;
  std::map<std::string, std::vector<std::pair<uint64_t, std::string>>> topics;
};

// /points: 14 messages of 700 KB (3 chunks: 6, 6, 2), /imu: 300 small ones interleaved (22 after
// each /points message), /empty: none.
// `times` gives /points' log times (default increasing).
Written WriteDrive(McapCompression compression, std::vector<uint64_t> times = {}) {
  Written w;
  w.path = test::TempDir() + "/w.mcap";
  if (times.empty()) {
    for (int i = 0; i < 14; ++i) times.push_back(1000000000ull + uint64_t(i) * 100000000ull);
  }
  McapWriter writer(w.path, compression);
  const uint16_t pc =
      writer.AddSchema("sensor_msgs/msg/PointCloud2", "ros2msg", PointCloud2Ros2MsgDefinition());
  const uint16_t imu_schema = writer.AddSchema("sensor_msgs/msg/Imu", "ros2msg", "float64 x\n");
  const uint16_t points = writer.AddChannel("/points", pc, "cdr");
  const uint16_t imu = writer.AddChannel("/imu", imu_schema, "cdr");
  writer.AddChannel("/empty", pc, "cdr");
  int k = 0;
  for (size_t i = 0; i < times.size(); ++i) {
    const std::string data = Noise(points, int(i), 700000);
    writer.Write(points, uint32_t(i), times[i], times[i] + 5,
                 reinterpret_cast<const uint8_t*>(data.data()), data.size());
    w.topics["/points"].push_back({times[i], data});
    for (int j = 0; j < 22 && k < 300; ++j, ++k) {
      const std::string small = Noise(imu, k, 64);
      const uint64_t t = times[i] + 1 + uint64_t(j);
      writer.Write(imu, uint32_t(k), t, t, reinterpret_cast<const uint8_t*>(small.data()),
                   small.size());
      w.topics["/imu"].push_back({t, small});
    }
  }
  writer.Close();
  return w;
}

::testing::AssertionResult SameMessages(
    const Walk& walk, const std::vector<std::pair<uint64_t, std::string>>& expected) {
  if (walk.messages.size() != expected.size()) {
    return ::testing::AssertionFailure()
           << walk.messages.size() << " messages, expected " << expected.size();
  }
  for (size_t i = 0; i < expected.size(); ++i) {
    const DriveMessage& m = walk.messages[i];
    if (m.sequence != i || m.log_time_ns != expected[i].first || Str(m.data) != expected[i].second)
      return ::testing::AssertionFailure()
             << "message " << i << ": sequence " << m.sequence << " time " << m.log_time_ns
             << " (expected " << expected[i].first << "), " << m.data.size() << " bytes";
  }
  return ::testing::AssertionSuccess();
}

size_t Count(const std::string& haystack, const std::string& needle) {
  size_t n = 0;
  for (size_t at = haystack.find(needle); at != std::string::npos;
       at = haystack.find(needle, at + 1))
    ++n;
  return n;
}

class DriveMcapCompression : public ::testing::TestWithParam<McapCompression> {};

TEST_P(DriveMcapCompression, WriterToReaderRoundTrip) {
  const Written w = WriteDrive(GetParam());
  const std::string bytes = ReadRaw(w.path);
  // Several chunks: the magic at both ends, and 3 chunks of /points' 14 x 700 KB.
  EXPECT_EQ(bytes.substr(0, 8), kMagic);
  EXPECT_EQ(bytes.substr(bytes.size() - 8), kMagic);
  EXPECT_GT(bytes.size(), size_t(14 * 700000));
  auto reader = OpenMcap(w.path);
  auto topics = TopicMap(reader.get());
  ASSERT_EQ(topics.size(), 3u);
  EXPECT_EQ(topics["/points"].messages, 14u);
  EXPECT_EQ(topics["/points"].type, "sensor_msgs/msg/PointCloud2");
  EXPECT_EQ(topics["/points"].encoding, "cdr");
  EXPECT_EQ(topics["/imu"].messages, 300u);
  EXPECT_EQ(topics["/imu"].type, "sensor_msgs/msg/Imu");
  EXPECT_EQ(topics["/empty"].messages, 0u);
  for (const char* topic : {"/points", "/imu"}) {
    const Walk walk = WalkTopic(reader.get(), topic);
    EXPECT_TRUE(walk.damages.empty()) << walk.damages[0];
    EXPECT_TRUE(SameMessages(walk, w.topics.at(topic))) << topic;
    for (const DriveMessage& m : walk.messages) {
      EXPECT_EQ(m.topic, topic);
      EXPECT_EQ(m.encoding, MessageEncoding::kCdr);
    }
  }
  const Walk empty = WalkTopic(reader.get(), "/empty");
  EXPECT_TRUE(empty.messages.empty() && empty.damages.empty());
  // Selecting again starts over, and the walk holds a chunk at a time, never the file.
  Walk again;
  const size_t largest =
      test::LargestAllocationDuring([&] { again = WalkTopic(reader.get(), "/points"); });
  EXPECT_TRUE(SameMessages(again, w.topics.at("/points")));
  EXPECT_LT(largest, size_t(6) << 20) << "the file has " << bytes.size() << " bytes";
}

TEST_P(DriveMcapCompression, ChunksComeInTheirIndexOrder) {
  // The second 4 MiB chunk (/points 6..11) logged before the first (0..5): the summary's chunk
  // indexes order by message_start_time, so 6.. come first; a scan (summary cut off) reads the
  // file order.
  std::vector<uint64_t> times;
  for (int i = 0; i < 14; ++i) times.push_back(i < 6 ? 5000 + uint64_t(i) * 10 : uint64_t(i) * 10);
  const Written w = WriteDrive(GetParam(), times);
  auto reader = OpenMcap(w.path);
  const Walk walk = WalkTopic(reader.get(), "/points");
  ASSERT_EQ(walk.messages.size(), 14u);
  EXPECT_TRUE(walk.damages.empty());
  std::vector<uint64_t> got;
  for (const DriveMessage& m : walk.messages) got.push_back(m.log_time_ns);
  // Chunks of 6, 6 and 2 /points messages (6 x 700 KB >= 4 MiB) starting at times 60, 111 (an
  // /imu message) and 5000.
  std::vector<uint64_t> expected(times.begin() + 6, times.end());
  expected.insert(expected.end(), times.begin(), times.begin() + 6);
  EXPECT_EQ(got, expected);

  // A summary CRC of 0 (not set) still lets the summary be used.
  std::string bytes = ReadRaw(w.path);
  const size_t footer = bytes.size() - 8 - 29;
  bytes.replace(footer + 25, 4, std::string(4, '\0'));
  auto unchecked = OpenMcap(Make(bytes, "unchecked.mcap"));
  std::vector<uint64_t> unchecked_times;
  for (const DriveMessage& m : WalkTopic(unchecked.get(), "/points").messages) {
    unchecked_times.push_back(m.log_time_ns);
  }
  EXPECT_EQ(unchecked_times, expected);

  // Without the summary (footer says none): the file order.
  bytes.replace(footer + 9, 20, std::string(20, '\0'));
  auto scanned = OpenMcap(Make(bytes));
  EXPECT_EQ(TopicMap(scanned.get())["/points"].messages, 14u);
  const Walk scan = WalkTopic(scanned.get(), "/points");
  EXPECT_TRUE(scan.damages.empty());
  ASSERT_EQ(scan.messages.size(), 14u);
  for (size_t i = 0; i < 14; ++i) EXPECT_EQ(scan.messages[i].log_time_ns, times[i]) << i;
}

TEST_P(DriveMcapCompression, CrcFlipInAChunkIsDamageAndTheNextChunkIsRead) {
  const Written w = WriteDrive(GetParam());
  std::string bytes = ReadRaw(w.path);
  // The middle chunk: find its start from /points message 8's payload (uncompressed) or from
  // the file's middle (compressed: any byte of the stored records).
  size_t at = bytes.size() / 2;
  if (GetParam() == McapCompression::kNone) at = bytes.find(Noise(0, 8, 700000).substr(0, 64));
  ASSERT_NE(at, std::string::npos);
  bytes[at + 1000] ^= 0x01;
  auto reader = OpenMcap(Make(bytes));
  const Walk walk = WalkTopic(reader.get(), "/points");
  ASSERT_EQ(walk.damages.size(), 1u);
  EXPECT_NE(walk.damages[0].find("chunk 2"), std::string::npos) << walk.damages[0];
  EXPECT_NE(walk.damages[0].find("d.mcap"), std::string::npos) << walk.damages[0];
  if (GetParam() == McapCompression::kNone) {
    EXPECT_NE(walk.damages[0].find("CRC"), std::string::npos) << walk.damages[0];
  }
  // Chunk 1 (0..5) before the damage, chunk 3 (12, 13) after it.
  ASSERT_EQ(walk.messages.size(), 8u);
  EXPECT_EQ(walk.damage_after[0], 6u);
  const auto& expected = w.topics.at("/points");
  for (size_t i = 0; i < 8; ++i) {
    const size_t k = i < 6 ? i : i + 6;
    EXPECT_EQ(Str(walk.messages[i].data), expected[k].second) << i;
    EXPECT_EQ(walk.messages[i].sequence, i);
  }
}

TEST_P(DriveMcapCompression, BrokenSummaryFallsBackToAScan) {
  const Written w = WriteDrive(GetParam());
  std::string bytes = ReadRaw(w.path);
  // The summary's copy of the /points channel is the last "/points" in the file; renaming it
  // breaks the summary CRC, and the scan finds the data section's channel.
  const size_t at = bytes.rfind("/points");
  ASSERT_GT(at, bytes.size() / 2);
  bytes[at + 2] = 'X';
  auto reader = OpenMcap(Make(bytes));
  auto topics = TopicMap(reader.get());
  EXPECT_EQ(topics.count("/pXints"), 0u);
  EXPECT_EQ(topics["/points"].messages, 14u);
  EXPECT_EQ(topics["/imu"].messages, 300u);
  EXPECT_TRUE(SameMessages(WalkTopic(reader.get(), "/points"), w.topics.at("/points")));
}

TEST_P(DriveMcapCompression, CutsAtManyOffsetsYieldAPrefixThenDamage) {
  const Written w = WriteDrive(GetParam());
  const std::string bytes = ReadRaw(w.path);
  const auto& expected = w.topics.at("/imu");
  for (size_t cut = 0; cut < bytes.size(); cut += 1 + bytes.size() / 37) {
    const std::string path = Make(bytes.substr(0, cut), "cut.mcap");
    std::unique_ptr<DriveReader> reader;
    try {
      reader = OpenMcap(path);
      reader->Topics();
      reader->SelectTopic("/imu");
    } catch (const IoError& e) {
      EXPECT_LT(cut, 1000u) << "cut " << cut << ": " << e.what();
      continue;
    }
    const Walk walk = WalkTopic(reader.get(), "/imu");
    ASSERT_EQ(walk.damages.size(), 1u) << "cut " << cut;
    EXPECT_EQ(walk.damage_after[0], walk.messages.size()) << "cut " << cut;
    EXPECT_NE(walk.damages[0].find("truncated"), std::string::npos) << walk.damages[0];
    ASSERT_LE(walk.messages.size(), expected.size());
    for (size_t i = 0; i < walk.messages.size(); ++i) {
      ASSERT_EQ(Str(walk.messages[i].data), expected[i].second) << "cut " << cut << " at " << i;
    }
    // Every chunk wholly before the cut (one per 4.21 MB, each with at least 110 /imu messages)
    // has been read.
    EXPECT_GE(walk.messages.size(), (cut / 4500000) * 110) << "cut " << cut;
  }
}

INSTANTIATE_TEST_SUITE_P(, DriveMcapCompression,
                         ::testing::Values(McapCompression::kNone, McapCompression::kZstd,
                                           McapCompression::kLz4),
                         [](const auto& info) {
                           return info.param == McapCompression::kNone   ? "none"
                                  : info.param == McapCompression::kZstd ? "zstd"
                                                                         : "lz4";
                         });

// ---- hand-made files ----

TEST(DriveMcap, UnindexedFileIsScannedWithMessagesInAndOutsideChunks) {
  const HandFile f = MakeHandFile();
  auto reader = OpenMcap(Make(f.bytes));
  auto topics = TopicMap(reader.get());
  ASSERT_EQ(topics.size(), 2u);
  EXPECT_EQ(topics["/points"].messages, f.points.size());
  EXPECT_EQ(topics["/points"].type, "sensor_msgs/msg/PointCloud2");
  EXPECT_EQ(topics["/other"].messages, f.points.size());
  const Walk walk = WalkTopic(reader.get(), "/points");
  EXPECT_TRUE(walk.damages.empty()) << walk.damages[0];
  ASSERT_EQ(walk.messages.size(), f.points.size());
  for (size_t i = 0; i < f.points.size(); ++i) {
    EXPECT_EQ(walk.messages[i].log_time_ns, f.points[i].log_time) << i;
    EXPECT_EQ(Str(walk.messages[i].data), f.points[i].data) << i;
  }
  // The last chunk's times 45 41 43 41 40 come as 40 41 41 43 45, the two 41s in record order.
  const size_t last = f.points.size() - 5;
  EXPECT_EQ(walk.messages[last].log_time_ns, 40u);
  EXPECT_EQ(walk.messages[last + 1].log_time_ns, 41u);
  EXPECT_LT(uint8_t(walk.messages[last + 1].data[0]), uint8_t(walk.messages[last + 2].data[0]));
}

TEST(DriveMcap, HandFileCutAtEveryOffset) {
  const HandFile f = MakeHandFile();
  for (size_t cut = 0; cut < f.bytes.size(); ++cut) {
    const std::string path = Make(f.bytes.substr(0, cut), "cut.mcap");
    std::unique_ptr<DriveReader> reader;
    try {
      reader = OpenMcap(path);
      reader->SelectTopic("/points");
    } catch (const IoError& e) {
      EXPECT_LT(cut, f.channel_end) << e.what();
      EXPECT_NE(std::string(e.what()).find(path), std::string::npos);
      continue;
    }
    const Walk walk = WalkTopic(reader.get(), "/points");
    // Three workers decompressing ahead give the same walk, damage included.
    EXPECT_EQ(WalkLines(WalkTopic(OpenMcap(path, 3).get(), "/points")), WalkLines(walk))
        << "cut " << cut;
    // Exactly the messages complete before the cut, in order, then one damage (a cut after the
    // data end record loses no message and is not damage).
    std::vector<std::string> complete;
    for (const Expected& e : f.points) {
      if (e.complete_at <= cut) complete.push_back(e.data);
    }
    ASSERT_EQ(walk.messages.size(), complete.size()) << "cut " << cut;
    for (size_t i = 0; i < complete.size(); ++i) {
      ASSERT_EQ(Str(walk.messages[i].data), complete[i]) << "cut " << cut << " message " << i;
    }
    if (cut < f.data_end) {
      ASSERT_EQ(walk.damages.size(), 1u) << "cut " << cut;
      EXPECT_NE(walk.damages[0].find("truncated"), std::string::npos) << walk.damages[0];
      EXPECT_NE(walk.damages[0].find(path), std::string::npos) << walk.damages[0];
    } else {
      EXPECT_TRUE(walk.damages.empty()) << walk.damages[0];
    }
  }
}

// The hand file with one chunk replaced; returns the walk of /points.
Walk WalkWithChunk(const std::string& chunk, std::string* path_out = nullptr) {
  const std::string bytes = kMagic + HeaderRec() + SchemaRec(1, "sensor_msgs/msg/PointCloud2") +
                            ChannelRec(1, 1, "/points") + ChunkRec(MessageRec(1, 1, "first"), "") +
                            chunk + ChunkRec(MessageRec(1, 3, "last"), "zstd") + DataEndRec() +
                            FooterAndMagic();
  const std::string path = Make(bytes);
  if (path_out) *path_out = path;
  auto reader = OpenMcap(path);
  return WalkTopic(reader.get(), "/points");
}

// Expects first, one damage naming chunk 2 and every word, last.
void ExpectDamagedMiddle(const Walk& walk, const std::vector<std::string>& words) {
  ASSERT_EQ(walk.messages.size(), 2u);
  EXPECT_EQ(Str(walk.messages[0].data), "first");
  EXPECT_EQ(Str(walk.messages[1].data), "last");
  EXPECT_EQ(walk.messages[1].sequence, 1u);
  ASSERT_EQ(walk.damages.size(), 1u);
  EXPECT_EQ(walk.damage_after[0], 1u);
  EXPECT_NE(walk.damages[0].find("chunk 2 at byte"), std::string::npos) << walk.damages[0];
  EXPECT_NE(walk.damages[0].find("(after 1 message of /points)"), std::string::npos)
      << walk.damages[0];
  for (const std::string& word : words) {
    EXPECT_NE(walk.damages[0].find(word), std::string::npos) << word << ": " << walk.damages[0];
  }
}

TEST(DriveMcap, DamagedChunksOfAScannedFile) {
  const std::string records = MessageRec(1, 2, "middle") + MessageRec(1, 2, "middle2");
  for (const char* compression : {"", "zstd", "lz4"}) {
    // A CRC that does not match the records.
    std::string bad_crc = ChunkRec(records, compression);
    const size_t crc_at = 9 + 24;
    bad_crc[crc_at] ^= 0x10;
    ExpectDamagedMiddle(WalkWithChunk(bad_crc), {"CRC"});
    // A flipped byte in the stored records.
    std::string flipped = ChunkRec(records, compression);
    flipped[flipped.size() - 3] ^= 0x40;
    ExpectDamagedMiddle(WalkWithChunk(flipped), {});
    // An uncompressed size that is not the records'.
    const std::string stored = Compress(records, compression);
    ExpectDamagedMiddle(WalkWithChunk(Rec(0x06, Bin()
                                                    .U64(0)
                                                    .U64(0)
                                                    .U64(records.size() + 5)
                                                    .U32(0)
                                                    .Str(compression)
                                                    .U64(stored.size())
                                                    .Raw(stored)
                                                    .b)),
                        {std::to_string(records.size() + 5)});
  }
  // An unknown compression.
  ExpectDamagedMiddle(WalkWithChunk(ChunkRec(records, "brotli")), {"unknown compression 'brotli'"});
  // Records that overrun the chunk: a message record claiming 2^62 bytes.
  const std::string huge = Bin().U8(0x05).U64(uint64_t(1) << 62).U16(1).b;
  ExpectDamagedMiddle(WalkWithChunk(ChunkRec(huge, "")), {"overruns"});
  // A malformed message (too short for its fixed fields) after a good one: the good one is kept.
  {
    const Walk walk = WalkWithChunk(ChunkRec(MessageRec(1, 2, "kept") + Rec(0x05, "abc"), ""));
    ASSERT_EQ(walk.messages.size(), 3u);
    EXPECT_EQ(Str(walk.messages[1].data), "kept");
    ASSERT_EQ(walk.damages.size(), 1u);
    EXPECT_NE(walk.damages[0].find("malformed"), std::string::npos) << walk.damages[0];
  }
  // A records length past the chunk record and a compression string longer than it.
  ExpectDamagedMiddle(
      WalkWithChunk(Rec(0x06, Bin().U64(0).U64(0).U64(4).U32(0).Str("").U64(~0ull).b)),
      {"malformed chunk"});
  ExpectDamagedMiddle(WalkWithChunk(Rec(0x06, Bin().U64(0).U64(0).U64(4).U32(0).U32(~0u).b)),
                      {"malformed chunk"});
}

TEST(DriveMcap, HugeClaimsAllocateNothing) {
  // A zstd chunk claiming 2^40 bytes uncompressed, and one claiming 512 MiB for a few bytes.
  const std::string records = MessageRec(1, 2, "middle");
  const std::string stored = Compress(records, "zstd");
  for (uint64_t claim : {uint64_t(1) << 40, uint64_t(512) << 20}) {
    const std::string chunk = Rec(
        0x06, Bin().U64(0).U64(0).U64(claim).U32(0).Str("zstd").U64(stored.size()).Raw(stored).b);
    Walk walk;
    const size_t largest = test::LargestAllocationDuring([&] { walk = WalkWithChunk(chunk); });
    ExpectDamagedMiddle(walk, {"zstd"});
    EXPECT_LE(largest, size_t(4) << 20) << claim;
  }
  // A top-level record claiming 2^63 bytes: the file ends inside it.
  const std::string bytes = kMagic + HeaderRec() + ChannelRec(1, 0, "/points") +
                            Rec(0x05, Bin().U16(1).U32(0).U64(1).U64(1).Raw("ok").b) +
                            Bin().U8(0x06).U64(uint64_t(1) << 63).U64(0).b;
  Walk walk;
  const size_t largest = test::LargestAllocationDuring([&] {
    auto reader = OpenMcap(Make(bytes));
    walk = WalkTopic(reader.get(), "/points");
  });
  ASSERT_EQ(walk.messages.size(), 1u);
  ASSERT_EQ(walk.damages.size(), 1u);
  EXPECT_NE(walk.damages[0].find("truncated"), std::string::npos) << walk.damages[0];
  EXPECT_LE(largest, size_t(1) << 20);
  // A header claiming 2^63 bytes: not an MCAP file we can read.
  EXPECT_TRUE(ThrowsIoError(
      [&] { OpenMcap(Make(kMagic + Bin().U8(0x01).U64(uint64_t(1) << 63).b + "xxxxxxxx")); },
      "d.mcap", {"header"}));
}

TEST(DriveMcap, BadMagicShortFilesAndMissingHeaderAreIoErrors) {
  const HandFile f = MakeHandFile();
  std::string bad = f.bytes;
  bad[1] = 'N';
  EXPECT_TRUE(ThrowsIoError([&] { OpenMcap(Make(bad)); }, "d.mcap", {"magic"}));
  EXPECT_TRUE(ThrowsIoError([&] { OpenMcap(Make("")); }, "d.mcap", {"too short"}));
  EXPECT_TRUE(ThrowsIoError([&] { OpenMcap(Make(kMagic)); }, "d.mcap", {"too short"}));
  EXPECT_TRUE(ThrowsIoError([&] { OpenMcap(Make(kMagic + ChannelRec(1, 0, "/a"))); }, "d.mcap",
                            {"header"}));
  EXPECT_TRUE(
      ThrowsIoError([&] { OpenMcap(Make(kMagic + Rec(0x01, "\x05"))); }, "d.mcap", {"header"}));
  EXPECT_TRUE(
      ThrowsIoError([&] { OpenMcap(test::TempDir() + "/missing.mcap"); }, "missing.mcap", {}));
  EXPECT_TRUE(ThrowsIoError([&] { OpenMcap(test::TempDir()); }, "/", {}));
}

TEST(DriveMcap, UnknownOpcodesAreSkipped) {
  const std::string bytes =
      kMagic + HeaderRec() + Rec(0xA0, "top-level extension") + ChannelRec(1, 0, "/points") +
      Rec(0x0C, Bin().Str("meta").U32(0).b) +  // metadata
      ChunkRec(Rec(0x7E, "future record") + MessageRec(1, 1, "a") + Rec(0xFF, ""), "zstd") +
      Rec(0x07, Bin().U16(1).U32(0).b) +  // a message index
      Rec(0x09, Bin().U64(0).U64(0).Str("att").Str("text/plain").U64(1).Raw("z").U32(0).b) +
      MessageRec(1, 2, "b") + DataEndRec() + FooterAndMagic();
  auto reader = OpenMcap(Make(bytes));
  EXPECT_EQ(TopicMap(reader.get())["/points"].messages, 2u);
  const Walk walk = WalkTopic(reader.get(), "/points");
  EXPECT_TRUE(walk.damages.empty()) << walk.damages[0];
  ASSERT_EQ(walk.messages.size(), 2u);
  EXPECT_EQ(Str(walk.messages[0].data), "a");
  EXPECT_EQ(Str(walk.messages[1].data), "b");
}

TEST(DriveMcap, MessageEncodings) {
  const std::string bytes = kMagic + HeaderRec() + SchemaRec(1, "sensor_msgs/PointCloud2") +
                            ChannelRec(1, 1, "/ros1", "ros1") + ChannelRec(2, 1, "/json", "json") +
                            MessageRec(1, 1, "r") + MessageRec(2, 1, "{}") + DataEndRec() +
                            FooterAndMagic();
  const std::string path = Make(bytes);
  auto reader = OpenMcap(path);
  auto topics = TopicMap(reader.get());
  EXPECT_EQ(topics["/ros1"].type, "sensor_msgs/PointCloud2");
  EXPECT_EQ(topics["/ros1"].encoding, "ros1");
  EXPECT_EQ(topics["/json"].encoding, "json");
  const Walk walk = WalkTopic(reader.get(), "/ros1");
  ASSERT_EQ(walk.messages.size(), 1u);
  EXPECT_EQ(walk.messages[0].encoding, MessageEncoding::kRos1);
  EXPECT_TRUE(ThrowsIoError([&] { reader->SelectTopic("/json"); }, path, {"'json'", "/json"}));
  EXPECT_TRUE(ThrowsIoError([&] { reader->SelectTopic("/nope"); }, path, {"/nope", "/ros1"}));
}

TEST(DriveMcap, WriterOutputHasTheSpecifiedLayout) {
  // Checked against the specification by hand: footer fields, summary CRC, data end CRC, the
  // summary offsets' groups, and a chunk followed by its message index.
  const Written w = WriteDrive(McapCompression::kZstd);
  const std::string b = ReadRaw(w.path);
  auto u64 = [&](size_t at) {
    uint64_t v = 0;
    for (int i = 0; i < 8; ++i) v |= uint64_t(uint8_t(b[at + i])) << (8 * i);
    return v;
  };
  auto u32 = [&](size_t at) { return uint32_t(u64(at) & 0xFFFFFFFFu); };
  const size_t footer = b.size() - 8 - 29;
  ASSERT_EQ(uint8_t(b[footer]), 0x02);
  EXPECT_EQ(u64(footer + 1), 20u);
  const uint64_t summary_start = u64(footer + 9), offsets_start = u64(footer + 17);
  ASSERT_GT(offsets_start, summary_start);
  const auto* p = reinterpret_cast<const uint8_t*>(b.data());
  EXPECT_EQ(u32(footer + 25), Crc32(p + summary_start, footer + 25 - summary_start));
  // Data end: the record just before the summary, CRC over everything before it.
  const size_t data_end = summary_start - 13;
  ASSERT_EQ(uint8_t(b[data_end]), 0x0F);
  EXPECT_EQ(u32(data_end + 9), Crc32(p, data_end));
  // Summary offsets: schema, channel, statistics and chunk index groups, each pointing at a run
  // of records of its opcode that fills the summary.
  std::vector<uint8_t> groups;
  uint64_t covered = 0;
  for (size_t at = offsets_start; at < footer;) {
    ASSERT_EQ(uint8_t(b[at]), 0x0E);
    const uint8_t op = uint8_t(b[at + 9]);
    const uint64_t start = u64(at + 10), length = u64(at + 18);
    groups.push_back(op);
    covered += length;
    for (uint64_t r = start; r < start + length; r += 9 + u64(r + 1)) EXPECT_EQ(uint8_t(b[r]), op);
    at += 9 + u64(at + 1);
  }
  EXPECT_EQ(groups, (std::vector<uint8_t>{0x03, 0x04, 0x0B, 0x08}));
  EXPECT_EQ(covered, offsets_start - summary_start);
  // The first chunk follows the header and the schema/channel records; a message index follows it.
  size_t at = 8;
  while (uint8_t(b[at]) != 0x06) at += 9 + u64(at + 1);
  at += 9 + u64(at + 1);
  EXPECT_EQ(uint8_t(b[at]), 0x07);
  EXPECT_EQ(Count(b, "MSG: std_msgs/Header"), 2u);  // the schema in data and summary
  EXPECT_NE(PointCloud2Ros2MsgDefinition().find("PointField[] fields"), std::string::npos);
  EXPECT_NE(PointCloud2Ros2MsgDefinition().find("MSG: builtin_interfaces/Time\nint32 sec\n"),
            std::string::npos);
}

// ---- decompression ahead (several workers) and chunk ranges ----

// The walk as text: a line per message (sequence, log time, data) and per damage (its place and
// problem).
std::vector<std::string> WalkLines(const Walk& w) {
  std::vector<std::string> lines;
  size_t d = 0;
  for (size_t i = 0; i <= w.messages.size(); ++i) {
    for (; d < w.damages.size() && w.damage_after[d] == i; ++d)
      lines.push_back("damage after " + std::to_string(i) + ": " + w.damages[d]);
    if (i == w.messages.size()) break;
    const DriveMessage& m = w.messages[i];
    lines.push_back(std::to_string(m.sequence) + " " + std::to_string(m.log_time_ns) + " " +
                    Str(m.data));
  }
  return lines;
}

// A file without summary (scanned): 40 chunks of none, zstd and lz4, four /points messages each
// out of log-time order, /other messages among them, a /points message outside the chunks every
// fifth chunk. `damaged`: chunk 21's stored records have a byte flipped.
std::string ManyChunkFile(bool damaged) {
  std::string bytes = kMagic + HeaderRec() + SchemaRec(1, "sensor_msgs/msg/PointCloud2") +
                      ChannelRec(1, 1, "/points") + ChannelRec(2, 1, "/other");
  const char* kinds[] = {"", "zstd", "lz4"};
  int n = 0;
  for (int c = 0; c < 40; ++c) {
    std::string records;
    for (uint64_t t : {3, 1, 2, 1}) {
      records += MessageRec(2, 100 * uint64_t(c) + t, "other");
      records += MessageRec(1, 100 * uint64_t(c) + t, Payload(n++, 300));
    }
    std::string chunk = ChunkRec(records, kinds[c % 3]);
    if (damaged && c == 20) chunk[chunk.size() - 40] ^= 0x10;
    bytes += chunk;
    if (c % 5 == 4) bytes += MessageRec(1, 100 * uint64_t(c) + 50, Payload(n++, 20));
  }
  return bytes + DataEndRec() + FooterAndMagic();
}

TEST(DriveMcap, SeveralWorkersYieldWhatOneYieldsScanned) {
  for (bool damaged : {false, true}) {
    SCOPED_TRACE(damaged ? "damaged" : "whole");
    const std::string path = Make(ManyChunkFile(damaged), "many.mcap");
    const std::vector<std::string> one = WalkLines(WalkTopic(OpenMcap(path, 1).get(), "/points"));
    ASSERT_EQ(one.size(), damaged ? 168u - 4 + 1 : 168u);
    if (damaged) {
      // after chunks 1..20's 80 messages and the 4 outside them
      EXPECT_EQ(one[84].rfind("damage after 84: ", 0), 0u) << one[84];
      EXPECT_NE(one[84].find("chunk 21 at byte"), std::string::npos) << one[84];
    }
    for (unsigned workers : {2u, 3u, 8u}) {
      auto reader = OpenMcap(path, workers);
      EXPECT_EQ(WalkLines(WalkTopic(reader.get(), "/points")), one) << workers << " workers";
      EXPECT_EQ(WalkLines(WalkTopic(reader.get(), "/points")), one) << "selected again";
    }
  }
}

TEST_P(DriveMcapCompression, SeveralWorkersYieldWhatOneYieldsIndexed) {
  std::vector<uint64_t> times;
  for (int i = 0; i < 40; ++i) times.push_back(1000 + uint64_t(i) * 10);
  const Written w = WriteDrive(GetParam(), times);  // 7 chunks
  for (bool damaged : {false, true}) {
    SCOPED_TRACE(damaged ? "damaged" : "whole");
    std::string bytes = ReadRaw(w.path);
    if (damaged) {  // inside chunk 4 (/points 18..23)
      const size_t at = bytes.find(Noise(0, 20, 700000).substr(0, 64));
      bytes[GetParam() == McapCompression::kNone ? at + 1000 : bytes.size() / 2] ^= 0x01;
    }
    const std::string path = Make(bytes, "many.mcap");
    const std::vector<std::string> one = WalkLines(WalkTopic(OpenMcap(path, 1).get(), "/points"));
    EXPECT_EQ(one.size(), damaged ? 35u : 40u);
    for (unsigned workers : {2u, 4u}) {
      auto reader = OpenMcap(path, workers);
      EXPECT_EQ(WalkLines(WalkTopic(reader.get(), "/points")), one) << workers << " workers";
    }
  }
}

// A reader destroyed, or given another topic, in the middle of a drive with workers ahead: no
// thread is left (the join would hang) and nothing leaks (LeakSanitizer).
TEST(DriveMcap, DestroyedInTheMiddleWithWorkersAhead) {
  const std::string path = Make(ManyChunkFile(false), "many.mcap");
  for (size_t stop : {0u, 1u, 9u, 100u}) {
    auto reader = OpenMcap(path, 4);
    reader->SelectTopic("/points");
    DriveMessage m;
    std::string problem;
    for (size_t k = 0; k < stop; ++k) ASSERT_EQ(reader->Next(&m, &problem), DriveStep::kMessage);
    reader->SelectTopic("/other");
    ASSERT_EQ(reader->Next(&m, &problem), DriveStep::kMessage);
    EXPECT_EQ(Str(m.data), "other");
  }
}

// Every message of the ranges of `partition` (each its own SelectChunks), as WalkLines' lines.
std::vector<std::string> RangeLines(DriveReader* reader,
                                    const std::vector<std::pair<uint64_t, uint64_t>>& partition) {
  std::vector<std::string> lines;
  for (const auto& [first, last] : partition) {
    reader->SelectTopic("/points");
    reader->SelectChunks(first, last);
    Walk w;
    DriveMessage m;
    std::string problem;
    for (DriveStep step; (step = reader->Next(&m, &problem)) != DriveStep::kEnd;) {
      if (step == DriveStep::kMessage) w.messages.push_back(m);
      if (step == DriveStep::kDamage) {
        w.damages.push_back(problem);
        w.damage_after.push_back(w.messages.size());
      }
    }
    for (std::string& line : WalkLines(w)) lines.push_back(std::move(line));
  }
  return lines;
}

// The ranges of a partition of the chunks yield together what the whole run yields, sequence
// numbers included: the hand file (scanned; messages outside chunks go with the chunk before
// them) and writer-made drives (indexed).
TEST_P(DriveMcapCompression, ChunkRangesTogetherYieldTheWholeRun) {
  const Written w = WriteDrive(GetParam());  // 3 chunks
  const HandFile f = MakeHandFile();         // 4 chunks
  for (const std::string& path : {w.path, Make(f.bytes, "hand.mcap")}) {
    SCOPED_TRACE(path);
    for (unsigned workers : {1u, 3u}) {
      auto reader = OpenMcap(path, workers);
      const uint64_t chunks = reader->ChunkCount();
      EXPECT_EQ(chunks, path == w.path ? 3u : 4u);
      EXPECT_EQ(reader->ChunksIndexed(), path == w.path);
      const std::vector<std::string> whole = WalkLines(WalkTopic(reader.get(), "/points"));
      std::vector<std::vector<std::pair<uint64_t, uint64_t>>> partitions = {{{1, chunks}}};
      partitions.push_back({});
      for (uint64_t c = 1; c <= chunks; ++c) partitions.back().push_back({c, c});
      partitions.push_back({{1, 2}, {3, chunks}});
      for (const auto& partition : partitions)
        EXPECT_EQ(RangeLines(reader.get(), partition), whole) << partition.size() << " ranges";
      EXPECT_TRUE(ThrowsIoError([&] { reader->SelectChunks(1, chunks + 1); }, path, {"has"}));
      EXPECT_TRUE(ThrowsIoError([&] { reader->SelectChunks(0, 1); }, path, {"from 1"}));
    }
  }
}

// An indexed file's range counts the messages before it from the message indexes, never
// decompressing those chunks: a damaged chunk 1 is not seen by the range 2..3, whose sequence
// numbers still start at 6; the range 1..1 reports it.
TEST_P(DriveMcapCompression, ARangeSkipsTheChunksBeforeItAndOwnsItsDamage) {
  const Written w = WriteDrive(GetParam());
  std::string bytes = ReadRaw(w.path);
  const size_t at = bytes.find(Noise(0, 2, 700000).substr(0, 64));
  bytes[GetParam() == McapCompression::kNone ? at + 1000 : 3000] ^= 0x01;
  auto reader = OpenMcap(Make(bytes, "bad1.mcap"), 2);
  const std::vector<std::string> later = RangeLines(reader.get(), {{2, 3}});
  ASSERT_EQ(later.size(), 8u);
  for (size_t i = 0; i < 8; ++i)
    EXPECT_EQ(later[i].substr(0, later[i].find(' ')), std::to_string(6 + i)) << later[i];
  const std::vector<std::string> first = RangeLines(reader.get(), {{1, 1}});
  ASSERT_EQ(first.size(), 1u);
  EXPECT_NE(first[0].find("chunk 1 at byte"), std::string::npos) << first[0];
}

TEST(DriveMcap, WriterCannotCreateAFileInAMissingFolder) {
  EXPECT_TRUE(ThrowsIoError(
      [] { McapWriter(test::TempDir() + "/no/such/dir/x.mcap", McapCompression::kNone); }, "x.mcap",
      {"create"}));
}

}  // namespace
}  // namespace lpir
