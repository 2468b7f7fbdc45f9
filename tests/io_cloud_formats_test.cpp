// The table of cloud formats (host/io/cloud_file.h): every row is found by its extension in any
// case, read back what its writer wrote, and named by the lists that messages and help texts use;
// a path of no row is refused naming the file and the formats.
#include <gtest/gtest.h>

#include <cctype>
#include <string>

#include "host/io/cloud_file.h"
#include "tests/io_test_helpers.h"
#include "tests/test_util.h"

namespace lpir {
namespace {

std::string Upper(std::string s) {
  for (char& c : s) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return s;
}

TEST(IoCloudFormats, EveryRowIsFoundByItsExtensionAndListed) {
  ASSERT_GE(CloudFormats().size(), 3u);
  for (const CloudFormat& f : CloudFormats()) {
    SCOPED_TRACE(f.extension);
    EXPECT_EQ(CloudFormatOf("dir.x/scan." + std::string(f.extension)), &f);
    EXPECT_EQ(CloudFormatOf("scan." + Upper(f.extension)), &f);
    EXPECT_TRUE(IsCloudFile("scan." + std::string(f.extension)));
    EXPECT_NE(CloudFormatList().find(f.summary), std::string::npos) << CloudFormatList();
    EXPECT_EQ(CloudFormatList(true).find(f.extension) != std::string::npos,
              f.write_labelled != nullptr)
        << CloudFormatList(true);
  }
  EXPECT_EQ(CloudFormatOf("scan.txt"), nullptr);
  EXPECT_EQ(CloudFormatOf("scan.pcd/noext"), nullptr);
}

TEST(IoCloudFormats, EveryWriterIsReadBackByItsReader) {
  const std::string dir = test::TempDir();
  const Cloud cloud = test::SampleCloud(12, true);
  Labels labels(cloud.size());
  for (size_t i = 0; i < labels.size(); ++i) labels[i] = i % 2;
  int writers = 0;
  for (const CloudFormat& f : CloudFormats()) {
    if (!f.write_labelled) continue;
    SCOPED_TRACE(f.extension);
    const std::string path = dir + "/l." + f.extension;
    WriteLabelledCloud(path, cloud, labels);
    EXPECT_TRUE(test::SameBits(cloud, ReadCloud(path)));
    ++writers;
  }
  EXPECT_GE(writers, 2);
}

TEST(IoCloudFormats, PathsOfNoRowAreRefusedNamingTheFormats) {
  const std::string dir = test::TempDir();
  const std::string txt = dir + "/a.txt";
  test::WriteRaw(txt, "1 2 3\n");
  EXPECT_TRUE(test::ThrowsIoError([&] { ReadCloud(txt); }, txt,
                                  {"unknown cloud file extension", CloudFormatList()}));
  const std::string bin = dir + "/l.bin";
  const Cloud cloud = test::SampleCloud(4, false);
  EXPECT_TRUE(test::ThrowsIoError([&] { WriteLabelledCloud(bin, cloud, Labels(4)); }, bin,
                                  {"no labelled-cloud writer", CloudFormatList(true)}));
}

}  // namespace
}  // namespace lpir
