#include "host/drive/bag_metadata.h"

#include "host/drive/mini_yaml.h"

namespace lpir {
namespace {

[[noreturn]] void Fail(const YamlNode& node, const std::string& what) {
  throw YamlError("line " + std::to_string(node.line) + ": " + what);
}

// The scalar under `key` ("" when absent or null); YamlError for a mapping or sequence there.
std::string Text(const YamlNode& map, const std::string& key) {
  const YamlNode* v = map.Get(key);
  if (!v || v->kind == YamlNode::Kind::kNull) return "";
  if (v->kind != YamlNode::Kind::kScalar) Fail(*v, "'" + key + "' is not a single value");
  return v->scalar;
}

uint64_t Count(const YamlNode& map, const std::string& key) {
  const std::string text = Text(map, key);
  if (text.empty() || text.size() > 19 || text.find_first_not_of("0123456789") != std::string::npos)
    Fail(map.Get(key) ? *map.Get(key) : map, "'" + key + "' is not a whole number: '" + text + "'");
  return std::stoull(text);
}

}  // namespace

BagMetadata ParseBagMetadata(const std::string& text) {
  const YamlNode root = ParseYaml(text);
  const YamlNode* info = root.Get("rosbag2_bagfile_information");
  if (!info || info->kind != YamlNode::Kind::kMap)
    Fail(root, "no 'rosbag2_bagfile_information' mapping");
  BagMetadata m;
  m.storage_identifier = Text(*info, "storage_identifier");
  m.compression_format = Text(*info, "compression_format");
  m.compression_mode = Text(*info, "compression_mode");
  const YamlNode* files = info->Get("relative_file_paths");
  if (!files || files->kind != YamlNode::Kind::kSeq || files->seq.empty())
    Fail(files ? *files : *info, "no 'relative_file_paths' listing the bag's files");
  for (const YamlNode& f : files->seq) {
    if (f.kind != YamlNode::Kind::kScalar || f.scalar.empty())
      Fail(f, "an item of 'relative_file_paths' that is no file name");
    m.relative_file_paths.push_back(f.scalar);
  }
  const YamlNode* topics = info->Get("topics_with_message_count");
  if (topics && topics->kind == YamlNode::Kind::kSeq) {
    for (const YamlNode& t : topics->seq) {
      const YamlNode* meta = t.Get("topic_metadata");
      if (!meta || meta->kind != YamlNode::Kind::kMap)
        Fail(t, "a topic without its 'topic_metadata' mapping");
      BagMetadata::Topic topic;
      topic.name = Text(*meta, "name");
      topic.type = Text(*meta, "type");
      topic.serialization_format = Text(*meta, "serialization_format");
      topic.messages = Count(t, "message_count");
      m.topics.push_back(std::move(topic));
    }
  } else if (topics && topics->kind != YamlNode::Kind::kNull) {
    Fail(*topics, "'topics_with_message_count' is not a list");
  }
  return m;
}

}  // namespace lpir
