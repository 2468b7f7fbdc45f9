// lpir-gseg segment DRIVE --format mcap|bag, run as a user would, on the fixtures independent
// writers made (tests/data/drives/, README there; the vlp16_full drives hold an IMU's and a GNSS
// receiver's topics beside the lidar, the MCAP also a metadata record and an attachment): the
// output holds every record of the input as it was (read back through our readers here, and
// through @mcap/core and python3-rosbag when they are installed: tools/drive_fixtures/read_mcap.mjs
// and read_bag.py), plus the labelled, ground and non-ground clouds with every field aligned, the
// ground cloud's points exactly the input's points labelled 1.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <map>
#include <string>
#include <variant>
#include <vector>

#include "host/drive/drive.h"
#include "host/drive/drive_content.h"
#include "host/drive/pointcloud2.h"
#include "tests/drive_fixtures.h"
#include "tests/io_test_helpers.h"
#include "tests/test_util.h"

namespace fs = std::filesystem;

namespace lpir {
namespace {

const char kTopic[] = "/velodyne_points";
constexpr size_t kFrames = 3;
const char* const kClouds[3] = {"/labelled", "/ground", "/nonground"};

std::string Segment(const std::string& drive, const std::string& format, const std::string& out,
                    std::string* log) {
  return std::to_string(test::RunCommand(test::CliPath() + " segment " + drive +
                                             " --sensor vlp16 --backend cpu --quiet --format " +
                                             format + " --out " + out,
                                         log));
}

// A drive's whole content through DriveContent: per topic its channel, schema and messages, and
// the metadata and attachment records; every damage it reported.
struct Content {
  std::string profile;
  struct Topic {
    DriveChannel channel;
    DriveSchema schema;  // id 0: none
    std::vector<DriveRecordMessage> messages;
  };
  std::map<std::string, Topic> topics;
  std::vector<DriveMetadata> metadata;
  std::vector<DriveAttachment> attachments;
  std::vector<std::string> damage;
};

Content ReadContent(const std::string& path) {
  Content out;
  auto content = OpenDriveContent(path);
  out.profile = content->profile();
  std::map<uint16_t, DriveSchema> schemas;
  std::map<uint16_t, std::string> topic_of;
  DriveRecord record;
  std::string problem;
  for (ContentStep step; (step = content->Next(&record, &problem)) != ContentStep::kEnd;) {
    if (step == ContentStep::kDamage) {
      out.damage.push_back(problem);
    } else if (const auto* s = std::get_if<DriveSchema>(&record)) {
      schemas[s->id] = *s;
    } else if (const auto* c = std::get_if<DriveChannel>(&record)) {
      Content::Topic& t = out.topics[c->topic];
      EXPECT_EQ(t.channel.topic, "") << path << ": a second channel on " << c->topic;
      t.channel = *c;
      if (schemas.count(c->schema_id)) t.schema = schemas[c->schema_id];
      topic_of[c->id] = c->topic;
    } else if (const auto* m = std::get_if<DriveRecordMessage>(&record)) {
      out.topics[topic_of.at(m->channel_id)].messages.push_back(*m);
    } else if (const auto* d = std::get_if<DriveMetadata>(&record)) {
      out.metadata.push_back(*d);
    } else {
      out.attachments.push_back(std::get<DriveAttachment>(record));
    }
  }
  return out;
}

// Every topic of `in` is in `out` with the same channel (encoding, metadata), schema (name,
// encoding, data) and messages (sequence, times, bytes) in order; and its metadata and
// attachment records.
void ExpectHoldsEveryRecordOf(const Content& out, const Content& in) {
  EXPECT_EQ(out.profile, in.profile);
  for (const auto& [name, want] : in.topics) {
    SCOPED_TRACE(name);
    ASSERT_TRUE(out.topics.count(name));
    const Content::Topic& got = out.topics.at(name);
    EXPECT_EQ(got.channel.message_encoding, want.channel.message_encoding);
    EXPECT_EQ(got.channel.metadata, want.channel.metadata);
    EXPECT_EQ(got.schema.name, want.schema.name);
    EXPECT_EQ(got.schema.encoding, want.schema.encoding);
    EXPECT_EQ(got.schema.data, want.schema.data);
    ASSERT_EQ(got.messages.size(), want.messages.size());
    for (size_t k = 0; k < want.messages.size(); ++k) {
      EXPECT_EQ(got.messages[k].sequence, want.messages[k].sequence) << k;
      EXPECT_EQ(got.messages[k].log_time_ns, want.messages[k].log_time_ns) << k;
      EXPECT_EQ(got.messages[k].publish_time_ns, want.messages[k].publish_time_ns) << k;
      EXPECT_EQ(got.messages[k].data, want.messages[k].data) << k;
    }
  }
  ASSERT_EQ(out.metadata.size(), in.metadata.size());
  for (size_t k = 0; k < in.metadata.size(); ++k) {
    EXPECT_EQ(out.metadata[k].name, in.metadata[k].name);
    EXPECT_EQ(out.metadata[k].entries, in.metadata[k].entries);
  }
  ASSERT_EQ(out.attachments.size(), in.attachments.size());
  for (size_t k = 0; k < in.attachments.size(); ++k) {
    const DriveAttachment &a = out.attachments[k], &b = in.attachments[k];
    EXPECT_EQ(a.name, b.name);
    EXPECT_EQ(a.media_type, b.media_type);
    EXPECT_EQ(a.log_time_ns, b.log_time_ns);
    EXPECT_EQ(a.create_time_ns, b.create_time_ns);
    EXPECT_EQ(a.data, b.data);
  }
}

PointCloud2 Parse(const Content::Topic& t, size_t k) {
  const std::vector<uint8_t>& d = t.messages.at(k).data;
  return t.channel.message_encoding == "ros1" ? ParseRos1PointCloud2("out", d.data(), d.size())
                                              : ParseCdrPointCloud2("out", d.data(), d.size());
}

size_t FieldSize(uint8_t datatype) {
  return datatype <= kPfUint8 ? 1 : datatype <= kPfUint16 ? 2 : datatype <= kPfFloat32 ? 4 : 8;
}

// The point_step % 4 == 0 and offset % size == 0 of every field; rows packed.
::testing::AssertionResult Aligned(const PointCloud2& c) {
  if (c.point_step % 4 != 0) return ::testing::AssertionFailure() << "point_step " << c.point_step;
  for (const PointField& f : c.fields)
    if (f.offset % FieldSize(f.datatype) != 0 || c.point_step % FieldSize(f.datatype) != 0)
      return ::testing::AssertionFailure() << f.name << " at " << f.offset;
  if (c.row_step != c.width * c.point_step || c.data.size() != size_t(c.row_step) * c.height)
    return ::testing::AssertionFailure() << "rows not packed";
  return ::testing::AssertionSuccess();
}

// Point i of a decoded cloud, all four floats and the ring.
Cloud Points(const Cloud& c, const std::vector<size_t>& which) {
  Cloud out;
  for (size_t i : which) {
    out.xyzi.insert(out.xyzi.end(), c.xyzi.begin() + 4 * i, c.xyzi.begin() + 4 * i + 4);
    if (!c.ring.empty()) out.ring.push_back(c.ring[i]);
  }
  return out;
}

// T/labelled, T/ground and T/nonground in `out`: 3 messages each after T's, headers and log
// times as T's, fields aligned, the labels those of `label_dir` (segment's .label files of the
// same drive), ground and non-ground the points labelled 1 and 0, each message with more than
// `min_ground` points labelled 1.
void ExpectTheThreeClouds(const Content& out, const std::string& label_dir, size_t frames = kFrames,
                          size_t min_ground = 100) {
  const Content::Topic& source = out.topics.at(kTopic);
  const std::vector<std::string> label_files = test::LabelFiles(label_dir);
  ASSERT_EQ(label_files.size(), frames);
  for (const char* suffix : kClouds) {
    SCOPED_TRACE(suffix);
    ASSERT_TRUE(out.topics.count(std::string(kTopic) + suffix));
    const Content::Topic& t = out.topics.at(std::string(kTopic) + suffix);
    EXPECT_EQ(t.schema.name, source.schema.name);
    EXPECT_EQ(t.schema.data, source.schema.data);
    EXPECT_EQ(t.channel.message_encoding, source.channel.message_encoding);
    ASSERT_EQ(t.messages.size(), frames);
  }
  for (size_t k = 0; k < frames; ++k) {
    SCOPED_TRACE(k);
    const PointCloud2 in = Parse(source, k);
    const Cloud points = CloudFromPointCloud2("in", in);
    const PointCloud2 labelled = Parse(out.topics.at(std::string(kTopic) + "/labelled"), k);
    const PointCloud2 ground = Parse(out.topics.at(std::string(kTopic) + "/ground"), k);
    const PointCloud2 nonground = Parse(out.topics.at(std::string(kTopic) + "/nonground"), k);
    for (const PointCloud2* c : {&labelled, &ground, &nonground}) {
      EXPECT_TRUE(Aligned(*c));
      EXPECT_EQ(c->stamp_ns(), in.stamp_ns());
      EXPECT_EQ(c->frame_id, in.frame_id);
      EXPECT_EQ(c->seq, in.seq);
    }
    for (const char* suffix : kClouds)
      EXPECT_EQ(out.topics.at(std::string(kTopic) + suffix).messages[k].log_time_ns,
                source.messages[k].log_time_ns);
    ASSERT_EQ(labelled.fields.back().name, "label");
    EXPECT_EQ(labelled.fields.back().datatype, kPfUint32);
    const PointField& label = labelled.fields.back();
    std::string labels;  // as a .label file: uint32 little-endian per point
    std::vector<size_t> ones, zeros;
    for (size_t i = 0; i < points.size(); ++i) {
      const uint8_t* at = labelled.data.data() + i * labelled.point_step + label.offset;
      labels.append(reinterpret_cast<const char*>(at), 4);
      (at[0] == 1 ? ones : zeros).push_back(i);
    }
    EXPECT_EQ(labels, test::ReadFileBytes(label_dir + "/" + label_files[k]));
    EXPECT_GT(ones.size(), min_ground);
    EXPECT_TRUE(test::SameBits(CloudFromPointCloud2("labelled", labelled), points));
    EXPECT_TRUE(test::SameBits(CloudFromPointCloud2("ground", ground), Points(points, ones)));
    EXPECT_TRUE(
        test::SameBits(CloudFromPointCloud2("nonground", nonground), Points(points, zeros)));
  }
}

struct Case {
  const char* drive;
  const char* format;   // mcap or bag
  const char* profile;  // of the output
};

const Case kCases[] = {
    {"vlp16_full.mcap", "mcap", "ros2"}, {"vlp16_full.db3", "mcap", "ros2"},
    {"vlp16_full.bag", "mcap", "ros1"},  {"vlp16_full.bag", "bag", "ros1"},
    {"vlp16_zstd.mcap", "mcap", "ros2"}, {"vlp16_bz2.bag", "bag", "ros1"},
};

class CliDriveOutput : public ::testing::TestWithParam<Case> {
 protected:
  std::string Input() const { return test::DrivesDir() + "/" + GetParam().drive; }
  // segment's output of the drive, and its .label files of the same drive in dir_/labels.
  std::string Output() {
    std::string log;
    EXPECT_EQ(Segment(Input(), GetParam().format, dir_.path + "/out", &log), "0") << log;
    EXPECT_EQ(Segment(Input(), "label", dir_.path + "/labels", &log), "0") << log;
    return dir_.path + "/out/" + fs::path(Input()).stem().string() + "." + GetParam().format;
  }
  std::string Labels() const { return dir_.path + "/labels"; }

  test::ScopedDir dir_;
};

TEST_P(CliDriveOutput, HoldsEveryRecordOfTheDriveAndTheThreeCloudsThroughOurReaders) {
  const std::string path = Output();
  const Content out = ReadContent(path);
  const Content in = ReadContent(Input());
  EXPECT_EQ(out.damage, std::vector<std::string>{});
  EXPECT_EQ(in.damage, std::vector<std::string>{});
  EXPECT_EQ(out.profile, GetParam().profile);
  // What the writers put in, counted from their scripts (extras.mjs), not from our reader.
  const bool full = std::string(GetParam().drive).find("full") != std::string::npos;
  EXPECT_EQ(in.topics.size(), full ? 3u : 1u);
  EXPECT_EQ(in.topics.at(kTopic).messages.size(), kFrames);
  if (full) {
    EXPECT_EQ(in.topics.at("/imu/data").messages.size(), 30u);
    EXPECT_EQ(in.topics.at("/gps/fix").messages.size(), kFrames);
  }
  const bool mcap_input = fs::path(Input()).extension() == ".mcap";
  EXPECT_EQ(in.metadata.size(), full && mcap_input ? 1u : 0u);
  EXPECT_EQ(in.attachments.size(), full && mcap_input ? 1u : 0u);
  ExpectHoldsEveryRecordOf(out, in);
  EXPECT_EQ(out.topics.size(), in.topics.size() + 3);
  ExpectTheThreeClouds(out, Labels());
  // The topic reader sees the output as a drive: the clouds' topics with their counts.
  for (const DriveTopic& t : OpenDrive(path)->Topics())
    EXPECT_EQ(t.messages, out.topics.at(t.name).messages.size()) << t.name;
}

TEST_P(CliDriveOutput, IndependentReadersFindEveryRecordAndTheThreeClouds) {
  const std::string tools =
      test::EnvOr("LPIR_DRIVE_TOOLS", (test::SensorsDir() + "/../tools/drive_fixtures").c_str());
  const bool bag = std::string(GetParam().format) == "bag";
  if (bag && test::RunCommand("/usr/bin/python3 -c 'import rosbag, sensor_msgs.msg'") != 0)
    GTEST_SKIP() << "/usr/bin/python3 without python3-rosbag (scripts/install_deps.sh)";
  if (!bag && (test::RunCommand("node --version") != 0 ||
               !fs::exists(tools + "/node_modules/@foxglove/rosmsg-serialization")))
    GTEST_SKIP() << "node or " << tools << "/node_modules absent (npm ci there)";
  const std::string path = Output();
  // The input itself when the reader reads its format, else the counts it must hold.
  std::string against;
  const std::string ext = fs::path(Input()).extension().string();
  if (ext == "." + std::string(GetParam().format)) {
    against = " --input " + Input();
  } else {
    against = std::string(" --expect ") + kTopic + ":3 --expect /imu/data:30 --expect /gps/fix:3";
  }
  for (const char* suffix : kClouds) against += std::string(" --expect ") + kTopic + suffix + ":3";
  const std::string command = bag ? "/usr/bin/python3 " + tools + "/read_bag.py " + path
                                  : "node " + tools + "/read_mcap.mjs " + path;
  std::string log;
  EXPECT_EQ(test::RunCommand(command + against + " --labels " + Labels(), &log), 0) << log;
  EXPECT_NE(log.find("every check passed"), std::string::npos) << log;
}

INSTANTIATE_TEST_SUITE_P(Fixtures, CliDriveOutput, ::testing::ValuesIn(kCases),
                         [](const ::testing::TestParamInfo<Case>& info) {
                           std::string name =
                               std::string(info.param.drive) + "_to_" + info.param.format;
                           for (char& c : name)
                             if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                           return name;
                         });

TEST(CliDriveOutputArgs, BagNeedsARos1InputAndNeitherTakesChunks) {
  test::ScopedDir dir;
  std::string log;
  for (const char* drive : {"vlp16_full.mcap", "vlp16_full.db3"}) {
    EXPECT_EQ(Segment(test::DrivesDir() + "/" + drive, "bag", dir.path, &log), "2") << log;
    EXPECT_NE(log.find("--format bag writes a ROS 1 bag, for a ROS 1 .bag input"),
              std::string::npos)
        << log;
  }
  EXPECT_EQ(Segment(test::DrivesDir() + "/vlp16_split_mcap", "bag", dir.path, &log), "2") << log;
  EXPECT_NE(log.find("vlp16_split_mcap is a ROS 2 drive"), std::string::npos) << log;
  EXPECT_EQ(Segment(test::FixtureFrameBase(0) + ".bin", "bag", dir.path, &log), "2") << log;
  for (const char* format : {"mcap", "bag"}) {
    EXPECT_EQ(Segment(test::DrivesDir() + "/vlp16_lz4.bag --chunks 1:2", format, dir.path, &log),
              "2")
        << log;
    EXPECT_NE(log.find("writes the whole drive back: it takes no --chunks"), std::string::npos)
        << log;
  }
  EXPECT_FALSE(fs::exists(dir.path + "/vlp16_lz4.bag")) << "nothing written";
}

TEST(CliDriveOutputArgs, BagNeverWritesOverTheBagItReads) {
  test::ScopedDir dir;
  const std::string drive = dir.path + "/vlp16_full.bag";
  test::WriteRaw(drive, test::ReadRaw(test::DrivesDir() + "/vlp16_full.bag"));
  std::string log;
  EXPECT_EQ(Segment(drive, "bag", dir.path, &log), "2") << log;
  EXPECT_NE(log.find("is the drive being read"), std::string::npos) << log;
  EXPECT_EQ(test::ReadRaw(drive), test::ReadRaw(test::DrivesDir() + "/vlp16_full.bag"));
}

// A drive cut short: what can be read of it is in the output, every record as it was; the damage
// is named (by the segmenting reader and by the copy, which names the output) and the exit code
// is 1.
TEST(CliDriveOutputDamage, ACutDriveKeepsEveryRecordBeforeTheCutAndNamesTheDamage) {
  for (const char* name : {"vlp16_full.mcap", "vlp16_full.bag"}) {
    SCOPED_TRACE(name);
    test::ScopedDir dir;
    const std::string whole = test::ReadRaw(test::DrivesDir() + "/" + name);
    const std::string drive = dir.path + "/cut_" + name;
    test::WriteRaw(drive, whole.substr(0, whole.size() * 19 / 20));  // inside the last chunk
    const std::string ext = fs::path(name).extension().string().substr(1);
    std::string log;
    EXPECT_EQ(Segment(drive, ext, dir.path + "/out", &log), "1") << log;
    const std::string out = dir.path + "/out/cut_" + fs::path(name).stem().string() + "." + ext;
    EXPECT_NE(log.find("lpir-gseg segment: error: " + drive), std::string::npos) << log;
    EXPECT_NE(log.find("its records are not in " + out), std::string::npos) << log;
    const Content in = ReadContent(drive);
    EXPECT_FALSE(in.damage.empty());
    const Content got = ReadContent(out);
    EXPECT_EQ(got.damage, std::vector<std::string>{});
    ExpectHoldsEveryRecordOf(got, in);
    size_t before = 0;
    for (const auto& [topic, t] : in.topics) before += t.messages.size();
    EXPECT_GT(before, 10u) << "the cut left messages to keep";
  }
}

// ---- drives as recorders leave them, and several drives ----

// A ROS 2 bag folder of two split files: one MCAP holding each file's records one after another,
// the channel and schema the files repeat written once (ReadContent fails on a second channel of
// a topic), the sequences numbered on across the files, and the three clouds of every message.
TEST(CliDriveOutputFolders, ABagFolderBecomesOneMcapHoldingEachFilesRecordsOnce) {
  for (const std::string folder : {"vlp16_split_mcap", "vlp16_split_db3"}) {
    SCOPED_TRACE(folder);
    test::ScopedDir dir;
    const std::string input = test::DrivesDir() + "/" + folder;
    std::string log;
    ASSERT_EQ(Segment(input, "mcap", dir.path + "/out", &log), "0") << log;
    ASSERT_EQ(Segment(input, "label", dir.path + "/labels", &log), "0") << log;
    const Content out = ReadContent(dir.path + "/out/" + folder + ".mcap");
    EXPECT_EQ(out.damage, std::vector<std::string>{});
    EXPECT_EQ(out.profile, "ros2");
    const std::string ext = folder == "vlp16_split_mcap" ? ".mcap" : ".db3";
    const Content parts[2] = {ReadContent(input + "/" + folder + "_0" + ext),
                              ReadContent(input + "/" + folder + "_1" + ext)};
    std::vector<DriveRecordMessage> want;
    for (const Content& part : parts) {
      ASSERT_EQ(part.topics.size(), 1u);
      const Content::Topic& t = part.topics.at(kTopic);
      EXPECT_EQ(out.topics.at(kTopic).channel.metadata, t.channel.metadata);
      EXPECT_EQ(out.topics.at(kTopic).schema.data, t.schema.data);
      want.insert(want.end(), t.messages.begin(), t.messages.end());
    }
    EXPECT_EQ(out.topics.size(), 1u + 3);
    const std::vector<DriveRecordMessage>& got = out.topics.at(kTopic).messages;
    ASSERT_EQ(got.size(), kFrames);
    ASSERT_EQ(want.size(), kFrames);
    for (size_t k = 0; k < kFrames; ++k) {
      EXPECT_EQ(got[k].sequence, k) << k;
      EXPECT_EQ(got[k].log_time_ns, want[k].log_time_ns) << k;
      EXPECT_EQ(got[k].data, want[k].data) << k;
    }
    ExpectTheThreeClouds(out, dir.path + "/labels", kFrames, 10);
  }
}

// What a ROS 1 recorder that died leaves: copied, as a bag or an MCAP, up to its last complete
// message, the three clouds of the two messages it finished; the cut named, exit code 1.
TEST(CliDriveOutputFolders, AKilledBagIsCopiedToItsLastCompleteMessage) {
  const std::string input = test::DrivesDir() + "/vlp16_killed.bag.active";
  const Content in = ReadContent(input);
  EXPECT_FALSE(in.damage.empty()) << "the last message is cut";
  ASSERT_EQ(in.topics.at(kTopic).messages.size(), 2u);
  for (const char* format : {"bag", "mcap"}) {
    SCOPED_TRACE(format);
    test::ScopedDir dir;
    std::string log;
    EXPECT_EQ(Segment(input, format, dir.path + "/out", &log), "1") << log;
    ASSERT_EQ(Segment(input, "label", dir.path + "/labels", &log), "1") << log;
    const Content out = ReadContent(dir.path + "/out/vlp16_killed." + format);
    EXPECT_EQ(out.damage, std::vector<std::string>{});
    ExpectHoldsEveryRecordOf(out, in);
    ExpectTheThreeClouds(out, dir.path + "/labels", 2, 10);
  }
}

// Several drives with --format mcap: each writes <drive stem>.mcap into its own folder; cloud
// files among them are refused, before anything is written.
TEST(CliDriveOutputFolders, SeveralDrivesEachWriteTheirCopyIntoTheirFolder) {
  test::ScopedDir dir;
  const std::string drives =
      test::DrivesDir() + "/vlp16_zstd.mcap " + test::DrivesDir() + "/vlp16_split_db3";
  std::string log;
  ASSERT_EQ(Segment(drives, "mcap", dir.path + "/out", &log), "0") << log;
  for (const std::string stem : {"vlp16_zstd", "vlp16_split_db3"}) {
    SCOPED_TRACE(stem);
    const Content out = ReadContent(dir.path + "/out/" + stem + "/" + stem + ".mcap");
    EXPECT_EQ(out.damage, std::vector<std::string>{});
    EXPECT_EQ(out.topics.at(kTopic + std::string("/labelled")).messages.size(), kFrames);
    EXPECT_TRUE(fs::exists(dir.path + "/out/" + stem + "/index.csv"));
  }
  EXPECT_EQ(
      Segment(drives + " " + test::FixtureFrameBase(0) + ".bin", "mcap", dir.path + "/o2", &log),
      "2")
      << log;
  EXPECT_NE(log.find("--format mcap is for recorded drives"), std::string::npos) << log;
  EXPECT_FALSE(fs::exists(dir.path + "/o2"));
}

}  // namespace
}  // namespace lpir
