// Replaces the global operator new to record the largest single allocation, so a test can assert
// that a reader given a hostile header (a huge point count) did not allocate on its word.
// Include from exactly one file of a test executable.
#pragma once
#include <atomic>
#include <cstdlib>
#include <new>

namespace lpir::test {

inline std::atomic<size_t> g_largest_allocation{0};

// The largest allocation `run` made, in bytes.
template <typename F>
size_t LargestAllocationDuring(F&& run) {
  g_largest_allocation = 0;
  run();
  return g_largest_allocation.load();
}

}  // namespace lpir::test

// Every form of the unaligned operators is replaced together (std::stable_sort's buffer comes
// from the nothrow form and goes back through plain delete), so that each allocation and its
// release meet in malloc and free. noinline: GCC would otherwise see free() of a `new` pointer at
// each call site and warn.
namespace lpir::test {
inline void* TrackedAllocation(std::size_t size) noexcept {
  size_t largest = g_largest_allocation.load();
  while (size > largest && !g_largest_allocation.compare_exchange_weak(largest, size)) {
  }
  return std::malloc(size ? size : 1);
}
}  // namespace lpir::test
__attribute__((noinline)) void* operator new(std::size_t size) {
  if (void* p = lpir::test::TrackedAllocation(size)) return p;
  throw std::bad_alloc();
}
__attribute__((noinline)) void* operator new[](std::size_t size) {
  if (void* p = lpir::test::TrackedAllocation(size)) return p;
  throw std::bad_alloc();
}
__attribute__((noinline)) void* operator new(std::size_t size, const std::nothrow_t&) noexcept {
  return lpir::test::TrackedAllocation(size);
}
__attribute__((noinline)) void* operator new[](std::size_t size, const std::nothrow_t&) noexcept {
  return lpir::test::TrackedAllocation(size);
}
__attribute__((noinline)) void operator delete(void* p) noexcept { std::free(p); }
__attribute__((noinline)) void operator delete(void* p, std::size_t) noexcept { std::free(p); }
__attribute__((noinline)) void operator delete[](void* p) noexcept { std::free(p); }
__attribute__((noinline)) void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
__attribute__((noinline)) void operator delete(void* p, const std::nothrow_t&) noexcept {
  std::free(p);
}
__attribute__((noinline)) void operator delete[](void* p, const std::nothrow_t&) noexcept {
  std::free(p);
}
