// Fuzz target of a ROS 2 bag folder's metadata.yaml reader (host/drive/bag_metadata.h over
// mini_yaml.h). Any bytes either throw YamlError or give metadata that keeps the reader's
// promises: at least one file, no empty file name, every topic counted. The tree ParseYaml gives
// for them holds only the node kinds it names, each with its line.
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz/fuzz_file.h"
#include "host/drive/bag_metadata.h"
#include "host/drive/mini_yaml.h"

namespace {

// Walks the tree (at most as deep as the reader lets it be), checking each node's kind and line.
size_t Nodes(const lpir::YamlNode& n, int depth) {
  LPIR_FUZZ_CHECK(depth <= 70 && n.line >= 0);
  size_t count = 1;
  switch (n.kind) {
    case lpir::YamlNode::Kind::kNull:
    case lpir::YamlNode::Kind::kScalar:
      LPIR_FUZZ_CHECK(n.map.empty() && n.seq.empty());
      break;
    case lpir::YamlNode::Kind::kMap:
      LPIR_FUZZ_CHECK(n.seq.empty());
      for (const auto& entry : n.map) count += Nodes(entry.second, depth + 1);
      break;
    case lpir::YamlNode::Kind::kSeq:
      LPIR_FUZZ_CHECK(n.map.empty());
      for (const lpir::YamlNode& item : n.seq) count += Nodes(item, depth + 1);
      break;
  }
  return count;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    Nodes(lpir::ParseYaml(text), 0);
  } catch (const lpir::YamlError&) {
  }
  lpir::BagMetadata m;
  try {
    m = lpir::ParseBagMetadata(text);
  } catch (const lpir::YamlError&) {
    return 0;
  }
  LPIR_FUZZ_CHECK(!m.relative_file_paths.empty());
  for (const std::string& file : m.relative_file_paths) LPIR_FUZZ_CHECK(!file.empty());
  return 0;
}
