// --threads N, for every command that segments: the CPU backend's threads
// (SegmenterOptions::threads).
#pragma once
#include <cstdint>

#include "apps/cli/args.h"

namespace lpir {

// The most --threads takes (SegmenterOptions::threads' limit).
constexpr uint32_t kMaxThreads = 1024;

// --threads as SegmenterOptions::threads: 0 (every core this process may run on) when absent;
// std::invalid_argument unless a whole number from 1 to kMaxThreads.
uint32_t ParseThreads(const Args& args);

}  // namespace lpir
