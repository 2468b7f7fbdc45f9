// Ground truth for the pictures: SemanticKITTI labels turned into 1 ground / 0 non-ground per
// point, as the DG protocol scores them.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace lpir {

// `gt` is a .label file, or a folder holding <stem>.label. IoError naming the file when it is
// missing or its count differs from `points`.
std::vector<uint8_t> LoadTruth(const std::string& gt, const std::string& stem, size_t points);

}  // namespace lpir
