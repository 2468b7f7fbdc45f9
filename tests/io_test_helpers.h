// Helpers for the file-format tests: writing raw test files, sample clouds, bit-exact comparison,
// and checking that a reader throws an IoError that names the file and the problem.
#pragma once
#include <gtest/gtest.h>

#include <cstring>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include "host/io/io_error.h"
#include "reference_cpu/cloud.h"

namespace lpir::test {

inline void WriteRaw(const std::string& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), std::streamsize(bytes.size()));
  ASSERT_TRUE(out.good()) << "cannot write " << path;
}

inline std::string ReadRaw(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// The bytes of `values` as stored little-endian.
template <typename T>
std::string Bytes(std::initializer_list<T> values) {
  std::string out;
  for (T v : values) out.append(reinterpret_cast<const char*>(&v), sizeof(T));
  return out;
}

// A cloud whose floats exercise exact round trips: negatives, tiny and large magnitudes, values
// with no short decimal form.
inline Cloud SampleCloud(size_t n, bool with_ring) {
  Cloud cloud;
  for (size_t i = 0; i < n; ++i) {
    const float f = static_cast<float>(i);
    cloud.Push(0.1f * f - 7.3f, -1.0f / (f + 3.0f), 1e-7f * f + 123456.789f, 0.3f * f);
    if (with_ring) cloud.ring.push_back(static_cast<int32_t>(i % 64));
  }
  return cloud;
}

// True when both clouds hold the same bits (floats compared as bytes, NaN payloads included).
inline ::testing::AssertionResult SameBits(const Cloud& a, const Cloud& b) {
  if (a.xyzi.size() != b.xyzi.size()) {
    return ::testing::AssertionFailure() << "sizes " << a.size() << " vs " << b.size();
  }
  if (std::memcmp(a.xyzi.data(), b.xyzi.data(), a.xyzi.size() * sizeof(float)) != 0) {
    return ::testing::AssertionFailure() << "xyzi bytes differ";
  }
  if (a.ring != b.ring) return ::testing::AssertionFailure() << "rings differ";
  return ::testing::AssertionSuccess();
}

// Succeeds when `read` throws an IoError whose message contains `path` and every one of `words`.
inline ::testing::AssertionResult ThrowsIoError(const std::function<void()>& read,
                                                const std::string& path,
                                                const std::vector<std::string>& words) {
  try {
    read();
  } catch (const IoError& e) {
    const std::string message = e.what();
    if (message.find(path) == std::string::npos) {
      return ::testing::AssertionFailure() << "message does not name " << path << ": " << message;
    }
    for (const std::string& word : words) {
      if (message.find(word) == std::string::npos) {
        return ::testing::AssertionFailure() << "message lacks '" << word << "': " << message;
      }
    }
    return ::testing::AssertionSuccess() << message;
  } catch (const std::exception& e) {
    return ::testing::AssertionFailure() << "threw a non-IoError: " << e.what();
  }
  return ::testing::AssertionFailure() << "no exception";
}

// Succeeds when `read` either returns or throws IoError (what a fuzzed input may do); a crash or
// any other exception fails.
inline ::testing::AssertionResult ReturnsOrThrowsIoError(const std::function<void()>& read) {
  try {
    read();
  } catch (const IoError&) {
  } catch (const std::exception& e) {
    return ::testing::AssertionFailure() << "threw a non-IoError: " << e.what();
  }
  return ::testing::AssertionSuccess();
}

}  // namespace lpir::test
