// The recorded-drive readers against drives that independent writers made (tests/data/drives/:
// @mcap/core, sqlite3, python3-rosbag; scripts/make_drive_fixtures.sh), and against damaged
// copies of them made here: truncated mid-chunk, a flipped byte in a chunk, an unknown
// compression. The chunks are found by walking the files' records in this test, not by the
// readers under test.
#include "tests/drive_fixtures.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cstring>
#include <functional>
#include <ostream>
#include <string>
#include <vector>

#include "host/drive/drive.h"
#include "host/io/io_error.h"
#include "tests/io_test_helpers.h"
#include "tests/test_util.h"

namespace lpir {
namespace {

const char kTopic[] = "/velodyne_points";
constexpr uint64_t kFirstStampNs = 1600000000ull * 1000000000ull;  // then 100 ms apart
constexpr size_t kFrames = 3;

enum class Container { kMcap, kDb3, kBag };

struct Fixture {
  const char* file;
  Container container;
  const char* type;
  const char* encoding;
  const char* compression;  // as the file names it in each chunk
};

const Fixture kFixtures[] = {
    {"vlp16_zstd.mcap", Container::kMcap, "sensor_msgs/msg/PointCloud2", "cdr", "zstd"},
    {"vlp16_lz4.mcap", Container::kMcap, "sensor_msgs/msg/PointCloud2", "cdr", "lz4"},
    {"vlp16_none.mcap", Container::kMcap, "sensor_msgs/msg/PointCloud2", "cdr", ""},
    {"vlp16.db3", Container::kDb3, "sensor_msgs/msg/PointCloud2", "cdr", ""},
    {"vlp16_bz2.bag", Container::kBag, "sensor_msgs/PointCloud2", "ros1", "bz2"},
    {"vlp16_lz4.bag", Container::kBag, "sensor_msgs/PointCloud2", "ros1", "lz4"},
};

std::string FixturePath(const Fixture& f) { return test::DrivesDir() + "/" + f.file; }

// gtest's name for a fixture in test names and listings: its file name.
void PrintTo(const Fixture& f, std::ostream* os) { *os << f.file; }
std::string FixtureName(const ::testing::TestParamInfo<Fixture>& info) {
  std::string name = info.param.file;
  for (char& c : name)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return name;
}

std::string Lower(std::string s) {
  for (char& c : s) c = char(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

// What reading the selected topic to the end gave: the steps in order, the messages' clouds,
// and the damage reports. An IoError thrown on the way ends the read and is kept in `error`.
struct ReadOut {
  std::vector<DriveStep> steps;
  std::vector<DriveMessage> messages;
  std::vector<std::string> problems;
  std::string error;
};

ReadOut ReadAll(const std::string& path, const std::string& topic) {
  ReadOut out;
  try {
    std::unique_ptr<DriveReader> reader = OpenDrive(path);
    reader->SelectTopic(topic);
    for (int guard = 0; guard < 100; ++guard) {  // 3 messages and a few damage reports at most
      DriveMessage message;
      std::string problem;
      const DriveStep step = reader->Next(&message, &problem);
      out.steps.push_back(step);
      if (step == DriveStep::kMessage) out.messages.push_back(message);
      if (step == DriveStep::kDamage) out.problems.push_back(problem);
      if (step == DriveStep::kEnd) break;
    }
  } catch (const IoError& e) {
    out.error = e.what();
  }
  return out;
}

// Succeeds when `message` decodes to frame `frame` of the fixtures, bit for bit.
::testing::AssertionResult IsFrame(const std::string& path, const DriveMessage& message,
                                   size_t frame) {
  Cloud cloud;
  try {
    cloud = DecodeDriveCloud(path, message);
  } catch (const IoError& e) {
    return ::testing::AssertionFailure() << "cannot decode: " << e.what();
  }
  const ::testing::AssertionResult same = test::SameBits(cloud, test::FixtureFrame(frame));
  if (!same) return ::testing::AssertionFailure() << "frame " << frame << ": " << same.message();
  return ::testing::AssertionSuccess();
}

// ---- Locating chunks without the readers under test ----

uint64_t Le(const std::string& b, size_t at, int bytes) {
  uint64_t v = 0;
  for (int k = bytes - 1; k >= 0; --k) v = v << 8 | uint8_t(b[at + size_t(k)]);
  return v;
}

struct ChunkSpan {
  size_t record = 0;       // first byte of the record
  size_t data = 0;         // first byte of its (compressed) payload
  size_t data_size = 0;    // payload bytes
  size_t compression = 0;  // first byte of the compression name, its length below
  size_t compression_size = 0;
};

// The Chunk records (opcode 0x06) of an MCAP file, walking records from after the magic: opcode
// u8, length u64, body. A chunk's body: start u64, end u64, uncompressed size u64, CRC u32,
// compression (u32 length + bytes), records (u64 length + bytes).
std::vector<ChunkSpan> McapChunks(const std::string& b) {
  std::vector<ChunkSpan> chunks;
  size_t at = 8;
  while (at + 9 <= b.size()) {
    const uint8_t op = uint8_t(b[at]);
    const uint64_t len = Le(b, at + 1, 8);
    const size_t body = at + 9;
    if (len > b.size() - body) break;
    if (op == 0x02) break;  // footer
    if (op == 0x06) {
      ChunkSpan c;
      c.record = at;
      c.compression_size = Le(b, body + 28, 4);
      c.compression = body + 32;
      c.data_size = Le(b, c.compression + c.compression_size, 8);
      c.data = c.compression + c.compression_size + 8;
      chunks.push_back(c);
    }
    at = body + len;
  }
  return chunks;
}

// The chunk records (op=0x05) of a ROS 1 bag 2.0, walking records from after "#ROSBAG V2.0\n":
// header length u32, header fields (u32 length + "name=value"), data length u32, data.
std::vector<ChunkSpan> BagChunks(const std::string& b) {
  std::vector<ChunkSpan> chunks;
  size_t at = 13;
  while (at + 4 <= b.size()) {
    const uint64_t header_len = Le(b, at, 4);
    const size_t header = at + 4;
    if (header_len > b.size() - header || b.size() - header - header_len < 4) break;
    const size_t data_len_at = header + header_len;
    const uint64_t data_len = Le(b, data_len_at, 4);
    if (data_len > b.size() - data_len_at - 4) break;
    bool is_chunk = false;
    ChunkSpan c;
    for (size_t f = header; f + 4 <= data_len_at;) {
      const uint64_t field_len = Le(b, f, 4);
      if (field_len > data_len_at - f - 4) break;
      const std::string field = b.substr(f + 4, field_len);
      if (field == std::string("op=\x05", 4)) is_chunk = true;
      if (field.rfind("compression=", 0) == 0) {
        c.compression = f + 4 + 12;
        c.compression_size = field_len - 12;
      }
      f += 4 + field_len;
    }
    if (is_chunk) {
      c.record = at;
      c.data = data_len_at + 4;
      c.data_size = data_len;
      chunks.push_back(c);
    }
    at = data_len_at + 4 + data_len;
  }
  return chunks;
}

std::vector<ChunkSpan> Chunks(const Fixture& f, const std::string& bytes) {
  return f.container == Container::kMcap ? McapChunks(bytes) : BagChunks(bytes);
}

// A copy of fixture `f` changed by `edit`, in a temporary folder with the fixture's file name.
std::string DamagedCopy(const test::ScopedDir& dir, const Fixture& f,
                        const std::function<void(std::string*)>& edit) {
  std::string bytes = test::ReadRaw(FixturePath(f));
  edit(&bytes);
  const std::string path = dir.path + "/" + f.file;
  test::WriteRaw(path, bytes);
  return path;
}

// A copy of fixture `f` (one message per chunk) with a byte flipped in the middle of its second
// chunk's payload.
std::string SecondChunkFlipped(const test::ScopedDir& dir, const Fixture& f) {
  return DamagedCopy(dir, f, [&](std::string* b) {
    const std::vector<ChunkSpan> chunks = Chunks(f, *b);
    ASSERT_EQ(chunks.size(), kFrames);
    (*b)[chunks[1].data + chunks[1].data_size / 2] ^= 0x10;
  });
}

class DriveFixture : public ::testing::TestWithParam<Fixture> {
 protected:
  void SetUp() override {
    if (test::ReadRaw(FixturePath(GetParam())).empty())
      GTEST_FAIL() << "fixture " << FixturePath(GetParam())
                   << " is missing (scripts/make_drive_fixtures.sh makes it)";
  }
};

TEST_P(DriveFixture, TopicsNameTheCloudTopicItsTypeAndThreeMessages) {
  const Fixture& f = GetParam();
  const std::vector<DriveTopic> topics = OpenDrive(FixturePath(f))->Topics();
  ASSERT_EQ(topics.size(), 1u);
  EXPECT_EQ(topics[0].name, kTopic);
  EXPECT_EQ(topics[0].type, f.type);
  EXPECT_EQ(topics[0].encoding, f.encoding);
  EXPECT_EQ(topics[0].messages, kFrames);
}

TEST_P(DriveFixture, EveryMessageDecodesToItsBinFrameBitForBit) {
  const Fixture& f = GetParam();
  const std::string path = FixturePath(f);
  const ReadOut out = ReadAll(path, kTopic);
  ASSERT_EQ(out.error, "");
  ASSERT_EQ(out.problems, std::vector<std::string>{});
  ASSERT_EQ(out.messages.size(), kFrames);
  EXPECT_EQ(out.steps.back(), DriveStep::kEnd);
  for (size_t i = 0; i < kFrames; ++i) {
    const DriveMessage& m = out.messages[i];
    EXPECT_EQ(m.sequence, i);
    EXPECT_EQ(m.log_time_ns, kFirstStampNs + i * 100000000ull);
    EXPECT_EQ(m.topic, kTopic);
    EXPECT_EQ(m.encoding,
              f.container == Container::kBag ? MessageEncoding::kRos1 : MessageEncoding::kCdr);
    EXPECT_TRUE(IsFrame(path, m, i)) << path << " message " << i;
  }
}

TEST_P(DriveFixture, NextAfterTheEndStaysAtTheEnd) {
  std::unique_ptr<DriveReader> reader = OpenDrive(FixturePath(GetParam()));
  reader->SelectTopic(kTopic);
  DriveMessage message;
  std::string problem;
  size_t messages = 0;
  while (reader->Next(&message, &problem) == DriveStep::kMessage) ++messages;
  EXPECT_EQ(messages, kFrames);
  EXPECT_EQ(reader->Next(&message, &problem), DriveStep::kEnd);
}

TEST_P(DriveFixture, SelectingTheTopicAgainStartsFromTheFirstMessage) {
  const std::string path = FixturePath(GetParam());
  std::unique_ptr<DriveReader> reader = OpenDrive(path);
  reader->SelectTopic(kTopic);
  DriveMessage message;
  std::string problem;
  ASSERT_EQ(reader->Next(&message, &problem), DriveStep::kMessage);
  ASSERT_EQ(reader->Next(&message, &problem), DriveStep::kMessage);
  reader->SelectTopic(kTopic);
  ASSERT_EQ(reader->Next(&message, &problem), DriveStep::kMessage);
  EXPECT_EQ(message.sequence, 0u);
  EXPECT_TRUE(IsFrame(path, message, 0));
}

TEST_P(DriveFixture, AnAbsentTopicIsAnIoErrorListingTheTopicsThereAre) {
  const std::string path = FixturePath(GetParam());
  std::unique_ptr<DriveReader> reader = OpenDrive(path);
  EXPECT_TRUE(test::ThrowsIoError([&] { reader->SelectTopic("/no_such_topic"); }, path,
                                  {"/no_such_topic", kTopic}));
}

// Cut in the middle of the last chunk's payload (MCAP, bag) or of the file (.db3): the messages
// before the cut come out whole, then the damage is reported, then the end.
TEST_P(DriveFixture, TruncatedMidChunkYieldsEveryMessageBeforeTheCutThenDamage) {
  const Fixture& f = GetParam();
  test::ScopedDir dir;
  size_t cut = 0;
  const std::string path = DamagedCopy(dir, f, [&](std::string* b) {
    if (f.container == Container::kDb3) {
      cut = b->size() / 2;
    } else {
      const std::vector<ChunkSpan> chunks = Chunks(f, *b);
      ASSERT_EQ(chunks.size(), kFrames) << "one message per chunk";
      cut = chunks.back().data + chunks.back().data_size / 2;
    }
    b->resize(cut);
  });
  const ReadOut out = ReadAll(path, kTopic);
  for (size_t i = 0; i < out.messages.size(); ++i)
    EXPECT_TRUE(IsFrame(path, out.messages[i], i)) << "message " << i << " of the cut file";
  if (f.container == Container::kDb3) {
    // SQLite pages, not chunks: what survives depends on where the cut falls, but the damage
    // must be reported, as a damage step or an IoError, naming the file.
    const std::string report = out.error + (out.problems.empty() ? "" : out.problems[0]);
    EXPECT_NE(report.find(path), std::string::npos)
        << "no report naming " << path << ": '" << report << "'";
    return;
  }
  ASSERT_EQ(out.error, "") << "cut at byte " << cut;
  ASSERT_EQ(out.messages.size(), kFrames - 1) << "cut at byte " << cut;
  ASSERT_EQ(out.steps.size(), kFrames + 1);
  EXPECT_EQ(out.steps[kFrames - 1], DriveStep::kDamage);
  EXPECT_EQ(out.steps[kFrames], DriveStep::kEnd);
  ASSERT_EQ(out.problems.size(), 1u);
  EXPECT_NE(out.problems[0].find(path), std::string::npos) << out.problems[0];
}

// A .db3 cut inside its last page (the third message's data ends there): the two messages
// before it come out whole, then the damage naming the file, then the end.
TEST(DriveDb3, ACutInItsLastPageYieldsTheMessagesBeforeIt) {
  const Fixture& f = kFixtures[3];
  ASSERT_EQ(f.container, Container::kDb3);
  test::ScopedDir dir;
  const std::string path = DamagedCopy(dir, f, [](std::string* b) { b->resize(b->size() - 2048); });
  const ReadOut out = ReadAll(path, kTopic);
  ASSERT_EQ(out.error, "");
  ASSERT_EQ(out.messages.size(), kFrames - 1);
  for (size_t i = 0; i < out.messages.size(); ++i) EXPECT_TRUE(IsFrame(path, out.messages[i], i));
  ASSERT_EQ(out.steps.size(), kFrames + 1);
  EXPECT_EQ(out.steps[kFrames - 1], DriveStep::kDamage);
  EXPECT_EQ(out.steps[kFrames], DriveStep::kEnd);
  ASSERT_EQ(out.problems.size(), 1u);
  EXPECT_NE(out.problems[0].find(path), std::string::npos) << out.problems[0];
}

// A byte flipped in the middle of the second chunk's payload. Uncompressed, only the chunk's CRC
// can tell, so the report names it; compressed, the decompressor or the CRC does. MCAP's chunk
// index leads the reader on to the third chunk.
using McapDrive = DriveFixture;  // the MCAP fixtures: their chunks carry a CRC

TEST_P(McapDrive, AFlippedByteInAChunkIsDamageAndTheReadGoesOnPastIt) {
  const Fixture& f = GetParam();
  test::ScopedDir dir;
  const std::string path = SecondChunkFlipped(dir, f);
  const ReadOut out = ReadAll(path, kTopic);
  ASSERT_EQ(out.error, "");
  ASSERT_EQ(out.steps.size(), 4u);
  EXPECT_EQ(out.steps[0], DriveStep::kMessage);
  EXPECT_EQ(out.steps[1], DriveStep::kDamage);
  EXPECT_EQ(out.steps[2], DriveStep::kMessage);
  EXPECT_EQ(out.steps[3], DriveStep::kEnd);
  ASSERT_EQ(out.messages.size(), 2u);
  EXPECT_TRUE(IsFrame(path, out.messages[0], 0));
  EXPECT_TRUE(IsFrame(path, out.messages[1], 2));
  ASSERT_EQ(out.problems.size(), 1u);
  EXPECT_NE(out.problems[0].find(path), std::string::npos) << out.problems[0];
  if (std::string(f.compression).empty()) {
    EXPECT_NE(Lower(out.problems[0]).find("crc"), std::string::npos) << out.problems[0];
  }
}

// The same flip in a bz2 bag chunk: bzip2's own block CRC catches it (ROS 1 chunks carry none),
// so the chunk is damage; frame 0 comes out before it, and anything after it is frame 2.
TEST(DriveBag, AFlippedByteInABz2ChunkIsDamage) {
  const Fixture& f = kFixtures[4];
  ASSERT_EQ(std::string(f.compression), "bz2");
  test::ScopedDir dir;
  const std::string path = SecondChunkFlipped(dir, f);
  const ReadOut out = ReadAll(path, kTopic);
  ASSERT_EQ(out.error, "");
  ASSERT_GE(out.steps.size(), 3u);
  EXPECT_EQ(out.steps[0], DriveStep::kMessage);
  EXPECT_EQ(out.steps[1], DriveStep::kDamage);
  EXPECT_EQ(out.steps.back(), DriveStep::kEnd);
  ASSERT_GE(out.messages.size(), 1u);
  ASSERT_LE(out.messages.size(), 2u);
  EXPECT_TRUE(IsFrame(path, out.messages[0], 0));
  if (out.messages.size() == 2) {
    EXPECT_TRUE(IsFrame(path, out.messages[1], 2));
  }
  ASSERT_EQ(out.problems.size(), 1u);
  EXPECT_NE(out.problems[0].find(path), std::string::npos) << out.problems[0];
}

// The second chunk's compression renamed to one no reader knows (same length, so every offset
// holds): damage naming the compression, or an IoError doing so; frame 0 comes out before it.
using CompressedDrive = DriveFixture;  // the fixtures whose chunks name a compression

TEST_P(CompressedDrive, AnUnknownCompressionIsDamageNamingIt) {
  const Fixture& f = GetParam();
  test::ScopedDir dir;
  std::string unknown;
  const std::string path = DamagedCopy(dir, f, [&](std::string* b) {
    const std::vector<ChunkSpan> chunks = Chunks(f, *b);
    ASSERT_EQ(chunks.size(), kFrames);
    ASSERT_EQ(b->substr(chunks[1].compression, chunks[1].compression_size), f.compression);
    unknown = std::string(chunks[1].compression_size, 'q');
    b->replace(chunks[1].compression, chunks[1].compression_size, unknown);
  });
  const ReadOut out = ReadAll(path, kTopic);
  const std::string report = out.error + (out.problems.empty() ? "" : out.problems[0]);
  EXPECT_NE(report.find(path), std::string::npos) << "'" << report << "'";
  EXPECT_NE(report.find(unknown), std::string::npos) << "'" << report << "'";
  ASSERT_GE(out.messages.size(), 1u);
  EXPECT_TRUE(IsFrame(path, out.messages[0], 0));
  EXPECT_FALSE(out.problems.empty() && out.error.empty()) << "the damage went unreported";
}

INSTANTIATE_TEST_SUITE_P(Fixtures, DriveFixture, ::testing::ValuesIn(kFixtures), FixtureName);
INSTANTIATE_TEST_SUITE_P(Fixtures, McapDrive,
                         ::testing::Values(kFixtures[0], kFixtures[1], kFixtures[2]), FixtureName);
INSTANTIATE_TEST_SUITE_P(Fixtures, CompressedDrive,
                         ::testing::Values(kFixtures[0], kFixtures[1], kFixtures[4], kFixtures[5]),
                         FixtureName);

}  // namespace
}  // namespace lpir
