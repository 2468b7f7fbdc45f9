#include "reference_cpu/wide.h"

#include <atomic>

namespace lpir {
namespace {

bool CpuHasAvx2() {
#if defined(__x86_64__)
  __builtin_cpu_init();
  return __builtin_cpu_supports("avx2");
#else
  return false;
#endif
}

std::atomic<bool>& WideFlag() {
  static std::atomic<bool> on{CpuHasAvx2()};
  return on;
}

}  // namespace

bool WideKernels() { return WideFlag().load(std::memory_order_relaxed); }

void SetWideKernels(bool on) { WideFlag().store(on && CpuHasAvx2(), std::memory_order_relaxed); }

}  // namespace lpir
