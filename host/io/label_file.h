// SemanticKITTI .label: little-endian uint32 per point; class = value & 0xFFFF, instance = >> 16.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace lpir {

// IoError (naming the file) when missing, empty, not a whole number of uint32, or, when
// expected_points > 0, holding a different count (the message gives both counts).
std::vector<uint32_t> ReadLabelFile(const std::string& path, size_t expected_points = 0);
void WriteLabelFile(const std::string& path, const std::vector<uint32_t>& labels);

}  // namespace lpir
