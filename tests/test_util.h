// Helpers shared by the tests: where the real scans, the profiles and the CLI are (the
// environment variables LPIR_DATA_DIR, LPIR_SENSORS_DIR and LPIR_CLI, when set and not empty,
// override the paths compiled in; a copy of the tests elsewhere, scripts/gpu_bundle.sh, sets them).
#pragma once
#include <string>

namespace lpir::test {

// The environment variable `name` when set and not empty, else `fallback`.
std::string EnvOr(const char* name, const char* fallback);
// ../shared/data (or $LPIR_DATA_DIR), or "" when the folder is absent (tests then GTEST_SKIP
// with a message).
std::string DataDir();
// Full path of a file under the data folder; "" when the folder or file is absent.
std::string DataFile(const std::string& relative);
std::string SensorsDir();
std::string CliPath();
// A fresh empty temporary folder, unique per call.
std::string TempDir();
// A TempDir() removed, with everything in it, when the object goes out of scope.
struct ScopedDir {
  std::string path = TempDir();
  ScopedDir() = default;
  ScopedDir(const ScopedDir&) = delete;
  ScopedDir& operator=(const ScopedDir&) = delete;
  ~ScopedDir();
};
// Runs a shell command; returns its exit code and fills `output` with stdout+stderr.
int RunCommand(const std::string& command, std::string* output = nullptr);
// A file's bytes ("" when it cannot be read).
std::string ReadFileBytes(const std::string& path);
// True when the CLI has a Vulkan device: VK_ICD_FILENAMES names an existing file (ctest points it
// at lavapipe for *_vk_test), or, with VK_ICD_FILENAMES unset or empty, `lpir-gseg devices`
// finds a usable device among the machine's drivers.
bool HasVulkanDevice();

}  // namespace lpir::test

// For tests that run Vulkan through the CLI (no VkTest fixture): skip without a Vulkan device.
#define LPIR_REQUIRE_VULKAN()                                                              \
  do {                                                                                     \
    if (!::lpir::test::HasVulkanDevice())                                                  \
      GTEST_SKIP() << "no Vulkan device (VK_ICD_FILENAMES, or none found by the loader); " \
                      "install mesa-vulkan-drivers for lavapipe";                          \
  } while (0)

// For tests that parse a JSON report with Python: skip, saying why, without python3 or its json.
#define LPIR_REQUIRE_PYTHON_JSON()                                                      \
  do {                                                                                  \
    if (::lpir::test::RunCommand("python3 -c 'import json'") != 0)                      \
      GTEST_SKIP() << "python3 with its json module not found: the JSON report is not " \
                      "parsed";                                                         \
  } while (0)

#define LPIR_REQUIRE_DATA(path)                                           \
  do {                                                                    \
    if (::lpir::test::DataFile(path).empty())                             \
      GTEST_SKIP() << "real scan " << (path) << " not found under "       \
                   << ::lpir::test::EnvOr("LPIR_DATA_DIR", LPIR_DATA_DIR) \
                   << " (../shared/data is absent on this machine)";      \
  } while (0)
