// What segment, topics and the fleet (through lpir_gseg) take as inputs: cloud files and
// recorded drives, given as files and folders. One rule for all of them.
#pragma once
#include <string>
#include <vector>

#include "host/io/output_paths.h"

namespace lpir {

// An entry of a folder that ListInputs passed over, and why.
struct SkippedInput {
  std::string path, why;
};

// The inputs `given` names, in order, each with the folder given that it was found in
// (RunInput, for OutputPaths): a ROS 2 bag folder (IsBagFolder) is one drive; any other folder
// gives its cloud files (IsCloudFile), drive files (IsDriveFile) and bag folders in path order,
// and with `recursive` those of its subfolders too (not following links to folders), every other
// entry of it going to *skipped with the reason; any other path is itself, a drive when
// IsDriveFile, else a cloud file (a missing one is reported when it is read).
// std::invalid_argument naming a folder that gives no input, saying so when its subfolders hold
// some and `recursive` was not asked for.
std::vector<RunInput> ListInputs(const std::vector<std::string>& given, bool recursive,
                                 std::vector<SkippedInput>* skipped);

}  // namespace lpir
