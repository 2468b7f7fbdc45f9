// lpir-gseg segment on a recorded drive on Vulkan (lavapipe under ctest): the messages go through
// frames in flight and batches as files do, and the labels equal the CPU reference's byte for
// byte; the report names the device.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "tests/drive_fixtures.h"
#include "tests/test_util.h"

namespace fs = std::filesystem;

namespace lpir {
namespace {

std::string Drive() { return test::DrivesDir() + "/vlp16_zstd.mcap"; }

TEST(CliDriveVulkan, LabelsEqualTheReferenceInFlightAndInBatches) {
  LPIR_REQUIRE_VULKAN();
  test::ScopedDir dir;
  const std::string segment = test::CliPath() + " segment " + Drive() + " --sensor vlp16 --out ";
  std::string log;
  ASSERT_EQ(test::RunCommand(segment + dir.path + "/cpu --backend cpu --quiet", &log), 0) << log;
  const std::vector<std::string> names = test::LabelFiles(dir.path + "/cpu");
  ASSERT_EQ(names.size(), 3u) << log;
  size_t ground = 0;
  for (const std::string& name : names)
    for (char c : test::ReadFileBytes(dir.path + "/cpu/" + name)) ground += c == 1;
  EXPECT_GT(ground, 100u) << "labels all 0 would make the comparison empty";
  for (const char* batch : {"1", "2"}) {
    const std::string out = dir.path + "/vk" + batch;
    ASSERT_EQ(test::RunCommand(segment + out + " --backend vulkan --quiet --batch " + batch +
                                   " --report " + out + ".csv",
                               &log),
              0)
        << log;
    EXPECT_EQ(test::LabelFiles(out), names) << "--batch " << batch;
    for (const std::string& name : names)
      EXPECT_EQ(test::ReadFileBytes(out + "/" + name),
                test::ReadFileBytes(dir.path + "/cpu/" + name))
          << name << " --batch " << batch;
    EXPECT_NE(test::ReadFileBytes(out + ".csv").find(",vulkan,"), std::string::npos);
  }
}

}  // namespace
}  // namespace lpir
