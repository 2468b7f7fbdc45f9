#include "host/io/output_paths.h"

#include <filesystem>
#include <map>
#include <stdexcept>

#include "host/io/io_error.h"

namespace lpir {
namespace {

namespace fs = std::filesystem;

// The path as the file system resolves it (symbolic links, "..", "."), for telling one file
// named two ways from two files.
std::string Resolved(const std::string& path) {
  std::error_code ec;
  const fs::path p = fs::weakly_canonical(path, ec);
  return ec ? fs::path(path).lexically_normal().string() : p.string();
}

// `path` without trailing separators ("bag/" -> "bag").
fs::path Trimmed(const std::string& path) {
  fs::path p(path);
  while (p.has_relative_path() && p.filename().empty()) p = p.parent_path();
  return p;
}

}  // namespace

std::string DriveStem(const std::string& path) {
  const fs::path p = Trimmed(path);
  std::error_code ec;
  if (fs::is_directory(p, ec)) return p.filename().string();
  const fs::path stem = p.stem();
  return p.extension() == ".active" && stem.extension() == ".bag" ? stem.stem().string()
                                                                  : stem.string();
}

std::string OutputPath(const RunInput& input, const std::string& out_dir,
                       const std::string& extension) {
  const fs::path path = Trimmed(input.path);
  fs::path below = input.folder.empty() ? path.filename() : path.lexically_relative(input.folder);
  if (below.empty() || *below.begin() == "..") below = path.filename();  // not inside its folder
  if (input.drive)
    below.replace_filename(DriveStem(input.path));
  else
    below.replace_extension(extension);
  return (fs::path(out_dir) / below).lexically_normal().string();
}

std::vector<std::string> OutputPaths(const std::vector<RunInput>& inputs,
                                     const std::string& out_dir, const std::string& extension) {
  std::vector<std::string> outputs;
  std::map<std::string, size_t> by_output;  // output -> the input writing it
  std::map<std::string, size_t> by_input;   // resolved input -> its index
  for (size_t i = 0; i < inputs.size(); ++i) {
    const RunInput& in = inputs[i];
    const auto [twice, fresh] = by_input.emplace(Resolved(in.path), i);
    if (!fresh)
      throw std::invalid_argument(in.path + " is listed twice (also as " +
                                  inputs[twice->second].path + "): each input once, please");
    outputs.push_back(OutputPath(in, out_dir, extension));
    const auto [same, unique] = by_output.emplace(outputs.back(), i);
    if (!unique)
      throw std::invalid_argument(inputs[same->second].path + " and " + in.path +
                                  " would both write " + outputs.back());
  }
  for (size_t i = 0; i < inputs.size(); ++i) {
    const auto input = by_input.find(Resolved(outputs[i]));
    if (input != by_input.end())
      throw std::invalid_argument(outputs[i] + ", the output of " + inputs[i].path +
                                  ", is the input " + inputs[input->second].path +
                                  ": writing it would overwrite the input");
    // an output inside a drive's folder, where that drive writes its labels and index.csv
    for (fs::path up = fs::path(outputs[i]).parent_path(); !up.empty() && up != up.parent_path();
         up = up.parent_path()) {
      const auto holder = by_output.find(up.string());
      if (holder != by_output.end() && inputs[holder->second].drive)
        throw std::invalid_argument(inputs[holder->second].path + " and " + inputs[i].path +
                                    " would both write into " + up.string());
    }
  }
  return outputs;
}

void CheckOutputFolder(const std::string& dir) {
  std::error_code ec;
  if (fs::is_directory(dir, ec)) return;
  if (fs::exists(dir, ec))
    throw IoError(dir, "is a file, not a folder: the outputs go into a folder (made when missing)");
  for (fs::path up = fs::path(dir).lexically_normal().parent_path(); !up.empty();
       up = up.parent_path()) {
    if (fs::is_directory(up, ec)) return;
    if (fs::exists(up, ec))
      throw IoError(dir, "cannot be made: " + up.string() + " is a file, not a folder");
    if (up == up.parent_path()) return;
  }
}

void MakeOutputFolder(const std::string& dir) {
  CheckOutputFolder(dir);
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec || !fs::is_directory(dir, ec))
    throw IoError(dir, "cannot make the folder" + (ec ? ": " + ec.message() : std::string()));
}

}  // namespace lpir
