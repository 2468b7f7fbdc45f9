// The threads a frame's stages may share, and how a stage splits its work over them (OpenMP).
// A stage splits its work into pieces: consecutive ranges of points, pixels, rows, cells or runs
// that only one thread writes. What the pieces add up (counts, minima and maxima of integer keys,
// integer sums) is merged with integer operations whose result does not depend on their order, and
// ties keep the lowest index, so every stage writes the same bytes at any thread count
// (docs/decisions/threads.md). With one thread a stage runs its one piece, the whole range, on the
// calling thread without OpenMP: the reference's own loop.
#pragma once
#include <algorithm>
#include <cstdint>

#include "reference_cpu/wide.h"

namespace lpir {

// How many threads a stage may use (at least 1).
struct Threads {
  uint32_t count = 1;
};

// A range [begin, end) of items.
struct Range {
  uint32_t begin = 0, end = 0;
};

// Piece k of `pieces` near-equal consecutive pieces of [0, n).
inline Range PieceOf(uint32_t n, uint32_t pieces, uint32_t k) {
  return {uint32_t(uint64_t(n) * k / pieces), uint32_t(uint64_t(n) * (k + 1) / pieces)};
}

// The pieces to split n items into: one per thread, but none smaller than `min_items` (a piece
// costs a few microseconds to hand out), and at least one.
inline uint32_t PiecesFor(Threads threads, uint32_t n, uint32_t min_items) {
  const uint32_t most = std::max<uint32_t>(n / std::max<uint32_t>(min_items, 1), 1);
  return std::max<uint32_t>(std::min(threads.count, most), 1);
}

// Calls fn(k, PieceOf(n, pieces, k)) for k = 0 .. pieces - 1 and returns when all have returned:
// with one thread or one piece in order on the calling thread, else on up to threads.count OpenMP
// threads; each call in the AVX2 build of fn where the CPU has AVX2 (RunWide). fn must not throw
// (an exception cannot leave an OpenMP region).
template <typename Fn>
void ForPieces(Threads threads, uint32_t pieces, uint32_t n, Fn&& fn) {
  auto piece = [&](uint32_t k) { RunWide([&] { fn(k, PieceOf(n, pieces, k)); }); };
  if (threads.count <= 1 || pieces <= 1) {
    for (uint32_t k = 0; k < pieces; ++k) piece(k);
    return;
  }
#pragma omp parallel for num_threads(threads.count) schedule(static, 1)
  for (uint32_t k = 0; k < pieces; ++k) piece(k);
}

}  // namespace lpir
