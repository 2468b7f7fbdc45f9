// The part of YAML that rosbag2's metadata.yaml is written in, read into a tree: block mappings
// and sequences (a sequence under a key indented or not, an item holding a mapping, "- key: v"),
// plain, single- and double-quoted scalars over one line or several (the escapes of YAML 1.2,
// an escaped line break, folding), literal and folded block scalars (| and >), the empty flow
// collections [] and {} and one-line flow sequences of scalars ([a, 'b']), comments, a leading
// "---". This is what yaml-cpp (rosbag2's writer, Foxy to Jazzy) and PyYAML's safe_dump write
// for it. Anything else (anchors, aliases, tags, flow mappings with content, tabs in the
// indentation, a key given twice) is a YamlError naming the line: the caller falls back rather
// than guess.
#pragma once
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace lpir {

class YamlError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct YamlNode {
  enum class Kind { kNull, kScalar, kMap, kSeq };
  Kind kind = Kind::kNull;
  std::string scalar;                                 // kScalar: its text, unquoted
  std::vector<std::pair<std::string, YamlNode>> map;  // kMap: in file order
  std::vector<YamlNode> seq;                          // kSeq
  int line = 0;                                       // where it starts (1-based)

  // The value under `key` of a mapping, or null when this is no mapping or has no such key.
  const YamlNode* Get(const std::string& key) const;
};

// The document in `text`. YamlError("line N: problem") for anything outside the subset above;
// nesting deeper than 64 levels is an error too.
YamlNode ParseYaml(const std::string& text);

}  // namespace lpir
