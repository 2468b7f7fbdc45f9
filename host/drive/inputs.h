// What segment, topics and the fleet (through lpir_gseg) take as inputs: cloud files and
// recorded drives, given as files and folders. One rule for all of them.
#pragma once
#include <string>
#include <vector>

namespace lpir {

struct Input {
  std::string path;
  bool drive = false;  // a recorded drive (IsDrive: a drive file or a ROS 2 bag folder)
};

// An entry of a folder that ListInputs passed over, and why.
struct SkippedInput {
  std::string path, why;
};

// The inputs `given` names, in order: a ROS 2 bag folder (IsBagFolder) is one drive; any other
// folder gives its cloud files (IsCloudFile), drive files (IsDriveFile) and bag folders in name
// order, every other entry of it going to *skipped with the reason; any other path is itself, a
// drive when IsDriveFile, else a cloud file (a missing one is reported when it is read).
// std::invalid_argument naming a folder that gives no input.
std::vector<Input> ListInputs(const std::vector<std::string>& given,
                              std::vector<SkippedInput>* skipped);

}  // namespace lpir
