// Recorded drives as recorders leave them, on the fixtures independent writers made
// (tests/data/drives/, scripts/make_drive_fixtures.sh): ROS 2 bag folders of two split files
// (MCAP by @mcap/core with rosbag2's yaml-cpp metadata.yaml, .db3 by sqlite3 with PyYAML's), read
// as one drive in metadata.yaml's order or, without it, by the files' numbers; the metadata.yaml
// reader (mini_yaml.h, bag_metadata.h); a ROS 1 bag a killed recorder left (.bag.active, by
// python3-rosbag); the damage a listing meets; the inputs rule (inputs.h).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <memory>
#include <ostream>
#include <stdexcept>
#include <string>
#include <vector>

#include "host/drive/bag_folder.h"
#include "host/drive/bag_metadata.h"
#include "host/drive/drive.h"
#include "host/drive/inputs.h"
#include "host/drive/mini_yaml.h"
#include "host/drive/pointcloud2.h"
#include "host/io/io_error.h"
#include "host/io/output_paths.h"
#include "tests/drive_fixtures.h"
#include "tests/io_test_helpers.h"
#include "tests/test_util.h"

namespace fs = std::filesystem;

namespace lpir {
namespace {

using test::kFirstStampNs;
const char* const kTopic = test::kFixtureTopic;

bool Has(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

std::string Joined(const std::vector<std::string>& lines) {
  std::string text;
  for (const std::string& line : lines) text += line + "\n";
  return text;
}

// Every step of reading `topic` from `reader`: the messages, and the damage in order ("" for a
// message), at most 20 steps.
struct Read {
  std::vector<DriveMessage> messages;
  std::vector<std::string> steps;  // "" for a message, else the problem
};
Read ReadAll(DriveReader& reader, const std::string& topic = kTopic) {
  Read out;
  reader.SelectTopic(topic);
  DriveMessage m;
  std::string problem;
  for (int guard = 0; guard < 20; ++guard) {
    const DriveStep step = reader.Next(&m, &problem);
    if (step == DriveStep::kEnd) break;
    out.steps.push_back(step == DriveStep::kMessage ? "" : problem);
    if (step == DriveStep::kMessage) out.messages.push_back(m);
  }
  return out;
}

long long Stamp(const DriveMessage& m) {
  const PointCloud2 c = ParseCdrPointCloud2("message", m.data.data(), m.data.size());
  return c.stamp_ns();
}

// A copy of the fixture folder `name` in `dir`, under the same name (a bag folder's files are
// named after it).
std::string CopyFolder(const test::ScopedDir& dir, const std::string& name) {
  const std::string to = dir.path + "/" + name;
  fs::copy(test::DrivesDir() + "/" + name, to, fs::copy_options::recursive);
  return to;
}

// ---- metadata.yaml ----

TEST(MiniYaml, ReadsTheFixturesMetadataAsBothWritersWriteIt) {
  for (const char* folder : {"vlp16_split_mcap", "vlp16_split_db3"}) {
    const std::string ext = std::string(folder) == "vlp16_split_mcap" ? ".mcap" : ".db3";
    const BagMetadata m =
        ParseBagMetadata(test::ReadRaw(test::DrivesDir() + "/" + folder + "/metadata.yaml"));
    EXPECT_EQ(m.storage_identifier, ext == ".mcap" ? "mcap" : "sqlite3") << folder;
    EXPECT_EQ(m.relative_file_paths, (std::vector<std::string>{std::string(folder) + "_0" + ext,
                                                               std::string(folder) + "_1" + ext}))
        << folder;
    EXPECT_EQ(m.compression_format, "") << folder;
    ASSERT_EQ(m.topics.size(), 1u) << folder;
    EXPECT_EQ(m.topics[0].name, kTopic);
    EXPECT_EQ(m.topics[0].type, "sensor_msgs/msg/PointCloud2");
    EXPECT_EQ(m.topics[0].serialization_format, "cdr");
    EXPECT_EQ(m.topics[0].messages, 3u);
  }
}

// PyYAML folds a long double-quoted string over lines, with escaped line breaks and spaces.
TEST(MiniYaml, UnfoldsADoubleQuotedScalarAsPyYamlFoldsIt) {
  const YamlNode root =
      ParseYaml(test::ReadRaw(test::DrivesDir() + "/vlp16_split_db3/metadata.yaml"));
  const YamlNode* info = root.Get("rosbag2_bagfile_information");
  ASSERT_NE(info, nullptr);
  const YamlNode& topic = info->Get("topics_with_message_count")->seq.at(0);
  const YamlNode* qos = topic.Get("topic_metadata")->Get("offered_qos_profiles");
  ASSERT_NE(qos, nullptr);
  // tools/drive_fixtures/write_metadata.py's QOS, what PyYAML was given
  EXPECT_EQ(qos->scalar,
            "- history: 3\n  depth: 0\n  reliability: 2\n  durability: 2\n"
            "  deadline:\n    sec: 9223372036\n    nsec: 854775807\n"
            "  lifespan:\n    sec: 9223372036\n    nsec: 854775807\n"
            "  liveliness: 1\n  liveliness_lease_duration:\n    sec: 9223372036\n"
            "    nsec: 854775807\n  avoid_ros_namespace_conventions: false\n");
}

TEST(MiniYaml, ReadsTheSubsetItNames) {
  const YamlNode root = ParseYaml(
      "---\n"
      "# a comment\n"
      "a:\n"
      "- x   # compact, as PyYAML writes\n"
      "- 'it''s'\n"
      "b:\n"
      "    - k: 1\n"
      "      l: \"t\\tab \\u00e9\"\n"
      "    - - nested\n"
      "c: []\n"
      "d: {}\n"
      "e: [p, 'q r', \"s\"]\n"
      "f: ~\n"
      "g: |\n"
      "  one\n"
      "   two\n"
      "h: >-\n"
      "  folded\n"
      "  line\n"
      "i: plain\n"
      "  continued\n"
      "'quoted key': 2\n");
  ASSERT_EQ(root.kind, YamlNode::Kind::kMap);
  const YamlNode& a = *root.Get("a");
  ASSERT_EQ(a.seq.size(), 2u);
  EXPECT_EQ(a.seq[0].scalar, "x");
  EXPECT_EQ(a.seq[1].scalar, "it's");
  const YamlNode& b = *root.Get("b");
  ASSERT_EQ(b.seq.size(), 2u);
  EXPECT_EQ(b.seq[0].Get("k")->scalar, "1");
  EXPECT_EQ(b.seq[0].Get("l")->scalar, "t\tab \xc3\xa9");
  EXPECT_EQ(b.seq[1].seq.at(0).scalar, "nested");
  EXPECT_EQ(root.Get("c")->kind, YamlNode::Kind::kSeq);
  EXPECT_TRUE(root.Get("c")->seq.empty());
  EXPECT_EQ(root.Get("d")->kind, YamlNode::Kind::kMap);
  ASSERT_EQ(root.Get("e")->seq.size(), 3u);
  EXPECT_EQ(root.Get("e")->seq[1].scalar, "q r");
  EXPECT_EQ(root.Get("f")->kind, YamlNode::Kind::kNull);
  EXPECT_EQ(root.Get("g")->scalar, "one\n two\n");
  EXPECT_EQ(root.Get("h")->scalar, "folded line");
  EXPECT_EQ(root.Get("i")->scalar, "plain continued");
  EXPECT_EQ(root.Get("quoted key")->scalar, "2");
  EXPECT_EQ(root.Get("absent"), nullptr);
}

TEST(MiniYaml, WhatItDoesNotReadIsAnErrorNamingTheLine) {
  const std::pair<const char*, const char*> cases[] = {
      {"a:\n\t- x\n", "line 2: a tab"},
      {"a: &anchor x\n", "line 1: '&'"},
      {"a: 1\na: 2\n", "line 2: key 'a' given twice"},
      {"a: \"open\n\nb: 1\n", "line 1: a double-quoted scalar that never ends"},
      {"? a\n: b\n", "line 1: '?'"},
      {"a: {b: 1}\n", "line 1: a flow mapping"},
      {"a:\n  b: 1\n c: 2\n", "line 3:"},
      {"a: [x,\n  y]\n", "line 1: a flow sequence that does not end on its line"},
  };
  for (const auto& [text, expected] : cases) {
    try {
      ParseYaml(text);
      ADD_FAILURE() << "no error for: " << text;
    } catch (const YamlError& e) {
      EXPECT_TRUE(Has(e.what(), expected)) << e.what() << "\nfor: " << text;
    }
  }
  std::string deep;  // "- - - ... x": a sequence in a sequence 100 deep, on one line
  for (int k = 0; k < 100; ++k) deep += "- ";
  try {
    ParseYaml(deep + "x\n");
    ADD_FAILURE() << "100 levels were read";
  } catch (const YamlError& e) {
    EXPECT_TRUE(Has(e.what(), "line 1: nested deeper than 64 levels")) << e.what();
  }
}

TEST(BagMetadata, RefusesMetadataThatNamesNoFiles) {
  EXPECT_THROW(ParseBagMetadata("other: 1\n"), YamlError);
  EXPECT_THROW(ParseBagMetadata("rosbag2_bagfile_information:\n  version: 5\n"), YamlError);
  EXPECT_THROW(ParseBagMetadata("rosbag2_bagfile_information:\n  relative_file_paths: []\n"),
               YamlError);
  try {
    ParseBagMetadata(
        "rosbag2_bagfile_information:\n  relative_file_paths:\n    - a_0.mcap\n"
        "  topics_with_message_count:\n    - topic_metadata:\n        name: /a\n"
        "      message_count: many\n");
    ADD_FAILURE() << "a count that is no number was read";
  } catch (const YamlError& e) {
    EXPECT_TRUE(Has(e.what(), "line 7")) << e.what();
    EXPECT_TRUE(Has(e.what(), "'message_count' is not a whole number")) << e.what();
  }
}

// ---- bag folders ----

struct SplitBag {
  const char* folder;
  const char* ext;
};
const SplitBag kSplitBags[] = {{"vlp16_split_mcap", ".mcap"}, {"vlp16_split_db3", ".db3"}};
void PrintTo(const SplitBag& b, std::ostream* os) { *os << b.folder; }

class BagFolder : public ::testing::TestWithParam<SplitBag> {
 protected:
  std::string Folder() const { return test::DrivesDir() + "/" + GetParam().folder; }
  std::string File(const std::string& folder, int n) const {
    return folder + "/" + GetParam().folder + "_" + std::to_string(n) + GetParam().ext;
  }
};

TEST_P(BagFolder, ReadsItsFilesInOrderAsOneDrive) {
  ASSERT_TRUE(IsBagFolder(Folder()));
  ASSERT_TRUE(IsDrive(Folder()));
  EXPECT_FALSE(IsDriveFile(Folder()));
  EXPECT_EQ(DriveStem(Folder() + "/"), GetParam().folder);
  const std::unique_ptr<DriveReader> reader = OpenDrive(Folder(), 1);
  const std::vector<DriveTopic> topics = reader->Topics();
  ASSERT_EQ(topics.size(), 1u);
  EXPECT_EQ(topics[0].name, kTopic);
  EXPECT_EQ(topics[0].messages, 3u);
  EXPECT_EQ(reader->ListingDamage(), std::vector<std::string>{});
  EXPECT_EQ(reader->Notes(), std::vector<std::string>{});
  const Read read = ReadAll(*reader);
  ASSERT_EQ(read.steps, std::vector<std::string>(3, ""));
  // file by file, each read alone: the same messages, numbered on
  std::vector<DriveMessage> alone;
  for (int n : {0, 1}) {
    const std::unique_ptr<DriveReader> file = OpenDrive(File(Folder(), n), 1);
    for (const DriveMessage& m : ReadAll(*file).messages) alone.push_back(m);
  }
  ASSERT_EQ(alone.size(), 3u);
  for (size_t i = 0; i < 3; ++i) {
    const DriveMessage& m = read.messages[i];
    EXPECT_EQ(m.sequence, i);
    EXPECT_EQ(m.data, alone[i].data) << i;
    EXPECT_EQ(m.log_time_ns, alone[i].log_time_ns) << i;
    EXPECT_EQ(Stamp(m), kFirstStampNs + (long long)i * 100000000LL) << i;
    EXPECT_TRUE(test::SameBits(DecodeDriveCloud("m", m), test::NarrowFrame(i))) << i;
  }
  EXPECT_EQ(alone[2].sequence, 0u) << "the second file alone starts at 0";
}

TEST_P(BagFolder, MetadataOrderRulesAndWithoutItTheNumbersDoWithANote) {
  test::ScopedDir dir;
  const std::string folder = CopyFolder(dir, GetParam().folder);
  const std::string name = GetParam().folder;
  const std::string ext = GetParam().ext;
  // metadata.yaml listing the second file first: its message comes first, as sequence 0
  test::WriteRaw(folder + "/metadata.yaml",
                 "rosbag2_bagfile_information:\n  relative_file_paths:\n    - " + name + "_1" +
                     ext + "\n    - " + name + "_0" + ext + "\n");
  Read read = ReadAll(*OpenDrive(folder, 1));
  ASSERT_EQ(read.messages.size(), 3u);
  EXPECT_EQ(Stamp(read.messages[0]), kFirstStampNs + 200000000LL);
  EXPECT_EQ(read.messages[0].sequence, 0u);
  EXPECT_EQ(Stamp(read.messages[1]), kFirstStampNs);
  // without metadata.yaml: by the files' numbers, said
  fs::remove(folder + "/metadata.yaml");
  ASSERT_TRUE(IsBagFolder(folder)) << "<folder name>_0" << ext << " marks it";
  std::unique_ptr<DriveReader> reader = OpenDrive(folder, 1);
  read = ReadAll(*reader);
  ASSERT_EQ(read.messages.size(), 3u);
  EXPECT_EQ(Stamp(read.messages[0]), kFirstStampNs);
  EXPECT_EQ(Stamp(read.messages[2]), kFirstStampNs + 200000000LL);
  const std::string notes = Joined(reader->Notes());
  EXPECT_TRUE(Has(notes, folder + ": no metadata.yaml")) << notes;
  EXPECT_TRUE(Has(notes, name + "_0" + ext + ", " + name + "_1" + ext)) << notes;
  // metadata.yaml that cannot be read: the same, the reason named
  test::WriteRaw(folder + "/metadata.yaml", "rosbag2_bagfile_information:\n\tversion: 5\n");
  reader = OpenDrive(folder, 1);
  EXPECT_EQ(ReadAll(*reader).messages.size(), 3u);
  EXPECT_TRUE(Has(Joined(reader->Notes()), folder + "/metadata.yaml: not read (line 2: a tab"))
      << Joined(reader->Notes());
}

TEST_P(BagFolder, AMissingFileIsDamageAtItsPlace) {
  test::ScopedDir dir;
  const std::string folder = CopyFolder(dir, GetParam().folder);
  fs::remove(File(folder, 0));
  const std::unique_ptr<DriveReader> reader = OpenDrive(folder, 1);
  ASSERT_EQ(reader->Topics().at(0).messages, 1u);
  const std::string damage = Joined(reader->ListingDamage());
  EXPECT_TRUE(Has(damage, File(folder, 0))) << damage;
  EXPECT_TRUE(Has(damage, "counts 3 messages of /velodyne_points, the bag's files hold 1"))
      << damage;
  const Read read = ReadAll(*reader);
  ASSERT_EQ(read.steps.size(), 2u);
  EXPECT_TRUE(Has(read.steps[0], File(folder, 0))) << read.steps[0];
  EXPECT_EQ(read.steps[1], "");
  EXPECT_EQ(read.messages.at(0).sequence, 0u);
  EXPECT_EQ(Stamp(read.messages.at(0)), kFirstStampNs + 200000000LL);
  // not one file left: an error naming the folder
  fs::remove(File(folder, 1));
  EXPECT_THROW(OpenDrive(folder, 1), IoError);
}

TEST_P(BagFolder, ABagRosbag2CompressedIsRefusedNamingHow) {
  test::ScopedDir dir;
  const std::string folder = CopyFolder(dir, GetParam().folder);
  std::string text = test::ReadRaw(folder + "/metadata.yaml");
  const std::pair<std::string, std::string> fields[] = {{"compression_format: ", "zstd"},
                                                        {"compression_mode: ", "FILE"}};
  for (const auto& [key, value] : fields) {
    const size_t at = text.find(key);
    ASSERT_NE(at, std::string::npos) << key;
    text.replace(at, text.find('\n', at) - at, key + value);
  }
  test::WriteRaw(folder + "/metadata.yaml", text);
  try {
    OpenDrive(folder, 1);
    ADD_FAILURE() << "a compressed bag was opened";
  } catch (const IoError& e) {
    EXPECT_TRUE(Has(e.what(), folder + "/metadata.yaml: ")) << e.what();
    EXPECT_TRUE(Has(e.what(), "compressed by rosbag2 (zstd, FILE mode)")) << e.what();
  }
}

INSTANTIATE_TEST_SUITE_P(Fixtures, BagFolder, ::testing::ValuesIn(kSplitBags),
                         [](const ::testing::TestParamInfo<SplitBag>& info) {
                           return std::string(info.param.ext + 1);
                         });

TEST(BagFolderChunks, AreNumberedOnAcrossTheFiles) {
  const std::unique_ptr<DriveReader> reader = OpenDrive(test::DrivesDir() + "/vlp16_split_mcap", 1);
  ASSERT_EQ(reader->ChunkCount(), 3u);
  EXPECT_TRUE(reader->ChunksIndexed());
  const std::vector<std::pair<uint64_t, uint64_t>> ranges = {{1, 1}, {2, 3}, {3, 3}, {1, 3}};
  for (const auto& [first, last] : ranges) {
    reader->SelectTopic(kTopic);
    reader->SelectChunks(first, last);
    std::vector<uint64_t> sequences;
    DriveMessage m;
    std::string problem;
    for (DriveStep s; (s = reader->Next(&m, &problem)) != DriveStep::kEnd;) {
      ASSERT_EQ(s, DriveStep::kMessage) << problem;
      sequences.push_back(m.sequence);
      EXPECT_EQ(Stamp(m), kFirstStampNs + (long long)m.sequence * 100000000LL);
    }
    std::vector<uint64_t> expected;
    for (uint64_t c = first; c <= last; ++c) expected.push_back(c - 1);  // a message a chunk
    EXPECT_EQ(sequences, expected) << first << ":" << last;
  }
  EXPECT_THROW(reader->SelectChunks(2, 4), IoError);
  const std::unique_ptr<DriveReader> db3 = OpenDrive(test::DrivesDir() + "/vlp16_split_db3", 1);
  EXPECT_EQ(db3->ChunkCount(), 0u);
  EXPECT_FALSE(db3->ChunksIndexed());
  db3->SelectTopic(kTopic);
  EXPECT_THROW(db3->SelectChunks(1, 1), IoError);
}

TEST(BagFolderTell, WhatIsAndIsNotABagFolder) {
  test::ScopedDir dir;
  EXPECT_FALSE(IsBagFolder(test::DrivesDir())) << "a folder of drives";
  EXPECT_FALSE(IsBagFolder(test::DrivesDir() + "/vlp16_zstd.mcap"));
  fs::create_directories(dir.path + "/run");
  fs::copy(test::DrivesDir() + "/vlp16_zstd.mcap", dir.path + "/run/other_0.mcap");
  EXPECT_FALSE(IsBagFolder(dir.path + "/run")) << "its files are named after the folder";
  fs::copy(test::DrivesDir() + "/vlp16_zstd.mcap", dir.path + "/run/run_0.mcap");
  EXPECT_TRUE(IsBagFolder(dir.path + "/run"));
  EXPECT_EQ(DriveStem(dir.path + "/run"), "run");
  EXPECT_EQ(DriveStem("/a/b/drive.bag.active"), "drive");
  EXPECT_EQ(DriveStem("/a/b/drive.mcap"), "drive");
  try {
    OpenDrive(test::DrivesDir() + "/frames");
    ADD_FAILURE() << "a folder of clouds was opened as a drive";
  } catch (const IoError& e) {
    EXPECT_TRUE(Has(e.what(), "not a ROS 2 bag")) << e.what();
  }
}

// ---- a ROS 1 recorder killed while writing ----

TEST(KilledRos1Bag, ItsCompleteMessagesAreReadThenTheCutIsNamed) {
  const std::string path = test::DrivesDir() + "/vlp16_killed.bag.active";
  ASSERT_TRUE(IsDriveFile(path));
  EXPECT_EQ(DriveStem(path), "vlp16_killed");
  const std::unique_ptr<DriveReader> reader = OpenDrive(path, 1);
  const std::vector<DriveTopic> topics = reader->Topics();
  ASSERT_EQ(topics.size(), 1u);
  EXPECT_EQ(topics[0].messages, 2u) << "frames 0 and 1 whole, frame 2 cut";
  EXPECT_EQ(reader->ChunkCount(), 2u);
  EXPECT_FALSE(reader->ChunksIndexed());
  const std::string notes = Joined(reader->Notes());
  EXPECT_TRUE(Has(notes, path + ": no index")) << notes;
  EXPECT_TRUE(Has(notes, "chunk 2 at byte")) << notes;
  const std::vector<std::string> damage = reader->ListingDamage();
  ASSERT_EQ(damage.size(), 1u);
  EXPECT_TRUE(Has(damage[0], path + ": chunk 2 at byte")) << damage[0];
  const Read read = ReadAll(*reader);
  ASSERT_EQ(read.steps.size(), 3u);
  EXPECT_EQ(read.steps[0], "");
  EXPECT_EQ(read.steps[1], "");
  EXPECT_TRUE(Has(read.steps[2], path + ": chunk 2 at byte")) << read.steps[2];
  for (size_t i = 0; i < 2; ++i)
    EXPECT_TRUE(test::SameBits(DecodeDriveCloud("m", read.messages[i]), test::NarrowFrame(i))) << i;
}

// ---- damage met while listing ----

TEST(ListingDamage, ACutDriveListsItsDamageAWholeOneNone) {
  test::ScopedDir dir;
  for (const char* name : {"vlp16_zstd.mcap", "vlp16_none.mcap", "vlp16_bz2.bag"}) {
    const std::string whole = test::DrivesDir() + "/" + name;
    std::unique_ptr<DriveReader> reader = OpenDrive(whole, 1);
    reader->Topics();
    EXPECT_EQ(reader->ListingDamage(), std::vector<std::string>{}) << name;
    const std::string bytes = test::ReadRaw(whole);
    const std::string cut = dir.path + "/" + name;
    test::WriteRaw(cut, bytes.substr(0, bytes.size() * 85 / 100));  // inside the third chunk
    reader = OpenDrive(cut, 1);
    EXPECT_EQ(reader->Topics().at(0).messages, 2u) << name;
    const std::vector<std::string> damage = reader->ListingDamage();
    ASSERT_EQ(damage.size(), 1u) << name;
    EXPECT_TRUE(Has(damage[0], cut + ": ")) << damage[0];
    EXPECT_TRUE(Has(damage[0], "chunk 3")) << damage[0];
  }
  // a 3 KB stub: not a topic could be read, and the listing says why
  const std::string stub = dir.path + "/stub.mcap";
  test::WriteRaw(stub, test::ReadRaw(test::DrivesDir() + "/vlp16_zstd.mcap").substr(0, 3000));
  const std::unique_ptr<DriveReader> reader = OpenDrive(stub, 1);
  EXPECT_TRUE(reader->Topics().empty());
  ASSERT_EQ(reader->ListingDamage().size(), 1u);
  EXPECT_TRUE(Has(reader->ListingDamage()[0], stub + ": chunk 1")) << reader->ListingDamage()[0];
}

// ---- the inputs rule ----

TEST(Inputs, AFolderGivesItsCloudsAndDrivesInNameOrderAndNamesTheRest) {
  test::ScopedDir dir;
  const std::string d = dir.path;
  fs::copy(test::FixtureFrameBase(0) + ".bin", d + "/a.bin");
  fs::copy(test::DrivesDir() + "/vlp16_zstd.mcap", d + "/b.mcap");
  fs::copy(test::DrivesDir() + "/vlp16_split_db3", d + "/c_bag", fs::copy_options::recursive);
  fs::copy(test::DrivesDir() + "/vlp16_killed.bag.active", d + "/d.bag.active");
  test::WriteRaw(d + "/notes.txt", "x");
  fs::create_directories(d + "/plain");
  std::vector<SkippedInput> skipped;
  const std::vector<RunInput> inputs = ListInputs({d}, false, &skipped);
  ASSERT_EQ(inputs.size(), 4u);
  const std::vector<std::pair<std::string, bool>> expected = {{d + "/a.bin", false},
                                                              {d + "/b.mcap", true},
                                                              {d + "/c_bag", true},
                                                              {d + "/d.bag.active", true}};
  for (size_t i = 0; i < inputs.size(); ++i) {
    EXPECT_EQ(inputs[i].path, expected[i].first);
    EXPECT_EQ(inputs[i].drive, expected[i].second) << inputs[i].path;
    EXPECT_EQ(inputs[i].folder, d) << inputs[i].path;
  }
  ASSERT_EQ(skipped.size(), 2u);
  EXPECT_EQ(skipped[0].path, d + "/notes.txt");
  EXPECT_TRUE(Has(skipped[0].why, "neither a cloud file")) << skipped[0].why;
  EXPECT_EQ(skipped[1].path, d + "/plain");
  EXPECT_TRUE(Has(skipped[1].why, "a folder that is no ROS 2 bag")) << skipped[1].why;
  // a bag folder given is one drive; a file given is itself, a drive by its name
  const std::vector<RunInput> bag =
      ListInputs({d + "/c_bag", d + "/x.bag", d + "/y.bin"}, false, nullptr);
  ASSERT_EQ(bag.size(), 3u);
  EXPECT_TRUE(bag[0].drive && bag[1].drive && !bag[2].drive);
  EXPECT_TRUE(bag[0].folder.empty() && bag[1].folder.empty() && bag[2].folder.empty());
  fs::create_directories(d + "/empty");
  EXPECT_THROW(ListInputs({d + "/empty"}, false, nullptr), std::invalid_argument);
}

TEST(Inputs, RecursiveTakesTheSubfoldersButNotABagFoldersFiles) {
  test::ScopedDir dir;
  const std::string d = dir.path + "/d";
  fs::create_directories(d + "/s/t");
  fs::copy(test::FixtureFrameBase(0) + ".bin", d + "/s/t/a.bin");
  fs::copy(test::DrivesDir() + "/vlp16_split_mcap", d + "/s/bag", fs::copy_options::recursive);
  fs::copy(test::DrivesDir() + "/vlp16_bz2.bag", d + "/z.bag");
  // without --recursive: nothing in d itself but the bag, the subfolder passed over
  std::vector<SkippedInput> skipped;
  std::vector<RunInput> inputs = ListInputs({d}, false, &skipped);
  ASSERT_EQ(inputs.size(), 1u);
  EXPECT_EQ(inputs[0].path, d + "/z.bag");
  ASSERT_EQ(skipped.size(), 1u);
  EXPECT_TRUE(Has(skipped[0].why, "--recursive walks it")) << skipped[0].why;
  skipped.clear();
  inputs = ListInputs({d}, true, &skipped);
  ASSERT_EQ(inputs.size(), 3u);
  EXPECT_EQ(inputs[0].path, d + "/s/bag");
  EXPECT_TRUE(inputs[0].drive);
  EXPECT_EQ(inputs[1].path, d + "/s/t/a.bin");
  EXPECT_FALSE(inputs[1].drive);
  EXPECT_EQ(inputs[2].path, d + "/z.bag");
  for (const RunInput& in : inputs) EXPECT_EQ(in.folder, d) << in.path;
  EXPECT_TRUE(skipped.empty()) << skipped[0].path;
  // each keeps its path below the folder given, a drive its stem
  EXPECT_EQ(OutputPaths(inputs, "o", ".label"),
            (std::vector<std::string>{"o/s/bag", "o/s/t/a.label", "o/z"}));
  // a folder of nothing but subfolders: the hint
  fs::create_directories(dir.path + "/e/f");
  fs::copy(test::FixtureFrameBase(0) + ".bin", dir.path + "/e/f/a.bin");
  try {
    ListInputs({dir.path + "/e"}, false, nullptr);
    ADD_FAILURE() << "no std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_TRUE(Has(e.what(), dir.path + "/e: folder holds no cloud files or drives, but its "
                                         "subfolders hold 1: --recursive (-r)"))
        << e.what();
  }
}

}  // namespace
}  // namespace lpir
