// What every fuzz target shares: the readers take file paths, so FuzzFile holds an in-memory file
// (memfd, no disk I/O, nothing left behind) whose bytes are replaced per input and whose path,
// /proc/self/fd/N, any reader or writer can open; and LPIR_FUZZ_CHECK, which aborts (a finding
// for libFuzzer) when a property of a successful read does not hold.
#pragma once
#include <sys/mman.h>
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#define LPIR_FUZZ_CHECK(condition)                                                       \
  do {                                                                                   \
    if (!(condition)) {                                                                  \
      std::fprintf(stderr, "%s:%d: check failed: %s\n", __FILE__, __LINE__, #condition); \
      std::abort();                                                                      \
    }                                                                                    \
  } while (0)

namespace lpir::fuzz {

class FuzzFile {
 public:
  FuzzFile() : fd_(memfd_create("lpir_fuzz", 0)) {
    if (fd_ < 0) {
      std::perror("memfd_create");
      std::abort();
    }
    path_ = "/proc/self/fd/" + std::to_string(fd_);
  }
  ~FuzzFile() { close(fd_); }
  FuzzFile(const FuzzFile&) = delete;
  FuzzFile& operator=(const FuzzFile&) = delete;

  // Replaces the file's contents with `size` bytes.
  void Write(const uint8_t* data, size_t size) {
    LPIR_FUZZ_CHECK(ftruncate(fd_, 0) == 0);
    size_t done = 0;
    while (done < size) {
      const ssize_t n = pwrite(fd_, data + done, size - done, off_t(done));
      LPIR_FUZZ_CHECK(n > 0);
      done += size_t(n);
    }
  }
  const std::string& path() const { return path_; }

 private:
  int fd_;
  std::string path_;
};

}  // namespace lpir::fuzz
