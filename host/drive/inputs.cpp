#include "host/drive/inputs.h"

#include <algorithm>
#include <filesystem>
#include <stdexcept>

#include "host/drive/bag_folder.h"
#include "host/drive/drive.h"
#include "host/io/cloud_file.h"

namespace fs = std::filesystem;

namespace lpir {
namespace {

// The inputs in `folder` (found in `given`) appended to *found in path order, descending into
// the subfolders that are no bag when `recursive`; the entries passed over to *skipped (when not
// null).
void ListFolder(const fs::path& folder, const std::string& given, bool recursive,
                std::vector<RunInput>* found, std::vector<SkippedInput>* skipped) {
  std::error_code ec;
  std::vector<fs::path> entries;
  for (fs::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec))
    entries.push_back(it->path());
  std::sort(entries.begin(), entries.end());
  for (const fs::path& entry : entries) {
    const std::string path = entry.string();
    const bool is_folder = fs::is_directory(entry, ec);
    const bool is_file = !is_folder && fs::is_regular_file(entry, ec);
    if (is_folder && IsBagFolder(path)) {
      found->push_back({path, given, true});
    } else if (is_folder && recursive && !fs::is_symlink(entry, ec)) {
      ListFolder(entry, given, true, found, skipped);
    } else if (is_file && (IsDriveFile(path) || IsCloudFile(path))) {
      found->push_back({path, given, IsDriveFile(path)});
    } else if (skipped) {
      skipped->push_back(SkippedInput{
          path, is_folder ? recursive ? "a link to a folder, not followed"
                                      : "a folder that is no ROS 2 bag (no metadata.yaml; "
                                        "--recursive walks it)"
                          : "neither a cloud file (" + CloudFormatList() +
                                ") nor a recorded drive (.mcap, .db3, .bag, .bag.active)"});
    }
  }
}

}  // namespace

std::vector<RunInput> ListInputs(const std::vector<std::string>& given, bool recursive,
                                 std::vector<SkippedInput>* skipped) {
  std::vector<RunInput> inputs;
  for (const std::string& in : given) {
    std::error_code ec;
    if (!fs::is_directory(in, ec)) {
      inputs.push_back({in, "", IsDriveFile(in)});
      continue;
    }
    if (IsBagFolder(in)) {
      inputs.push_back({in, "", true});
      continue;
    }
    std::vector<RunInput> found;
    ListFolder(in, in, recursive, &found, skipped);
    if (found.empty()) {
      std::vector<RunInput> below;
      if (!recursive) ListFolder(in, in, true, &below, nullptr);
      throw std::invalid_argument(
          in + ": folder holds no cloud files or drives" +
          (below.empty() ? ""
                         : ", but its subfolders hold " + std::to_string(below.size()) +
                               ": --recursive (-r) segments them, each to its path below the "
                               "folder"));
    }
    inputs.insert(inputs.end(), found.begin(), found.end());
  }
  return inputs;
}

}  // namespace lpir
