#include "tests/test_util.h"

#include <sys/wait.h>

#include <array>
#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <unistd.h>

namespace fs = std::filesystem;

namespace lpir::test {

std::string DataDir() {
  std::error_code ec;
  return fs::is_directory(LPIR_DATA_DIR, ec) ? std::string(LPIR_DATA_DIR) : std::string();
}

std::string DataFile(const std::string& relative) {
  std::string dir = DataDir();
  if (dir.empty()) return "";
  std::string path = dir + "/" + relative;
  std::error_code ec;
  return fs::exists(path, ec) ? path : std::string();
}

std::string SensorsDir() { return LPIR_SENSORS_DIR; }
std::string CliPath() { return LPIR_CLI; }

std::string TempDir() {
  static std::atomic<int> counter{0};
  fs::path p = fs::temp_directory_path() /
               ("lpir_test_" + std::to_string(::getpid()) + "_" + std::to_string(counter++));
  fs::remove_all(p);
  fs::create_directories(p);
  return p.string();
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

bool HasLavapipe() {
  const char* icd = std::getenv("VK_ICD_FILENAMES");
  std::error_code ec;
  return icd && fs::exists(icd, ec);
}

}  // namespace lpir::test
