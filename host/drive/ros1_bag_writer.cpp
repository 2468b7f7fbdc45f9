// The ROS 1 bag writer (see ros1_bag_writer.h); the records are those ros1_bag_file.h reads.
#include "host/drive/ros1_bag_writer.h"

#include <algorithm>
#include <fstream>
#include <map>
#include <utility>
#include <vector>

#include "host/drive/decompress.h"
#include "host/drive/ros1_bag_file.h"
#include "host/io/io_error.h"

namespace lpir {
namespace {

// A chunk is closed once its uncompressed records reach this size (rosbag's default threshold).
constexpr size_t kChunkTarget = size_t(768) << 10;
// The bag header record's whole size: rosbag pads it so that it can be rewritten in place.
constexpr size_t kBagHeaderBytes = 4096;

void PutU32(std::vector<uint8_t>* out, uint32_t v) {
  for (int k = 0; k < 4; ++k) out->push_back(uint8_t(v >> (8 * k)));
}
std::string U32Bytes(uint32_t v) {
  std::vector<uint8_t> b;
  PutU32(&b, v);
  return std::string(b.begin(), b.end());
}
std::string U64Bytes(uint64_t v) { return U32Bytes(uint32_t(v)) + U32Bytes(uint32_t(v >> 32)); }
// A ROS time: uint32 sec, uint32 nsec.
std::string TimeBytes(uint64_t ns) {
  return U32Bytes(uint32_t(ns / 1000000000u)) + U32Bytes(uint32_t(ns % 1000000000u));
}

// Header fields (uint32 length, "name=value") as one header block.
std::vector<uint8_t> Header(const DriveMap& fields) {
  std::vector<uint8_t> out;
  for (const auto& [name, value] : fields) {
    PutU32(&out, uint32_t(name.size() + 1 + value.size()));
    out.insert(out.end(), name.begin(), name.end());
    out.push_back('=');
    out.insert(out.end(), value.begin(), value.end());
  }
  return out;
}

// A record: uint32 header_len, header, uint32 data_len, data, appended to `out`.
void PutRecord(std::vector<uint8_t>* out, const DriveMap& fields, const uint8_t* data,
               size_t size) {
  const std::vector<uint8_t> header = Header(fields);
  PutU32(out, uint32_t(header.size()));
  out->insert(out->end(), header.begin(), header.end());
  PutU32(out, uint32_t(size));
  out->insert(out->end(), data, data + size);
}

std::string Op(uint8_t op) { return std::string(1, char(op)); }

}  // namespace

struct Ros1BagWriter::State {
  std::string path;
  std::ofstream out;
  uint64_t position = 0;  // bytes written so far
  bool closed = false;

  struct Connection {
    std::string topic;
    DriveMap fields;  // the connection header, topic first
    bool written = false;
  };
  std::vector<Connection> connections;
  // Per chunk for the index: its position, time range and messages per connection.
  struct ChunkInfo {
    uint64_t pos, start, end;
    std::map<uint32_t, uint32_t> counts;
  };
  std::vector<ChunkInfo> chunk_infos;

  // The open chunk: its uncompressed records, time range and per-connection (time, offset).
  std::vector<uint8_t> chunk;
  uint64_t chunk_start = 0, chunk_end = 0;
  std::map<uint32_t, std::vector<std::pair<uint64_t, uint32_t>>> chunk_index;

  void Put(const std::vector<uint8_t>& bytes) {
    out.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
    if (!out) throw IoError(path, "cannot write the bag");
    position += bytes.size();
  }

  // The connection record: header op, conn, topic; data the connection header.
  void PutConnection(std::vector<uint8_t>* to, uint32_t conn) const {
    const std::vector<uint8_t> data = Header(connections[conn].fields);
    PutRecord(to,
              {{"op", Op(ros1::kOpConnection)},
               {"conn", U32Bytes(conn)},
               {"topic", connections[conn].topic}},
              data.data(), data.size());
  }

  // The bag header record, padded with spaces to kBagHeaderBytes.
  std::vector<uint8_t> BagHeader(uint64_t index_pos) const {
    const std::vector<uint8_t> header =
        Header({{"op", Op(ros1::kOpBagHeader)},
                {"index_pos", U64Bytes(index_pos)},
                {"conn_count", U32Bytes(uint32_t(connections.size()))},
                {"chunk_count", U32Bytes(uint32_t(chunk_infos.size()))}});
    const std::vector<uint8_t> padding(kBagHeaderBytes - 8 - header.size(), ' ');
    std::vector<uint8_t> out;
    PutU32(&out, uint32_t(header.size()));
    out.insert(out.end(), header.begin(), header.end());
    PutU32(&out, uint32_t(padding.size()));
    out.insert(out.end(), padding.begin(), padding.end());
    return out;
  }

  // Writes the open chunk (when it holds a message) lz4-compressed, and its index data records
  // after it in conn order.
  void FlushChunk() {
    if (chunk_index.empty()) return;
    const std::vector<uint8_t> packed = CompressLz4Frame(chunk.data(), chunk.size());
    ChunkInfo info{position, chunk_start, chunk_end, {}};
    std::vector<uint8_t> bytes;
    PutRecord(&bytes,
              {{"op", Op(ros1::kOpChunk)},
               {"compression", "lz4"},
               {"size", U32Bytes(uint32_t(chunk.size()))}},
              packed.data(), packed.size());
    for (const auto& [conn, entries] : chunk_index) {
      std::vector<uint8_t> data;
      for (const auto& [time, offset] : entries) {
        const std::string t = TimeBytes(time);
        data.insert(data.end(), t.begin(), t.end());
        PutU32(&data, offset);
      }
      PutRecord(&bytes,
                {{"op", Op(ros1::kOpIndexData)},
                 {"ver", U32Bytes(1)},
                 {"conn", U32Bytes(conn)},
                 {"count", U32Bytes(uint32_t(entries.size()))}},
                data.data(), data.size());
      info.counts[conn] = uint32_t(entries.size());
    }
    Put(bytes);
    chunk_infos.push_back(std::move(info));
    chunk.clear();
    chunk_index.clear();
  }
};

Ros1BagWriter::Ros1BagWriter(const std::string& path) : state_(std::make_unique<State>()) {
  State& s = *state_;
  s.path = path;
  s.out.open(path, std::ios::binary | std::ios::trunc);
  if (!s.out) throw IoError(path, "cannot create the bag");
  s.Put(std::vector<uint8_t>(ros1::kMagic, ros1::kMagic + ros1::kMagicSize));
  s.Put(s.BagHeader(0));
}

Ros1BagWriter::~Ros1BagWriter() {
  if (state_ && !state_->closed) {
    try {
      Close();
    } catch (...) {
    }
  }
}

uint32_t Ros1BagWriter::AddConnection(const std::string& topic, const DriveMap& fields) {
  State& s = *state_;
  State::Connection c{topic, {{"topic", topic}}, false};
  for (const auto& field : fields)
    if (field.first != "topic") c.fields.push_back(field);
  s.connections.push_back(std::move(c));
  return uint32_t(s.connections.size() - 1);
}

void Ros1BagWriter::Write(uint32_t conn, uint64_t time_ns, const uint8_t* data, size_t size) {
  State& s = *state_;
  if (time_ns / 1000000000u > UINT32_MAX)
    throw IoError(s.path, "a message time of " + std::to_string(time_ns) +
                              " ns is past the uint32 seconds of a ROS time");
  if (!s.connections[conn].written) {
    s.PutConnection(&s.chunk, conn);
    s.connections[conn].written = true;
  }
  if (s.chunk_index.empty()) s.chunk_start = s.chunk_end = time_ns;
  s.chunk_start = std::min(s.chunk_start, time_ns);
  s.chunk_end = std::max(s.chunk_end, time_ns);
  s.chunk_index[conn].emplace_back(time_ns, uint32_t(s.chunk.size()));
  PutRecord(&s.chunk,
            {{"op", Op(ros1::kOpMessage)}, {"conn", U32Bytes(conn)}, {"time", TimeBytes(time_ns)}},
            data, size);
  if (s.chunk.size() >= kChunkTarget) s.FlushChunk();
}

void Ros1BagWriter::Close() {
  State& s = *state_;
  if (s.closed) return;
  s.closed = true;
  s.FlushChunk();
  const uint64_t index_pos = s.position;
  std::vector<uint8_t> index;
  for (uint32_t conn = 0; conn < s.connections.size(); ++conn) s.PutConnection(&index, conn);
  for (const State::ChunkInfo& info : s.chunk_infos) {
    std::vector<uint8_t> data;
    for (const auto& [conn, count] : info.counts) {
      PutU32(&data, conn);
      PutU32(&data, count);
    }
    PutRecord(&index,
              {{"op", Op(ros1::kOpChunkInfo)},
               {"ver", U32Bytes(1)},
               {"chunk_pos", U64Bytes(info.pos)},
               {"start_time", TimeBytes(info.start)},
               {"end_time", TimeBytes(info.end)},
               {"count", U32Bytes(uint32_t(info.counts.size()))}},
              data.data(), data.size());
  }
  s.Put(index);
  s.out.seekp(std::streamoff(ros1::kMagicSize));
  const std::vector<uint8_t> header = s.BagHeader(index_pos);
  s.out.write(reinterpret_cast<const char*>(header.data()), std::streamsize(header.size()));
  s.out.close();
  if (!s.out) throw IoError(s.path, "cannot write the bag");
}

}  // namespace lpir
