// lpir-gseg topics and segment on recorded drives, run as a user would, on the fixtures that
// independent writers made (tests/data/drives/, README there): every message labelled as
// `segment` labels the same frame given as a file, byte for byte; index.csv; damaged copies
// (cut mid-chunk, a flipped byte) labelling every readable message, naming the damage and
// exiting 1; a message without x written here with our MCAP writer. --format mcap|bag:
// cli_drive_output_test.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

#include "host/drive/drive.h"
#include "host/drive/mcap_writer.h"
#include "host/drive/pointcloud2.h"
#include "host/io/label_file.h"
#include "host/io/pcd.h"
#include "tests/drive_fixtures.h"
#include "tests/io_test_helpers.h"
#include "tests/test_util.h"

namespace fs = std::filesystem;

namespace lpir {
namespace {

const char kTopic[] = "/velodyne_points";
constexpr long long kFirstStampNs = 1600000000LL * 1000000000LL;  // then 100 ms apart
constexpr size_t kFrames = 3;

std::string Cli() { return test::CliPath(); }

long long StampNs(size_t frame) { return kFirstStampNs + (long long)frame * 100000000LL; }

// "<sequence %06>_<stamp ns>.label": segment's name for a drive's message.
std::string LabelName(size_t sequence, size_t frame) {
  char name[64];
  std::snprintf(name, sizeof(name), "%06zu_%lld.label", sequence, StampNs(frame));
  return name;
}

std::string Name(size_t i) {
  char name[16];
  std::snprintf(name, sizeof(name), "%06zu", i);
  return name;
}

std::string FrameBase(size_t i) { return test::FixtureFrameBase(i); }

// `segment` of the fixture frames given as files, once per run: with their rings (PCD files
// written here, as the drives carry them) and as the committed .bin files (no ring).
struct Reference {
  test::ScopedDir dir;
  std::string sensor = "vlp16";
  Reference() {
    std::string args;
    for (size_t i = 0; i < kFrames; ++i) {
      char name[16];
      std::snprintf(name, sizeof(name), "/%06zu.pcd", i);
      WritePcd(dir.path + name, test::FixtureFrame(i), nullptr, true);
      args += " " + dir.path + name;
    }
    std::string log;
    EXPECT_EQ(test::RunCommand(Cli() + " segment" + args + " --sensor " + sensor +
                                   " --backend cpu --quiet --out " + dir.path + "/ring",
                               &log),
              0)
        << log;
    EXPECT_EQ(test::RunCommand(Cli() + " segment " + test::DrivesDir() + "/frames --sensor " +
                                   sensor + " --backend cpu --quiet --out " + dir.path + "/bin",
                               &log),
              0)
        << log;
    size_t ground = 0;
    for (size_t i = 0; i < kFrames; ++i)
      for (uint32_t l : ReadLabelFile(dir.path + "/ring/" + Name(i) + ".label")) ground += l;
    EXPECT_GT(ground, 100u) << "labels all 0 would make the comparisons empty";
  }
  // The .label bytes of frame i: with rings, or from the .bin file.
  std::string Ring(size_t i) const { return Label("/ring/", i); }
  std::string Bin(size_t i) const { return Label("/bin/", i); }
  std::string RingDir() const { return dir.path + "/ring"; }

 private:
  std::string Label(const char* sub, size_t i) const {
    char name[16];
    std::snprintf(name, sizeof(name), "%06zu.label", i);
    return test::ReadFileBytes(dir.path + sub + name);
  }
};

const Reference& Ref() {
  static const Reference* ref = new Reference;  // kept to the end of the run
  return *ref;
}

std::string Sensor() { return Ref().sensor; }

std::vector<std::string> Lines(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

std::vector<std::string> Split(const std::string& line, char sep) {
  std::vector<std::string> out(1);
  for (char c : line) {
    if (c == sep)
      out.emplace_back();
    else
      out.back() += c;
  }
  return out;
}

// The label file in `dir` of the message with frame i's stamp ("" when none): the sequence a
// reader gives a message after damage is its place among those yielded.
std::string LabelOfStamp(const std::string& dir, size_t frame) {
  const std::string suffix = "_" + std::to_string(StampNs(frame)) + ".label";
  for (const std::string& name : test::LabelFiles(dir))
    if (name.size() > suffix.size() &&
        name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0)
      return test::ReadFileBytes(dir + "/" + name);
  return "";
}

struct Kind {
  const char* file;
  bool mcap, bag;
};

const Kind kKinds[] = {
    {"vlp16_zstd.mcap", true, false}, {"vlp16_lz4.mcap", true, false},
    {"vlp16_none.mcap", true, false}, {"vlp16.db3", false, false},
    {"vlp16_bz2.bag", false, true},   {"vlp16_lz4.bag", false, true},
};

std::string DrivePath(const Kind& k) { return test::DrivesDir() + "/" + k.file; }

class CliDrive : public ::testing::TestWithParam<Kind> {
 protected:
  void SetUp() override {
    if (test::ReadRaw(DrivePath(GetParam())).empty())
      GTEST_FAIL() << "fixture " << DrivePath(GetParam()) << " is missing";
  }
};

TEST_P(CliDrive, LabelsEveryMessageAsSegmentLabelsTheSameFrameAsAFile) {
  test::ScopedDir out;
  std::string log;
  ASSERT_EQ(test::RunCommand(Cli() + " segment " + DrivePath(GetParam()) + " --sensor " + Sensor() +
                                 " --backend cpu --out " + out.path,
                             &log),
            0)
      << log;
  std::vector<std::string> expected_names;
  for (size_t i = 0; i < kFrames; ++i) {
    expected_names.push_back(LabelName(i, i));
    const std::string labels = test::ReadFileBytes(out.path + "/" + LabelName(i, i));
    ASSERT_FALSE(labels.empty()) << LabelName(i, i) << " missing; " << log;
    EXPECT_EQ(labels, Ref().Ring(i)) << "message " << i;
    EXPECT_EQ(labels.size(), test::FixtureFrame(i).size() * 4);
  }
  EXPECT_EQ(test::LabelFiles(out.path), expected_names);
  EXPECT_NE(log.find("progress: 3/3"), std::string::npos) << log;  // piped: plain lines
  EXPECT_NE(log.find("segmented 3 of 3 messages of /velodyne_points"), std::string::npos) << log;
}

TEST_P(CliDrive, IndexListsEveryMessage) {
  test::ScopedDir out;
  std::string log;
  ASSERT_EQ(
      test::RunCommand(Cli() + " segment " + DrivePath(GetParam()) + " --topic " + kTopic +
                           " --sensor " + Sensor() + " --backend cpu --quiet --out " + out.path,
                       &log),
      0)
      << log;
  const std::vector<std::string> lines = Lines(test::ReadFileBytes(out.path + "/index.csv"));
  ASSERT_EQ(lines.size(), kFrames + 1);
  EXPECT_EQ(lines[0], "sequence,stamp_ns,topic,points,ground_fraction,ms,file");
  for (size_t i = 0; i < kFrames; ++i) {
    const std::vector<std::string> f = Split(lines[i + 1], ',');
    ASSERT_EQ(f.size(), 7u) << lines[i + 1];
    EXPECT_EQ(f[0], std::to_string(i));
    EXPECT_EQ(f[1], std::to_string(StampNs(i)));
    EXPECT_EQ(f[2], kTopic);
    const size_t n = test::FixtureFrame(i).size();
    EXPECT_EQ(f[3], std::to_string(n));
    size_t ground = 0;
    for (uint32_t l : ReadLabelFile(out.path + "/" + LabelName(i, i), n)) ground += l;
    EXPECT_NEAR(std::stod(f[4]), double(ground) / double(n), 1e-6);
    EXPECT_GT(std::stod(f[5]), 0.0);
    EXPECT_EQ(f[6], LabelName(i, i));
  }
}

TEST_P(CliDrive, TopicsListsTheTopicItsTypeAndCount) {
  std::string log;
  ASSERT_EQ(test::RunCommand(Cli() + " topics " + DrivePath(GetParam()), &log), 0) << log;
  const std::vector<std::string> lines = Lines(log);
  ASSERT_EQ(lines.size(), 2u) << log;
  std::istringstream head(lines[0]), row(lines[1]);
  std::string a, b, c, d;
  head >> a >> b >> c >> d;
  EXPECT_EQ(a + " " + b + " " + c + " " + d, "topic type encoding messages");
  row >> a >> b >> c >> d;
  EXPECT_EQ(a, kTopic);
  EXPECT_EQ(b, GetParam().bag ? "sensor_msgs/PointCloud2" : "sensor_msgs/msg/PointCloud2");
  EXPECT_EQ(c, GetParam().bag ? "ros1" : "cdr");
  EXPECT_EQ(d, "3");
}

// index.csv's lines without the ms column (which differs from run to run).
std::vector<std::string> IndexRowsWithoutMs(const std::string& dir) {
  std::vector<std::string> rows;
  for (const std::string& line : Lines(test::ReadFileBytes(dir + "/index.csv"))) {
    std::vector<std::string> f = Split(line, ',');
    if (f.size() != 7u) return {"malformed: " + line};
    f.erase(f.begin() + 5);
    std::string row;
    for (const std::string& field : f) row += (row.empty() ? "" : ",") + field;
    rows.push_back(row);
  }
  return rows;
}

// `topics --chunks` counts the chunks; `segment --chunks A:B` runs over ranges that cover the
// drive write together the whole run's .label files, byte for byte, and its index rows (each
// range's header, then its rows; in sequence order the whole run's), several read threads or one.
TEST_P(CliDrive, ChunkRangesTogetherWriteTheWholeRun) {
  const std::string drive = DrivePath(GetParam());
  std::string log;
  ASSERT_EQ(test::RunCommand(Cli() + " topics " + drive + " --chunks", &log), 0) << log;
  const bool db3 = !GetParam().mcap && !GetParam().bag;
  EXPECT_EQ(log, db3 ? "0\n" : "3\n");
  const std::string common = " --sensor " + Sensor() + " --backend cpu --quiet --out ";
  test::ScopedDir whole;
  ASSERT_EQ(test::RunCommand(Cli() + " segment " + drive + common + whole.path, &log), 0) << log;
  if (db3) {
    EXPECT_EQ(
        test::RunCommand(Cli() + " segment " + drive + " --chunks 1:1" + common + whole.path, &log),
        4);
    EXPECT_NE(log.find("no chunks"), std::string::npos) << log;
    return;
  }
  const std::vector<std::string> names = test::LabelFiles(whole.path);
  ASSERT_EQ(names.size(), kFrames);
  const std::vector<std::string> rows = IndexRowsWithoutMs(whole.path);
  for (const char* threads : {"1", "3"}) {
    for (const std::vector<const char*>& ranges :
         std::vector<std::vector<const char*>>{{"1:1", "2:2", "3:3"}, {"1:2", "3:3"}}) {
      test::ScopedDir parts;
      std::vector<std::string> together = {rows[0]};
      for (const char* range : ranges) {
        const std::string out = parts.path + "/" + range;
        ASSERT_EQ(test::RunCommand(Cli() + " segment " + drive + " --chunks " + range +
                                       " --read-threads " + threads + common + out,
                                   &log),
                  0)
            << log;
        std::vector<std::string> part = IndexRowsWithoutMs(out);
        ASSERT_FALSE(part.empty());
        EXPECT_EQ(part[0], rows[0]);
        together.insert(together.end(), part.begin() + 1, part.end());
        for (const std::string& name : test::LabelFiles(out))
          EXPECT_EQ(test::ReadFileBytes(out + "/" + name),
                    test::ReadFileBytes(whole.path + "/" + name))
              << range << " " << name;
      }
      std::sort(
          together.begin() + 1, together.end(), [](const std::string& a, const std::string& b) {
            return std::stoull(a.substr(0, a.find(','))) < std::stoull(b.substr(0, b.find(',')));
          });
      EXPECT_EQ(together, rows) << threads << " threads";
      size_t files = 0;
      for (const char* range : ranges) files += test::LabelFiles(parts.path + "/" + range).size();
      EXPECT_EQ(files, kFrames);
    }
  }
  EXPECT_EQ(
      test::RunCommand(Cli() + " segment " + drive + " --chunks 2:4" + common + whole.path, &log),
      4);
  EXPECT_NE(log.find("has 3"), std::string::npos) << log;
  for (const char* bad : {"0:1", "2:1", "1", "a:b", "1:"}) {
    EXPECT_EQ(test::RunCommand(
                  Cli() + " segment " + drive + " --chunks " + bad + common + whole.path, &log),
              2)
        << bad;
    EXPECT_NE(log.find("--chunks must be A:B"), std::string::npos) << log;
  }
  for (const char* bad : {"0", "65", "1.5"}) {
    EXPECT_EQ(
        test::RunCommand(
            Cli() + " segment " + drive + " --read-threads " + bad + common + whole.path, &log),
        2)
        << bad;
    EXPECT_NE(log.find("--read-threads must be"), std::string::npos) << log;
  }
}

INSTANTIATE_TEST_SUITE_P(Fixtures, CliDrive, ::testing::ValuesIn(kKinds),
                         [](const ::testing::TestParamInfo<Kind>& info) {
                           std::string name = info.param.file;
                           for (char& c : name)
                             if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                           return name;
                         });

// ---- Damaged copies: the chunks found by walking the records here, not by the readers ----

uint64_t Le(const std::string& b, size_t at, int bytes) {
  uint64_t v = 0;
  for (int k = bytes - 1; k >= 0; --k) v = v << 8 | uint8_t(b[at + size_t(k)]);
  return v;
}

struct Span {
  size_t data = 0, size = 0;              // a chunk's (compressed) payload
  size_t compression = 0, name_size = 0;  // its compression's name
};

// MCAP: records after the 8-byte magic (opcode u8, length u64, body) up to the footer; a Chunk
// (0x06) body holds start, end, uncompressed size (u64 each), CRC u32, compression (u32 length +
// bytes), then the records' length u64 and bytes.
std::vector<Span> McapChunks(const std::string& b) {
  std::vector<Span> chunks;
  for (size_t at = 8; at + 9 <= b.size();) {
    const uint8_t op = uint8_t(b[at]);
    const uint64_t len = Le(b, at + 1, 8);
    const size_t body = at + 9;
    if (op == 0x02 || len > b.size() - body) break;
    if (op == 0x06) {
      const size_t name = body + 32, name_size = Le(b, body + 28, 4);
      chunks.push_back({name + name_size + 8, size_t(Le(b, name + name_size, 8)), name, name_size});
    }
    at = body + len;
  }
  return chunks;
}

// ROS 1 bag 2.0: records after "#ROSBAG V2.0\n" (header length u32, fields of u32 length +
// "name=value", data length u32, data); a chunk's header holds "op=\x05".
std::vector<Span> BagChunks(const std::string& b) {
  std::vector<Span> chunks;
  for (size_t at = 13; at + 4 <= b.size();) {
    const uint64_t header_len = Le(b, at, 4);
    if (header_len > b.size() - at - 4 || b.size() - at - 4 - header_len < 4) break;
    const size_t data_len_at = at + 4 + header_len;
    const uint64_t data_len = Le(b, data_len_at, 4);
    if (data_len > b.size() - data_len_at - 4) break;
    const std::string header = b.substr(at + 4, header_len);
    const size_t name = header.find("compression=");
    if (header.find(std::string("op=\x05", 4)) != std::string::npos && name >= 4) {
      const size_t field = size_t(Le(header, name - 4, 4));  // "compression=<name>"
      chunks.push_back({data_len_at + 4, size_t(data_len), at + 4 + name + 12, field - 12});
    }
    at = data_len_at + 4 + data_len;
  }
  return chunks;
}

// A copy of `kind` changed by `edit`, in `dir` under the fixture's name.
std::string DamagedCopy(const test::ScopedDir& dir, const Kind& kind,
                        const std::function<void(std::string*, const std::vector<Span>&)>& edit) {
  std::string bytes = test::ReadRaw(DrivePath(kind));
  edit(&bytes, kind.mcap ? McapChunks(bytes) : BagChunks(bytes));
  const std::string path = dir.path + "/" + kind.file;
  test::WriteRaw(path, bytes);
  return path;
}

class CliDamagedDrive : public ::testing::TestWithParam<Kind> {};

TEST_P(CliDamagedDrive, CutMidChunkLabelsEveryMessageBeforeItNamesItAndExits1) {
  test::ScopedDir dir;
  const std::string path = DamagedCopy(dir, GetParam(), [](std::string* b, const auto& chunks) {
    ASSERT_EQ(chunks.size(), kFrames) << "one message per chunk";
    b->resize(chunks.back().data + chunks.back().size / 2);
  });
  std::string log;
  EXPECT_EQ(test::RunCommand(Cli() + " segment " + path + " --sensor " + Sensor() +
                                 " --backend cpu --out " + dir.path + "/out",
                             &log),
            1)
      << log;
  for (size_t i = 0; i + 1 < kFrames; ++i)
    EXPECT_EQ(test::ReadFileBytes(dir.path + "/out/" + LabelName(i, i)), Ref().Ring(i))
        << "message " << i << "; " << log;
  EXPECT_EQ(test::LabelFiles(dir.path + "/out").size(), kFrames - 1) << log;
  EXPECT_NE(log.find("lpir-gseg segment: error: " + path), std::string::npos) << log;
  EXPECT_EQ(Lines(test::ReadFileBytes(dir.path + "/out/index.csv")).size(), kFrames) << log;
}

TEST_P(CliDamagedDrive, AnUnknownCompressionLabelsTheOtherMessagesNamesItAndExits1) {
  std::string unknown;
  test::ScopedDir dir;
  const std::string path =
      DamagedCopy(dir, GetParam(), [&](std::string* b, const std::vector<Span>& chunks) {
        ASSERT_EQ(chunks.size(), kFrames);
        unknown.assign(chunks[1].name_size, 'q');  // same length: every offset holds
        b->replace(chunks[1].compression, chunks[1].name_size, unknown);
      });
  if (unknown.empty()) GTEST_SKIP() << "uncompressed: no name to change";
  std::string log;
  EXPECT_EQ(test::RunCommand(Cli() + " segment " + path + " --sensor " + Sensor() +
                                 " --backend cpu --out " + dir.path + "/out",
                             &log),
            1)
      << log;
  EXPECT_EQ(test::ReadFileBytes(dir.path + "/out/" + LabelName(0, 0)), Ref().Ring(0)) << log;
  EXPECT_EQ(LabelOfStamp(dir.path + "/out", 1), "") << log;
  EXPECT_EQ(LabelOfStamp(dir.path + "/out", 2), Ref().Ring(2)) << "read on past it; " << log;
  EXPECT_NE(log.find("lpir-gseg segment: error: " + path), std::string::npos) << log;
  EXPECT_NE(log.find(unknown), std::string::npos) << log;
}

// A .db3 cut inside its last page: its message counts cannot be taken, so the topic must be
// named; the two messages before the cut are labelled, the damage named, exit 1.
TEST(CliDamagedDb3, CutInItsLastPageLabelsTheMessagesBeforeItWhenTheTopicIsNamed) {
  test::ScopedDir dir;
  const std::string path = dir.path + "/vlp16.db3";
  const std::string bytes = test::ReadRaw(test::DrivesDir() + "/vlp16.db3");
  ASSERT_GT(bytes.size(), 2048u);
  test::WriteRaw(path, bytes.substr(0, bytes.size() - 2048));
  const std::string segment =
      Cli() + " segment " + path + " --sensor " + Sensor() + " --backend cpu --out " + dir.path;
  std::string log;
  EXPECT_EQ(test::RunCommand(segment + "/a", &log), 4) << log;
  EXPECT_NE(log.find("--topic T reads T's messages up to the damage"), std::string::npos) << log;
  EXPECT_EQ(test::RunCommand(segment + "/b --topic " + kTopic, &log), 1) << log;
  for (size_t i = 0; i + 1 < kFrames; ++i)
    EXPECT_EQ(test::ReadFileBytes(dir.path + "/b/" + LabelName(i, i)), Ref().Ring(i)) << log;
  EXPECT_EQ(test::LabelFiles(dir.path + "/b").size(), kFrames - 1) << log;
  EXPECT_NE(log.find("lpir-gseg segment: error: " + path), std::string::npos) << log;
  EXPECT_NE(log.find("segmented 2 messages of /velodyne_points"), std::string::npos) << log;
}

// MCAP only: its chunks carry a CRC (a bag's bz2 or lz4 chunk may decompress a flipped byte).
class CliFlippedDrive : public ::testing::TestWithParam<Kind> {};

TEST_P(CliFlippedDrive, AFlippedByteLabelsTheOtherMessagesNamesItAndExits1) {
  test::ScopedDir dir;
  const std::string path = DamagedCopy(dir, GetParam(), [](std::string* b, const auto& chunks) {
    ASSERT_EQ(chunks.size(), kFrames);
    (*b)[chunks[1].data + chunks[1].size / 2] ^= 0x10;
  });
  std::string log;
  EXPECT_EQ(test::RunCommand(Cli() + " segment " + path + " --sensor " + Sensor() +
                                 " --backend cpu --out " + dir.path + "/out --report " + dir.path +
                                 "/r.csv",
                             &log),
            1)
      << log;
  EXPECT_EQ(test::ReadFileBytes(dir.path + "/out/" + LabelName(0, 0)), Ref().Ring(0)) << log;
  EXPECT_EQ(LabelOfStamp(dir.path + "/out", 2), Ref().Ring(2)) << log;
  EXPECT_EQ(LabelOfStamp(dir.path + "/out", 1), "") << log;
  EXPECT_EQ(test::LabelFiles(dir.path + "/out").size(), 2u) << log;
  EXPECT_NE(log.find("lpir-gseg segment: error: " + path), std::string::npos) << log;
  // the report: the two frames and the damage, in that order, the damage with its error
  const std::vector<std::string> rows = Lines(test::ReadFileBytes(dir.path + "/r.csv"));
  ASSERT_EQ(rows.size(), 4u);
  EXPECT_EQ(rows[1].back(), ',');                       // no error
  EXPECT_NE(rows[2].find(path, 1), std::string::npos);  // the error names the copy
  EXPECT_EQ(rows[3].back(), ',');
}

std::string KindName(const ::testing::TestParamInfo<Kind>& info) {
  std::string name = info.param.file;
  for (char& c : name)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return name;
}

INSTANTIATE_TEST_SUITE_P(Fixtures, CliDamagedDrive,
                         ::testing::Values(kKinds[0], kKinds[1], kKinds[2], kKinds[4], kKinds[5]),
                         KindName);
INSTANTIATE_TEST_SUITE_P(Fixtures, CliFlippedDrive,
                         ::testing::Values(kKinds[0], kKinds[1], kKinds[2]), KindName);

// A CDR PointCloud2 of `cloud`: fields x y z intensity float32 (the first named `x_name`).
std::vector<uint8_t> CdrCloud(const Cloud& cloud, long long stamp_ns, const std::string& x_name) {
  PointCloud2 m;
  m.stamp_sec = int32_t(stamp_ns / 1000000000LL);
  m.stamp_nanosec = uint32_t(stamp_ns % 1000000000LL);
  m.frame_id = "velodyne";
  m.width = uint32_t(cloud.size());
  m.fields = {{x_name, 0, kPfFloat32, 1},
              {"y", 4, kPfFloat32, 1},
              {"z", 8, kPfFloat32, 1},
              {"intensity", 12, kPfFloat32, 1}};
  m.point_step = 16;
  m.row_step = 16 * m.width;
  m.data.resize(cloud.xyzi.size() * 4);
  std::memcpy(m.data.data(), cloud.xyzi.data(), m.data.size());
  m.is_dense = true;
  return SerializeCdrPointCloud2(m);
}

Cloud BinFrame(size_t i) {
  const std::string bin = test::ReadRaw(FrameBase(i) + ".bin");
  Cloud cloud;
  cloud.xyzi.resize(bin.size() / 4);
  std::memcpy(cloud.xyzi.data(), bin.data(), cloud.xyzi.size() * 4);
  return cloud;
}

TEST(CliDriveMessages, AMessageWithoutXIsNamedAndTheOthersLabelledAsTheBinFiles) {
  test::ScopedDir dir;
  const std::string path = dir.path + "/no_x.mcap";
  {
    McapWriter w(path, McapCompression::kZstd);
    const uint16_t schema =
        w.AddSchema("sensor_msgs/msg/PointCloud2", "ros2msg", PointCloud2Ros2MsgDefinition());
    const uint16_t channel = w.AddChannel("/points", schema, "cdr");
    for (size_t i = 0; i < kFrames; ++i) {
      const std::vector<uint8_t> m = CdrCloud(BinFrame(i), StampNs(i), i == 1 ? "q" : "x");
      w.Write(channel, uint32_t(i), uint64_t(StampNs(i)), uint64_t(StampNs(i)), m.data(), m.size());
    }
    w.Close();
  }
  std::string log;
  EXPECT_EQ(test::RunCommand(Cli() + " segment " + path + " --sensor " + Sensor() +
                                 " --backend cpu --out " + dir.path + "/out --report " + dir.path +
                                 "/r.json",
                             &log),
            1)
      << log;
  EXPECT_EQ(test::ReadFileBytes(dir.path + "/out/" + LabelName(0, 0)), Ref().Bin(0)) << log;
  EXPECT_EQ(test::ReadFileBytes(dir.path + "/out/" + LabelName(2, 2)), Ref().Bin(2)) << log;
  EXPECT_EQ(test::LabelFiles(dir.path + "/out").size(), 2u) << log;
  EXPECT_NE(log.find("lpir-gseg segment: error: " + path + ": /points message 1"),
            std::string::npos)
      << log;
  EXPECT_NE(log.find("'x'"), std::string::npos) << log;
  EXPECT_NE(log.find(path + ": 1 problem (damaged parts"), std::string::npos) << log;
  LPIR_REQUIRE_PYTHON_JSON();
  const std::string script =
      "import json,sys\n"
      "for f in json.load(open(sys.argv[1]))['frames']:\n"
      "  print(f['sequence'],f['stamp_ns'],f['topic'],f['points']>0,f['error'] is None)\n";
  std::ofstream(dir.path + "/check.py") << script;
  std::string parsed;
  ASSERT_EQ(test::RunCommand("python3 " + dir.path + "/check.py " + dir.path + "/r.json", &parsed),
            0)
      << parsed;
  EXPECT_EQ(parsed, "0 " + std::to_string(StampNs(0)) + " /points True True\n" + "1 " +
                        std::to_string(StampNs(1)) + " /points False False\n" + "2 " +
                        std::to_string(StampNs(2)) + " /points True True\n");
}

TEST(CliDriveArgs, McapOutputNeedsDrivesOnly) {
  test::ScopedDir dir;
  std::string log;
  for (const std::string& inputs :
       {FrameBase(0) + ".bin", test::DrivesDir() + "/vlp16.db3 " + FrameBase(0) + ".bin"}) {
    EXPECT_EQ(
        test::RunCommand(
            Cli() + " segment " + inputs + " --format mcap --sensor vlp16 --out " + dir.path, &log),
        2);
    EXPECT_NE(log.find("--format mcap is for recorded drives"), std::string::npos) << log;
    EXPECT_NE(log.find(FrameBase(0) + ".bin"), std::string::npos) << log;
  }
}

TEST(CliDriveArgs, FormatMcapNeverWritesOverTheDriveItReads) {
  test::ScopedDir dir;
  const std::string drive = dir.path + "/vlp16_zstd.mcap";
  test::WriteRaw(drive, test::ReadRaw(test::DrivesDir() + "/vlp16_zstd.mcap"));
  std::string log;
  EXPECT_EQ(test::RunCommand(Cli() + " segment " + drive + " --sensor " + Sensor() +
                                 " --backend cpu --format mcap --out " + dir.path,
                             &log),
            2);
  EXPECT_NE(log.find("is the drive being read"), std::string::npos) << log;
  EXPECT_EQ(test::ReadRaw(drive), test::ReadRaw(test::DrivesDir() + "/vlp16_zstd.mcap"));
}

TEST(CliDriveArgs, AnAbsentTopicIsNamedWithTheTopicsThereAre) {
  test::ScopedDir dir;
  std::string log;
  EXPECT_EQ(test::RunCommand(Cli() + " segment " + test::DrivesDir() +
                                 "/vlp16.db3 --topic /nope --sensor vlp16 --out " + dir.path,
                             &log),
            2);
  EXPECT_NE(log.find("/nope"), std::string::npos) << log;
  EXPECT_NE(log.find(kTopic), std::string::npos) << log;
}

TEST(CliDriveArgs, TopicsOfAMissingDriveIsAnErrorNamingIt) {
  std::string log;
  EXPECT_EQ(test::RunCommand(Cli() + " topics /nonexistent/drive.mcap", &log), 4);  // cannot run
  EXPECT_NE(log.find("/nonexistent/drive.mcap"), std::string::npos) << log;
  EXPECT_EQ(test::RunCommand(Cli() + " topics", &log), 2);
  EXPECT_NE(log.find("usage: lpir-gseg topics DRIVE"), std::string::npos) << log;
}

}  // namespace
}  // namespace lpir
