// Byte comparison of two whole frames (every buffer of every stage, reference_cpu/frame.h), for
// the tests that run the full pipeline on both backends, or on one thread and on several. A
// mismatch names the stage, the buffer, the first differing element, both values in decimal and
// hex, and the point, pixel (u, v) or cell the element belongs to.
#pragma once
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>
#include <type_traits>
#include <vector>

#include "reference_cpu/cloud.h"
#include "reference_cpu/frame.h"
#include "reference_cpu/params.h"

namespace lpir::test {

template <typename T>
std::string ElementText(T value) {
  char text[64];
  uint32_t bits = 0;
  std::memcpy(&bits, &value, sizeof(T) < 4 ? sizeof(T) : 4);
  if constexpr (sizeof(T) == 4 && std::is_floating_point_v<T>)
    std::snprintf(text, sizeof(text), "%.9g (0x%08x)", double(value), bits);
  else if constexpr (std::is_signed_v<T>)
    std::snprintf(text, sizeof(text), "%d (0x%08x)", int(value), bits);
  else
    std::snprintf(text, sizeof(text), "%u (0x%0*x)", unsigned(value), int(2 * sizeof(T)), bits);
  return text;
}

// The two sides' names in a mismatch's message.
struct Sides {
  const char* first = "CPU";
  const char* second = "GPU";
};

// Compares one buffer; returns the number of bytes compared (0 on a size mismatch).
template <typename T>
uint64_t ExpectSameBuffer(const char* stage, const char* buffer, Per per, uint32_t stride,
                          const std::vector<T>& cpu, const std::vector<T>& gpu, const Params& p,
                          const Cloud* cloud, const std::string& what, Sides sides = Sides()) {
  EXPECT_EQ(gpu.size(), cpu.size()) << what << ": " << stage << " buffer " << buffer << " size";
  if (gpu.size() != cpu.size()) return 0;
  size_t first = cpu.size(), count = 0;
  for (size_t i = 0; i < cpu.size(); ++i)
    if (std::memcmp(&cpu[i], &gpu[i], sizeof(T)) != 0) {
      if (first == cpu.size()) first = i;
      ++count;
    }
  if (count != 0) {
    const size_t item = first / stride;
    std::string where;
    if (per == Per::kPixel) {
      where = "pixel (u " + std::to_string(item % p.width) + ", v " +
              std::to_string(item / p.width) + ")";
    } else if (per == Per::kCell) {
      where = "cell " + std::to_string(item) + " (word " + std::to_string(first % stride) + ")";
    } else {
      where = "point " + std::to_string(item);
      if (cloud && item < cloud->size())
        where += " (x " + ElementText(cloud->x(item)) + ", y " + ElementText(cloud->y(item)) +
                 ", z " + ElementText(cloud->z(item)) + ")";
    }
    ADD_FAILURE() << what << ": stage " << stage << ", buffer " << buffer << " differs first at "
                  << "element " << first << " (" << count << " of " << cpu.size()
                  << " differ): " << sides.first << " " << ElementText(cpu[first]) << ", "
                  << sides.second << " " << ElementText(gpu[first]) << "; " << where;
  }
  return uint64_t(cpu.size()) * sizeof(T);
}

// Every buffer of the two frames (ForEachBuffer: every table line's); returns the bytes compared.
inline uint64_t ExpectSameFrame(const Params& p, const Frame& cpu, const Frame& gpu,
                                const Cloud* cloud, const std::string& what,
                                Sides sides = Sides()) {
  EXPECT_EQ(gpu.n, cpu.n) << what << ": point count";
  uint64_t bytes = 0;
  ForEachBuffer(
      [&](const BufferInfo& info, const auto& a, const auto& b) {
        bytes += ExpectSameBuffer(info.stage, info.name, info.per, info.stride, a, b, p, cloud,
                                  what, sides);
      },
      cpu, gpu);
  return bytes;
}

}  // namespace lpir::test
