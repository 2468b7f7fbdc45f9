// A command's help text with the cloud formats filled in from their table (host/io/cloud_file.h),
// so that no help text lists them itself: "{clouds}" becomes ".bin (KITTI), .pcd, .ply",
// "{writable clouds}" the --format names of the formats with a writer, "pcd, ply".
#pragma once
#include <string>

#include "host/io/cloud_file.h"

namespace lpir {

inline std::string HelpText(const char* text) {
  std::string help = text;
  const std::pair<std::string, std::string> fills[] = {
      {"{clouds}", CloudFormatList()}, {"{writable clouds}", CloudFormatList(true)}};
  for (const auto& [token, value] : fills)
    for (size_t at = help.find(token); at != std::string::npos; at = help.find(token, at))
      help.replace(at, token.size(), value);
  return help;
}

}  // namespace lpir
