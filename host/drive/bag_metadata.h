// What this reader takes from a ROS 2 bag folder's metadata.yaml (rosbag2_bagfile_information,
// every version from Foxy's 4 to Jazzy's 9): the storage, the files in their order, how
// rosbag2 compressed them, and each topic's message count.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace lpir {

struct BagMetadata {
  std::string storage_identifier;                // "mcap", "sqlite3" ("" when not given)
  std::vector<std::string> relative_file_paths;  // in the order the bag was written
  std::string compression_format;                // "" (none), "zstd", ...
  std::string compression_mode;                  // "" / "NONE", "FILE", "MESSAGE"
  struct Topic {
    std::string name, type, serialization_format;
    uint64_t messages = 0;
  };
  std::vector<Topic> topics;  // topics_with_message_count
};

// metadata.yaml's text read into a BagMetadata. YamlError ("line N: problem") when the text is
// outside mini_yaml.h's subset, has no rosbag2_bagfile_information mapping, lists no
// relative_file_paths, or holds a field of the wrong kind (a count that is no whole number).
BagMetadata ParseBagMetadata(const std::string& text);

}  // namespace lpir
