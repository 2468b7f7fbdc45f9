// Where a run's outputs go: the one rule of `lpir-gseg segment` (every --format), the fleet and
// the Python helpers, so that no output of a run overwrites another (docs/decisions/outputs.md).
// An input's output is the output folder joined with the input's path below the folder it was
// listed from (its own name when it was given itself), the last extension replaced; a run in
// which two inputs would write the same output is refused before anything is written.
#pragma once
#include <string>
#include <vector>

namespace lpir {

// One input of a run.
struct RunInput {
  std::string path;    // the file or drive as listed: "kitti/00/velodyne/000000.bin"
  std::string folder;  // the folder given that it was found in ("kitti"); "" when given itself
  bool drive = false;  // a recorded drive: its output is a folder (its labels and index.csv)
};

// The name a drive's outputs take (its folder among several inputs, its whole copy with
// --format mcap|bag): a drive file's name without its extension, `.bag.active` (what a ROS 1
// recorder writes until it closes the bag) taken whole ("run.bag.active" -> "run"); a folder's
// (a ROS 2 bag's) name, trailing separators ignored.
std::string DriveStem(const std::string& path);

// The output of `input` in `out_dir`: out_dir/<input.path below input.folder, or its file name>
// with the last extension replaced by `extension` (".label", ".pcd"); for a drive, its name
// replaced by its DriveStem: the folder its messages' labels and index.csv go to.
// ("a/000000.bin" given itself, ".label" -> "out/000000.label"; "kitti/00/velodyne/000000.bin"
// found in "kitti" -> "out/00/velodyne/000000.label"; "d/r/run.bag.active" found in "d" ->
// "out/r/run".)
std::string OutputPath(const RunInput& input, const std::string& out_dir,
                       const std::string& extension);

// OutputPath of every input, in order. std::invalid_argument, naming both inputs and the output,
// when two inputs would write the same output or one's output lies inside a drive's folder
// ("a/000000.bin and b/000000.bin would both write out/000000.label"), when a file is listed
// twice, or when an output is one of the inputs; the caller has written nothing then.
std::vector<std::string> OutputPaths(const std::vector<RunInput>& inputs,
                                     const std::string& out_dir, const std::string& extension);

// Checks, making nothing, that `dir` is a folder or can be made one: IoError naming it when it is
// a file ("is a file, not a folder") or when a file stands where one of its parents would be.
void CheckOutputFolder(const std::string& dir);

// Makes `dir` and its missing parents (nothing when it is a folder already); IoError naming it
// and why when it cannot be made.
void MakeOutputFolder(const std::string& dir);

}  // namespace lpir
