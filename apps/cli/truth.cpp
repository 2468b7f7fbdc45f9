#include "apps/cli/truth.h"

#include <filesystem>

#include "host/eval/metrics.h"
#include "host/io/label_file.h"

namespace lpir {

std::vector<uint8_t> LoadTruth(const std::string& gt, const std::string& stem, size_t points) {
  std::error_code ec;
  const std::string path = std::filesystem::is_directory(gt, ec)
                               ? (std::filesystem::path(gt) / (stem + ".label")).string()
                               : gt;
  const std::vector<uint32_t> labels = ReadLabelFile(path, points);
  std::vector<uint8_t> truth(labels.size());
  for (size_t i = 0; i < labels.size(); ++i) truth[i] = IsGroundClass(labels[i]) ? 1 : 0;
  return truth;
}

}  // namespace lpir
