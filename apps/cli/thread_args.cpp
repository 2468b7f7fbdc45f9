#include "apps/cli/thread_args.h"

#include <stdexcept>
#include <string>

namespace lpir {

uint32_t ParseThreads(const Args& args) {
  if (!args.Has("--threads")) return 0;
  const double n = args.GetNumber("--threads", 0);
  if (!(n >= 1 && n <= kMaxThreads) || n != double(uint32_t(n)))
    throw std::invalid_argument("--threads must be a whole number from 1 to " +
                                std::to_string(kMaxThreads));
  return uint32_t(n);
}

}  // namespace lpir
