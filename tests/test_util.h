// Helpers shared by the tests: where the real scans, the profiles and the CLI are.
#pragma once
#include <string>

namespace lpir::test {

// ../shared/data, or "" when the folder is absent (tests then GTEST_SKIP with a message).
std::string DataDir();
// Full path of a file under the data folder; "" when the folder or file is absent.
std::string DataFile(const std::string& relative);
std::string SensorsDir();
std::string CliPath();
// A fresh empty temporary folder, unique per call.
std::string TempDir();
// Runs a shell command; returns its exit code and fills `output` with stdout+stderr.
int RunCommand(const std::string& command, std::string* output = nullptr);
// A file's bytes ("" when it cannot be read).
std::string ReadFileBytes(const std::string& path);
// True when VK_ICD_FILENAMES names an existing file (ctest points it at lavapipe for *_vk_test).
bool HasLavapipe();

}  // namespace lpir::test

// For tests that run Vulkan through the CLI (no VkTest fixture): skip without the lavapipe ICD.
#define LPIR_REQUIRE_LAVAPIPE()                                                           \
  do {                                                                                    \
    if (!::lpir::test::HasLavapipe())                                                     \
      GTEST_SKIP() << "no lavapipe ICD (VK_ICD_FILENAMES); install mesa-vulkan-drivers";  \
  } while (0)

#define LPIR_REQUIRE_DATA(path)                                                             \
  do {                                                                                      \
    if (::lpir::test::DataFile(path).empty())                                               \
      GTEST_SKIP() << "real scan " << (path) << " not found under " LPIR_DATA_DIR           \
                   << " (../shared/data is absent on this machine)";                        \
  } while (0)
