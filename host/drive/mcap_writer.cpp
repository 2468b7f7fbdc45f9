#include "host/drive/mcap_writer.h"

#include <algorithm>
#include <map>
#include <utility>

#include "host/drive/decompress.h"
#include "host/drive/mcap_records.h"
#include "host/io/io_error.h"

namespace lpir {

namespace {

// A chunk is closed once its uncompressed records reach this size.
constexpr size_t kChunkTarget = size_t(4) << 20;

const char* CompressionName(McapCompression c) {
  switch (c) {
    case McapCompression::kZstd:
      return "zstd";
    case McapCompression::kLz4:
      return "lz4";
    case McapCompression::kNone:
      break;
  }
  return "";
}

}  // namespace

struct McapWriter::State {
  std::string path;
  McapCompression compression;
  std::ofstream out;
  uint64_t position = 0;  // bytes written so far
  uint32_t data_crc = 0;  // CRC-32 of every byte written so far (the data section's, at DataEnd)
  bool closed = false;

  // Summary copies, in the order added.
  std::vector<mcap::Out> schema_records, channel_records;
  std::vector<mcap::Out> chunk_indexes, attachment_indexes, metadata_indexes;
  std::map<uint16_t, uint64_t> channel_counts;
  uint64_t message_count = 0, first_time = 0, last_time = 0;

  // The open chunk: its uncompressed records, time range and per-channel (log_time, offset).
  mcap::Out chunk;
  uint64_t chunk_start = 0, chunk_end = 0;
  std::map<uint16_t, std::vector<std::pair<uint64_t, uint64_t>>> chunk_index;

  void Put(const std::vector<uint8_t>& bytes) {
    out.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
    if (!out) throw IoError(path, "cannot write the MCAP file");
    data_crc = Crc32(bytes.data(), bytes.size(), data_crc);
    position += bytes.size();
  }
  void PutRecord(uint8_t op, const mcap::Out& content) {
    mcap::Out r;
    r.Record(op, content);
    Put(r.bytes);
  }

  // Writes the open chunk (when it holds a message) and its message indexes after it, in
  // channel-id order, and keeps its chunk index for the summary.
  void FlushChunk() {
    if (chunk_index.empty()) return;
    const std::vector<uint8_t>& records = chunk.bytes;
    std::vector<uint8_t> packed;
    if (compression == McapCompression::kZstd)
      packed = CompressZstd(records.data(), records.size());
    if (compression == McapCompression::kLz4) {
      packed = CompressLz4Frame(records.data(), records.size());
    }
    const std::vector<uint8_t>& stored = compression == McapCompression::kNone ? records : packed;
    mcap::Out c;
    c.U64(chunk_start);
    c.U64(chunk_end);
    c.U64(records.size());
    c.U32(Crc32(records.data(), records.size()));
    c.Str(CompressionName(compression));
    c.U64(stored.size());
    c.Raw(stored.data(), stored.size());
    const uint64_t chunk_offset = position;
    PutRecord(mcap::kChunk, c);
    const uint64_t chunk_length = position - chunk_offset;

    std::map<uint16_t, uint64_t> index_offsets;
    const uint64_t indexes_start = position;
    for (const auto& [channel, entries] : chunk_index) {
      mcap::Out m;
      m.U16(channel);
      m.U32(uint32_t(entries.size() * 16));
      for (const auto& [time, offset] : entries) {
        m.U64(time);
        m.U64(offset);
      }
      index_offsets[channel] = position;
      PutRecord(mcap::kMessageIndex, m);
    }

    mcap::Out ci;
    ci.U64(chunk_start);
    ci.U64(chunk_end);
    ci.U64(chunk_offset);
    ci.U64(chunk_length);
    ci.U32(uint32_t(index_offsets.size() * 10));
    for (const auto& [channel, offset] : index_offsets) {
      ci.U16(channel);
      ci.U64(offset);
    }
    ci.U64(position - indexes_start);
    ci.Str(CompressionName(compression));
    ci.U64(stored.size());
    ci.U64(records.size());
    chunk_indexes.push_back(std::move(ci));

    chunk.bytes.clear();
    chunk_index.clear();
  }
};

McapWriter::McapWriter(const std::string& path, McapCompression compression,
                       const std::string& profile)
    : state_(std::make_unique<State>()) {
  State& s = *state_;
  s.path = path;
  s.compression = compression;
  s.out.open(path, std::ios::binary | std::ios::trunc);
  if (!s.out) throw IoError(path, "cannot create the MCAP file");
  s.Put(std::vector<uint8_t>(mcap::kMagic, mcap::kMagic + mcap::kMagicSize));
  mcap::Out header;
  header.Str(profile);
  header.Str("lpir-gseg");
  s.PutRecord(mcap::kHeader, header);
}

McapWriter::~McapWriter() {
  if (state_ && !state_->closed) {
    try {
      Close();
    } catch (...) {
    }
  }
}

uint16_t McapWriter::AddSchema(const std::string& name, const std::string& encoding,
                               const std::string& data) {
  State& s = *state_;
  if (s.schema_records.size() >= UINT16_MAX) throw IoError(s.path, "more than 65535 schemas");
  const uint16_t id = uint16_t(s.schema_records.size() + 1);
  mcap::Out r;
  r.U16(id);
  r.Str(name);
  r.Str(encoding);
  r.Str(data);  // uint32 length-prefixed bytes: the same encoding as a String
  s.PutRecord(mcap::kSchema, r);
  s.schema_records.push_back(std::move(r));
  return id;
}

uint16_t McapWriter::AddChannel(const std::string& topic, uint16_t schema_id,
                                const std::string& message_encoding, const DriveMap& metadata) {
  State& s = *state_;
  if (s.channel_records.size() > UINT16_MAX) throw IoError(s.path, "more than 65536 channels");
  const uint16_t id = uint16_t(s.channel_records.size());
  mcap::Out r;
  r.U16(id);
  r.U16(schema_id);
  r.Str(topic);
  r.Str(message_encoding);
  r.Map(metadata);
  s.PutRecord(mcap::kChannel, r);
  s.channel_records.push_back(std::move(r));
  s.channel_counts[id];  // listed in the statistics even when it gets no message
  return id;
}

void McapWriter::Write(uint16_t channel_id, uint32_t sequence, uint64_t log_time_ns,
                       uint64_t publish_time_ns, const uint8_t* data, size_t size) {
  State& s = *state_;
  if (s.chunk_index.empty()) {
    s.chunk_start = s.chunk_end = log_time_ns;
  }
  s.chunk_start = std::min(s.chunk_start, log_time_ns);
  s.chunk_end = std::max(s.chunk_end, log_time_ns);
  s.first_time = s.message_count == 0 ? log_time_ns : std::min(s.first_time, log_time_ns);
  s.last_time = s.message_count == 0 ? log_time_ns : std::max(s.last_time, log_time_ns);
  ++s.message_count;
  ++s.channel_counts[channel_id];
  s.chunk_index[channel_id].emplace_back(log_time_ns, s.chunk.bytes.size());
  mcap::Out m;
  m.U16(channel_id);
  m.U32(sequence);
  m.U64(log_time_ns);
  m.U64(publish_time_ns);
  m.Raw(data, size);
  s.chunk.Record(mcap::kMessage, m);
  if (s.chunk.bytes.size() >= kChunkTarget) s.FlushChunk();
}

void McapWriter::AddMetadata(const DriveMetadata& metadata) {
  State& s = *state_;
  s.FlushChunk();
  mcap::Out r;
  r.Str(metadata.name);
  r.Map(metadata.entries);
  mcap::Out index;
  index.U64(s.position);
  index.U64(mcap::kRecordPrefix + r.bytes.size());
  index.Str(metadata.name);
  s.PutRecord(mcap::kMetadata, r);
  s.metadata_indexes.push_back(std::move(index));
}

void McapWriter::AddAttachment(const DriveAttachment& a) {
  State& s = *state_;
  s.FlushChunk();
  mcap::Out r;
  r.U64(a.log_time_ns);
  r.U64(a.create_time_ns);
  r.Str(a.name);
  r.Str(a.media_type);
  r.U64(a.data.size());
  r.Raw(a.data.data(), a.data.size());
  r.U32(Crc32(r.bytes.data(), r.bytes.size()));
  mcap::Out index;
  index.U64(s.position);
  index.U64(mcap::kRecordPrefix + r.bytes.size());
  index.U64(a.log_time_ns);
  index.U64(a.create_time_ns);
  index.U64(a.data.size());
  index.Str(a.name);
  index.Str(a.media_type);
  s.PutRecord(mcap::kAttachment, r);
  s.attachment_indexes.push_back(std::move(index));
}

void McapWriter::Close() {
  State& s = *state_;
  if (s.closed) return;
  s.closed = true;
  s.FlushChunk();
  mcap::Out data_end;
  data_end.U32(s.data_crc);
  s.PutRecord(mcap::kDataEnd, data_end);

  // The summary, grouped by opcode, then one summary offset per group; summary_crc covers both
  // and the footer up to the CRC itself.
  const uint64_t summary_start = s.position;
  mcap::Out summary, offsets;
  auto group = [&](uint8_t op, const std::vector<mcap::Out>& records) {
    if (records.empty()) return;
    const uint64_t start = summary_start + summary.bytes.size();
    for (const mcap::Out& r : records) summary.Record(op, r);
    mcap::Out o;
    o.U8(op);
    o.U64(start);
    o.U64(summary_start + summary.bytes.size() - start);
    offsets.Record(mcap::kSummaryOffset, o);
  };
  mcap::Out stats;
  stats.U64(s.message_count);
  stats.U16(uint16_t(s.schema_records.size()));
  stats.U32(uint32_t(s.channel_records.size()));
  stats.U32(uint32_t(s.attachment_indexes.size()));
  stats.U32(uint32_t(s.metadata_indexes.size()));
  stats.U32(uint32_t(s.chunk_indexes.size()));
  stats.U64(s.first_time);
  stats.U64(s.last_time);
  stats.U32(uint32_t(s.channel_counts.size() * 10));
  for (const auto& [channel, count] : s.channel_counts) {
    stats.U16(channel);
    stats.U64(count);
  }
  group(mcap::kSchema, s.schema_records);
  group(mcap::kChannel, s.channel_records);
  group(mcap::kStatistics, {stats});
  group(mcap::kChunkIndex, s.chunk_indexes);
  group(mcap::kAttachmentIndex, s.attachment_indexes);
  group(mcap::kMetadataIndex, s.metadata_indexes);

  mcap::Out tail = summary;
  tail.Raw(offsets.bytes.data(), offsets.bytes.size());
  const uint64_t summary_offset_start = summary_start + summary.bytes.size();
  tail.U8(mcap::kFooter);
  tail.U64(mcap::kFooterContent);
  tail.U64(summary_start);
  tail.U64(offsets.bytes.empty() ? 0 : summary_offset_start);
  tail.U32(Crc32(tail.bytes.data(), tail.bytes.size()));
  tail.Raw(mcap::kMagic, mcap::kMagicSize);
  s.Put(tail.bytes);
  s.out.close();
  if (!s.out) throw IoError(s.path, "cannot write the MCAP file");
}

const std::string& PointCloud2Ros2MsgDefinition() {
  static const std::string kDefinition = [] {
    const std::string rule = "\n" + std::string(80, '=') + "\n";
    return std::string(
               "std_msgs/Header header\n"
               "uint32 height\n"
               "uint32 width\n"
               "PointField[] fields\n"
               "bool is_bigendian\n"
               "uint32 point_step\n"
               "uint32 row_step\n"
               "uint8[] data\n"
               "bool is_dense\n") +
           rule +
           "MSG: std_msgs/Header\n"
           "builtin_interfaces/Time stamp\n"
           "string frame_id\n" +
           rule +
           "MSG: builtin_interfaces/Time\n"
           "int32 sec\n"
           "uint32 nanosec\n" +
           rule +
           "MSG: sensor_msgs/PointField\n"
           "uint8 INT8    = 1\n"
           "uint8 UINT8   = 2\n"
           "uint8 INT16   = 3\n"
           "uint8 UINT16  = 4\n"
           "uint8 INT32   = 5\n"
           "uint8 UINT32  = 6\n"
           "uint8 FLOAT32 = 7\n"
           "uint8 FLOAT64 = 8\n"
           "string name\n"
           "uint32 offset\n"
           "uint8 datatype\n"
           "uint32 count\n";
  }();
  return kDefinition;
}

}  // namespace lpir
