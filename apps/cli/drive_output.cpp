// segment's index and labelled MCAP for drives (see drive_output.h).
#include "apps/cli/drive_output.h"

#include <cerrno>
#include <cstring>
#include <vector>

#include "host/drive/pointcloud2.h"
#include "host/io/io_error.h"

namespace lpir {

DriveIndex::DriveIndex(const std::string& path) : path_(path) {
  file_ = std::fopen(path.c_str(), "wb");
  if (!file_) throw IoError(path, std::string("cannot create the index: ") + std::strerror(errno));
  std::fputs("sequence,stamp_ns,topic,points,ground_fraction,ms,file\n", file_);
}

DriveIndex::~DriveIndex() {
  if (file_) std::fclose(file_);
}

void DriveIndex::Add(const FrameInput& in, size_t ground, double ms, const std::string& file) {
  const size_t n = in.cloud.size();
  // a topic or file name holding a comma or quote is quoted, as CSV does
  auto field = [](const std::string& s) {
    if (s.find_first_of(",\"\r\n") == std::string::npos) return s;
    std::string q = "\"";
    for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
    return q + "\"";
  };
  std::fprintf(file_, "%llu,%lld,%s,%zu,%.6f,%.3f,%s\n",
               static_cast<unsigned long long>(in.sequence), static_cast<long long>(in.stamp_ns),
               field(in.topic).c_str(), n, n ? double(ground) / double(n) : 0.0, ms,
               field(file).c_str());
}

void DriveIndex::Close() {
  const bool failed_write = std::ferror(file_) != 0;
  const bool failed_close = std::fclose(file_) != 0;
  file_ = nullptr;
  if (failed_write || failed_close) throw IoError(path_, "writing the index failed");
}

LabelledMcap::LabelledMcap(const std::string& path, const std::string& topic)
    : path_(path), writer_(path, McapCompression::kZstd) {
  const uint16_t schema =
      writer_.AddSchema("sensor_msgs/msg/PointCloud2", "ros2msg", PointCloud2Ros2MsgDefinition());
  topic_channel_ = writer_.AddChannel(topic, schema, "cdr");
  ground_channel_ = writer_.AddChannel(topic + "/ground", schema, "cdr");
}

void LabelledMcap::Copy(const FrameInput& in, bool decoded) {
  if (!in.has_message) return;
  const uint32_t sequence = uint32_t(in.sequence);
  if (in.message.encoding == MessageEncoding::kCdr) {
    writer_.Write(topic_channel_, sequence, in.log_time_ns, in.log_time_ns, in.message.data.data(),
                  in.message.data.size());
  } else if (decoded) {
    const std::vector<uint8_t> cdr = SerializeCdrPointCloud2(in.cloud2);
    writer_.Write(topic_channel_, sequence, in.log_time_ns, in.log_time_ns, cdr.data(), cdr.size());
  }
}

void LabelledMcap::AddLabelled(const FrameInput& in, const Labels& labels) {
  const std::string where = in.input + ": " + in.topic + " message " + std::to_string(in.sequence);
  const std::vector<uint8_t> cdr = SerializeCdrPointCloud2(AddLabelField(where, in.cloud2, labels));
  writer_.Write(ground_channel_, uint32_t(in.sequence), in.log_time_ns, in.log_time_ns, cdr.data(),
                cdr.size());
}

void LabelledMcap::Close() { writer_.Close(); }

}  // namespace lpir
