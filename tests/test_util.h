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

}  // namespace lpir::test

#define LPIR_REQUIRE_DATA(path)                                                             \
  do {                                                                                      \
    if (::lpir::test::DataFile(path).empty())                                               \
      GTEST_SKIP() << "real scan " << (path) << " not found under " LPIR_DATA_DIR           \
                   << " (../shared/data is absent on this machine)";                        \
  } while (0)
