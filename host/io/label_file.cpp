// SemanticKITTI .label files: one little-endian uint32 per point.
#include "host/io/label_file.h"

#include <cstring>

#include "host/io/file_bytes.h"
#include "host/io/io_error.h"

namespace lpir {

std::vector<uint32_t> ReadLabelFile(const std::string& path, size_t expected_points) {
  const std::vector<char> bytes = ReadFileBytes(path);
  if (bytes.empty()) throw IoError(path, "empty file");
  if (bytes.size() % sizeof(uint32_t) != 0) {
    throw IoError(path, "size " + std::to_string(bytes.size()) +
                            " bytes is not a whole number of 4-byte labels");
  }
  const size_t n = bytes.size() / sizeof(uint32_t);
  if (expected_points > 0 && n != expected_points) {
    throw IoError(path, "holds " + std::to_string(n) + " labels but the cloud has " +
                            std::to_string(expected_points) + " points");
  }
  std::vector<uint32_t> labels(n);
  std::memcpy(labels.data(), bytes.data(), bytes.size());
  return labels;
}

void WriteLabelFile(const std::string& path, const std::vector<uint32_t>& labels) {
  WriteFileBytes(path, labels.data(), labels.size() * sizeof(uint32_t));
}

}  // namespace lpir
