// Writes an MCAP file (.mcap) that standard MCAP tools read: magic, header (profile "ros2" or the
// one given), chunks of messages (compressed with zstd, lz4 or none) each followed by its message
// indexes, metadata and attachment records between chunks, then the summary (schemas, channels,
// statistics, chunk indexes, attachment and metadata indexes), summary offsets, the footer and the
// closing magic, every CRC filled in.
#pragma once
#include <cstdint>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "host/drive/drive_content.h"

namespace lpir {

enum class McapCompression { kNone, kZstd, kLz4 };

class McapWriter {
 public:
  // IoError naming the file when it cannot be created.
  McapWriter(const std::string& path, McapCompression compression,
             const std::string& profile = "ros2");
  ~McapWriter();  // closes the file (Close) when not closed yet, ignoring errors
  McapWriter(const McapWriter&) = delete;
  McapWriter& operator=(const McapWriter&) = delete;

  // A schema ("sensor_msgs/msg/PointCloud2", encoding "ros2msg", its concatenated definition);
  // returns its id (1, 2, ...). IoError naming the file past 65535 schemas.
  uint16_t AddSchema(const std::string& name, const std::string& encoding, const std::string& data);
  // A channel on `topic` ("cdr", "ros1", ...; schema_id 0: none); returns its id (0, 1, ...).
  // IoError naming the file past 65536 channels.
  uint16_t AddChannel(const std::string& topic, uint16_t schema_id,
                      const std::string& message_encoding, const DriveMap& metadata = {});
  // Appends a message; a chunk is closed and written once it holds about 4 MiB.
  void Write(uint16_t channel_id, uint32_t sequence, uint64_t log_time_ns, uint64_t publish_time_ns,
             const uint8_t* data, size_t size);
  // A metadata or attachment record, after the open chunk (closed first: the file keeps the order
  // of the calls).
  void AddMetadata(const DriveMetadata& metadata);
  void AddAttachment(const DriveAttachment& attachment);
  // Writes the last chunk, the summary and the footer. IoError naming the file on a write error.
  void Close();

 private:
  struct State;
  std::unique_ptr<State> state_;
};

// The ros2msg definition of sensor_msgs/msg/PointCloud2 with its dependencies, as ROS 2's
// recorder stores it in an MCAP schema.
const std::string& PointCloud2Ros2MsgDefinition();

}  // namespace lpir
