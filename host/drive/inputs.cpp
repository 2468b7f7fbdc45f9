#include "host/drive/inputs.h"

#include <algorithm>
#include <filesystem>
#include <stdexcept>

#include "host/drive/bag_folder.h"
#include "host/drive/drive.h"
#include "host/io/cloud_file.h"

namespace fs = std::filesystem;

namespace lpir {

std::vector<Input> ListInputs(const std::vector<std::string>& given,
                              std::vector<SkippedInput>* skipped) {
  std::vector<Input> inputs;
  for (const std::string& in : given) {
    std::error_code ec;
    if (!fs::is_directory(in, ec)) {
      inputs.push_back(Input{in, IsDriveFile(in)});
      continue;
    }
    if (IsBagFolder(in)) {
      inputs.push_back(Input{in, true});
      continue;
    }
    std::vector<fs::path> entries;
    for (const auto& entry : fs::directory_iterator(in, ec)) entries.push_back(entry.path());
    std::sort(entries.begin(), entries.end());
    size_t found = 0;
    for (const fs::path& entry : entries) {
      const std::string path = entry.string();
      const bool folder = fs::is_directory(entry, ec);
      if (folder ? IsBagFolder(path) : fs::is_regular_file(entry, ec) && IsDriveFile(path)) {
        inputs.push_back(Input{path, true});
        ++found;
      } else if (!folder && fs::is_regular_file(entry, ec) && IsCloudFile(path)) {
        inputs.push_back(Input{path, false});
        ++found;
      } else if (skipped) {
        skipped->push_back(SkippedInput{
            path, folder ? "a folder that is no ROS 2 bag (no metadata.yaml)"
                         : "neither a cloud file (.bin, .pcd, .ply) nor a recorded drive (.mcap, "
                           ".db3, .bag, .bag.active)"});
      }
    }
    if (!found) throw std::invalid_argument(in + ": folder holds no cloud files or drives");
  }
  return inputs;
}

}  // namespace lpir
