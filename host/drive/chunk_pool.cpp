// The readers' default worker count (see chunk_pool.h).
#include "host/drive/chunk_pool.h"

#include <cstdlib>
#include <string>
#include <thread>

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

}  // namespace lpir
