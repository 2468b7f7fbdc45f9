// segment's index and labelled drive for drives (see drive_output.h).
#include "apps/cli/drive_output.h"

#include <cerrno>
#include <cstring>
#include <map>
#include <optional>
#include <variant>
#include <vector>

#include "host/drive/drive_content.h"
#include "host/drive/mcap_writer.h"
#include "host/drive/pointcloud2.h"
#include "host/drive/ros1_bag_writer.h"
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

namespace {

// The topics a labelled message's clouds go to, after the segmented topic's name.
const char* const kCloudSuffixes[3] = {"/labelled", "/ground", "/nonground"};

// A channel's ROS 1 connection header: type from its schema, the other fields (md5sum, callerid,
// latching, ...) from its metadata in their order, message_definition from its schema.
DriveMap ConnectionFields(const DriveChannel& channel, const DriveSchema* schema) {
  DriveMap fields = {{"type", schema ? schema->name : ""}};
  fields.insert(fields.end(), channel.metadata.begin(), channel.metadata.end());
  fields.emplace_back("message_definition", schema ? schema->data : "");
  return fields;
}

}  // namespace

struct LabelledDrive::State {
  std::string drive, path, topic;
  std::unique_ptr<DriveContent> content;
  std::unique_ptr<McapWriter> mcap;  // one of the two
  std::unique_ptr<Ros1BagWriter> bag;

  std::optional<DriveRecord> next;  // the input's next record, read ahead
  bool ended = false;
  std::vector<std::string> problems;
  std::map<uint16_t, DriveSchema> schemas;    // input id -> the schema
  std::map<uint16_t, uint16_t> schema_ids;    // input id -> output id (MCAP)
  std::map<uint16_t, DriveChannel> channels;  // input id -> the channel
  std::map<uint16_t, uint32_t> channel_ids;   // input id -> output channel or conn id
  std::optional<uint16_t> source;             // the input channel of `topic` met first
  std::vector<uint32_t> clouds;               // output ids of the three clouds' channels

  // The input's next record into `next` (nothing at the end); damage goes to `problems`.
  bool Peek() {
    while (!next && !ended) {
      DriveRecord record;
      std::string problem;
      const ContentStep step = content->Next(&record, &problem);
      if (step == ContentStep::kRecord) next = std::move(record);
      if (step == ContentStep::kDamage)
        problems.push_back(problem + "; its records are not in " + path);
      if (step == ContentStep::kEnd) ended = true;
    }
    return next.has_value();
  }

  // Copies input records until the next is a message logged after `time_ns` (with
  // `until_source`, and the channel of `topic` met), or to the end.
  void CopyUntil(uint64_t time_ns, bool until_source) {
    while (Peek()) {
      const auto* m = std::get_if<DriveRecordMessage>(&*next);
      if (m && m->log_time_ns > time_ns && (!until_source || source)) return;
      Copy(*next);
      next.reset();
    }
  }

  void Copy(const DriveRecord& record) {
    if (const auto* s = std::get_if<DriveSchema>(&record)) {
      schemas[s->id] = *s;
      if (mcap) schema_ids[s->id] = mcap->AddSchema(s->name, s->encoding, s->data);
    } else if (const auto* c = std::get_if<DriveChannel>(&record)) {
      channels[c->id] = *c;
      channel_ids[c->id] = AddChannel(c->topic, *c);
      if (!source && c->topic == topic) source = c->id;
    } else if (const auto* m = std::get_if<DriveRecordMessage>(&record)) {
      const uint32_t id = channel_ids.at(m->channel_id);
      if (mcap)
        mcap->Write(uint16_t(id), m->sequence, m->log_time_ns, m->publish_time_ns, m->data.data(),
                    m->data.size());
      else
        bag->Write(id, m->log_time_ns, m->data.data(), m->data.size());
    } else if (mcap) {
      if (const auto* meta = std::get_if<DriveMetadata>(&record)) mcap->AddMetadata(*meta);
      if (const auto* a = std::get_if<DriveAttachment>(&record)) mcap->AddAttachment(*a);
    } else {
      problems.push_back(drive +
                         ": a metadata or attachment record, which a ROS 1 bag cannot "
                         "hold, is not in " +
                         path);
    }
  }

  // A channel like `like` (its schema, encoding and metadata) on `name`; its output id.
  uint32_t AddChannel(const std::string& name, const DriveChannel& like) {
    const auto schema = schemas.find(like.schema_id);
    if (bag)
      return bag->AddConnection(
          name, ConnectionFields(like, schema == schemas.end() ? nullptr : &schema->second));
    const auto id = schema_ids.find(like.schema_id);
    return mcap->AddChannel(name, id == schema_ids.end() ? 0 : id->second, like.message_encoding,
                            like.metadata);
  }
};

LabelledDrive::LabelledDrive(const std::string& drive, const std::string& path,
                             const std::string& topic, Format format)
    : state_(std::make_unique<State>()) {
  State& s = *state_;
  s.drive = drive;
  s.path = path;
  s.topic = topic;
  s.content = OpenDriveContent(drive);
  if (format == Format::kBag)
    s.bag = std::make_unique<Ros1BagWriter>(path);
  else
    s.mcap = std::make_unique<McapWriter>(path, McapCompression::kZstd, s.content->profile());
}

LabelledDrive::~LabelledDrive() = default;

void LabelledDrive::AddLabelled(const FrameInput& in, const Labels& labels) {
  State& s = *state_;
  s.CopyUntil(in.log_time_ns, s.clouds.empty());
  const std::string where = in.input + ": " + in.topic + " message " + std::to_string(in.sequence);
  const LabelledClouds clouds = SplitByLabel(where, in.cloud2, labels);
  if (s.clouds.empty()) {
    if (!s.source) throw IoError(where, "no channel of " + s.topic + " in the drive's records");
    for (const char* suffix : kCloudSuffixes)
      s.clouds.push_back(s.AddChannel(s.topic + suffix, s.channels.at(*s.source)));
  }
  const PointCloud2* const out[3] = {&clouds.labelled, &clouds.ground, &clouds.nonground};
  for (int k = 0; k < 3; ++k) {
    const std::vector<uint8_t> bytes = in.message.encoding == MessageEncoding::kCdr
                                           ? SerializeCdrPointCloud2(*out[k])
                                           : SerializeRos1PointCloud2(*out[k]);
    if (s.mcap)
      s.mcap->Write(uint16_t(s.clouds[k]), uint32_t(in.sequence), in.log_time_ns, in.log_time_ns,
                    bytes.data(), bytes.size());
    else
      s.bag->Write(s.clouds[k], in.log_time_ns, bytes.data(), bytes.size());
  }
}

void LabelledDrive::Close() {
  State& s = *state_;
  s.CopyUntil(UINT64_MAX, false);
  if (s.mcap) s.mcap->Close();
  if (s.bag) s.bag->Close();
}

std::vector<std::string> LabelledDrive::TakeProblems() {
  std::vector<std::string> out;
  out.swap(state_->problems);
  return out;
}

}  // namespace lpir
