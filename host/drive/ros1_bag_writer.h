// Writes a ROS 1 bag (format 2.0, .bag) as rosbag writes one, so that rosbag and this project's
// reader read it: the magic, the bag header record (4096 bytes, padded with spaces, rewritten at
// Close with index_pos, conn_count and chunk_count), chunks of about 768 KiB of records compressed
// with lz4 (the LZ4 frame format roslz4 reads), each chunk holding a connection's record before
// its first message and followed by an index data record per connection in it, then at index_pos
// every connection record and a chunk info record per chunk.
#pragma once
#include <cstdint>
#include <memory>
#include <string>

#include "host/drive/drive_content.h"

namespace lpir {

class Ros1BagWriter {
 public:
  // IoError naming `path` when it cannot be created.
  explicit Ros1BagWriter(const std::string& path);
  ~Ros1BagWriter();  // closes the file (Close) when not closed yet, ignoring errors
  Ros1BagWriter(const Ros1BagWriter&) = delete;
  Ros1BagWriter& operator=(const Ros1BagWriter&) = delete;

  // A connection on `topic` whose connection header holds `fields` (type, md5sum,
  // message_definition, callerid, latching, ...; "topic" is put first); returns its conn id
  // (0, 1, ...).
  uint32_t AddConnection(const std::string& topic, const DriveMap& fields);
  // A message of connection `conn` received at `time_ns` (IoError naming the file past the
  // uint32 seconds of a ROS time).
  void Write(uint32_t conn, uint64_t time_ns, const uint8_t* data, size_t size);
  // The last chunk, the index and the bag header. IoError naming the file on a write error.
  void Close();

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace lpir
