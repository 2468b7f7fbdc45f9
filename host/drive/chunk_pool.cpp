// The readers' default worker count and chunk range check (see chunk_pool.h).
#include "host/drive/chunk_pool.h"

#include <cstdlib>
#include <string>
#include <thread>

#include "host/io/io_error.h"

namespace lpir {

unsigned DefaultReadThreads() {
  const char* env = std::getenv("LPIR_READ_THREADS");
  if (env && *env) {
    char* end = nullptr;
    const unsigned long n = std::strtoul(env, &end, 10);
    if (*end == '\0' && n >= 1 && n <= kMaxReadThreads) return unsigned(n);
  }
  const unsigned hw = std::thread::hardware_concurrency();
  return hw < 1 ? 1 : hw > kDefaultReadThreadsCap ? kDefaultReadThreadsCap : hw;
}

unsigned ReadThreads(unsigned threads) {
  return threads >= 1 && threads <= kMaxReadThreads ? threads : DefaultReadThreads();
}

void CheckChunkRange(const std::string& path, const char* kind, uint64_t first, uint64_t last,
                     uint64_t count) {
  if (first < 1 || first > last || last > count) {
    throw IoError(path, "no chunks " + std::to_string(first) + " to " + std::to_string(last) +
                            ": the " + kind + " has " + std::to_string(count) +
                            " (numbered from 1)");
  }
}

}  // namespace lpir
