#include "tests/test_util.h"

#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>

namespace fs = std::filesystem;

namespace lpir::test {

std::string EnvOr(const char* name, const char* fallback) {
  const char* value = std::getenv(name);
  return value && *value ? std::string(value) : std::string(fallback);
}

std::string DataDir() {
  const std::string dir = EnvOr("LPIR_DATA_DIR", LPIR_DATA_DIR);
  std::error_code ec;
  return fs::is_directory(dir, ec) ? dir : std::string();
}

std::string DataFile(const std::string& relative) {
  std::string dir = DataDir();
  if (dir.empty()) return "";
  std::string path = dir + "/" + relative;
  std::error_code ec;
  return fs::exists(path, ec) ? path : std::string();
}

std::string SensorsDir() { return EnvOr("LPIR_SENSORS_DIR", LPIR_SENSORS_DIR); }
std::string CliPath() { return EnvOr("LPIR_CLI", LPIR_CLI); }

std::string TempDir() {
  static std::atomic<int> counter{0};
  fs::path p = fs::temp_directory_path() /
               ("lpir_test_" + std::to_string(::getpid()) + "_" + std::to_string(counter++));
  fs::remove_all(p);
  fs::create_directories(p);
  return p.string();
}

ScopedDir::~ScopedDir() {
  std::error_code ec;
  fs::remove_all(path, ec);
}

int RunCommand(const std::string& command, std::string* output) {
  std::string cmd = command + " 2>&1";
  FILE* pipe = ::popen(cmd.c_str(), "r");
  if (!pipe) return -1;
  std::array<char, 4096> buf;
  std::string out;
  size_t n;
  while ((n = std::fread(buf.data(), 1, buf.size(), pipe)) > 0) out.append(buf.data(), n);
  int status = ::pclose(pipe);
  if (output) *output = out;
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

std::string ReadFileBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

bool HasVulkanDevice() {
  const char* icd = std::getenv("VK_ICD_FILENAMES");
  std::error_code ec;
  if (icd && *icd) return fs::exists(icd, ec);
  // The loader's own search (the machine's drivers): asked once, of the CLI the tests run.
  static const bool found = RunCommand(CliPath() + " devices >/dev/null") == 0;
  return found;
}

}  // namespace lpir::test
