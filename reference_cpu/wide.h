// Every piece of every stage (ForPieces, reference_cpu/threads.h) in two builds on x86-64, chosen
// at run time: the baseline's (SSE2, which every x86-64 CPU has) and one for CPUs with AVX2
// (vectors twice as wide), so that one binary runs on any x86-64 machine and uses the wider vectors
// where the CPU has them (docs/decisions/wide.md). The two write the same bytes: the project
// compiles with -ffp-contract=off and without fast-math, so every float operation is IEEE's,
// rounded alike in any vector width (no FMA: the AVX2 build does not enable it), and integer
// operations are exact. Off x86-64 there is one build.
#pragma once

namespace lpir {

// True when the AVX2 build runs: the CPU has AVX2 and the system saves its registers (GCC's
// __builtin_cpu_supports), and SetWideKernels has not turned it off. False off x86-64.
bool WideKernels();

// Turns the AVX2 build off (false: the baseline's runs everywhere) or back on (true, where the CPU
// has AVX2). For the tests that compare the two builds byte for byte; not thread-safe against
// stages running at the time.
void SetWideKernels(bool on);

#if defined(__x86_64__)
// fn() compiled into this function for AVX2: flatten inlines every call inside it where it can (fn,
// and what fn calls, recursively), and the target attribute makes all that code AVX2's. What it
// cannot inline (the C library, out-of-line standard library code) stays the baseline's, so no
// AVX2 code is shared with the baseline build.
template <typename Fn>
[[gnu::flatten, gnu::target("avx2")]] void RunAvx2(Fn& fn) {
  fn();
}
#endif

// fn() in the AVX2 build when WideKernels(), else as compiled (the baseline's).
template <typename Fn>
void RunWide(Fn&& fn) {
#if defined(__x86_64__)
  if (WideKernels()) return RunAvx2(fn);
#endif
  fn();
}

}  // namespace lpir
