// A recorded drive's whole content, every topic, for writing the drive back (segment --format
// mcap|bag): the records in file order as MCAP models them (schemas, channels, messages, metadata,
// attachments), read from an MCAP, a ROS 2 .db3, a ROS 2 bag folder or a ROS 1 bag. DriveReader
// (drive.h) yields one topic's messages for segmenting; a DriveContent yields everything, each
// message with the channel it belongs to, so that nothing of the drive is lost on the way through.
//
// How each format maps onto the model:
//   MCAP      its own records: ids, schema data, channel metadata, sequence and publish time as
//             stored; metadata and attachment records; the summary is not read (the data
//             section repeats everything it holds).
//   ROS 1 bag one schema per distinct (type, message_definition): name = type, encoding
//             "ros1msg", data = message_definition; a channel per connection (id = conn, message
//             encoding "ros1"), its metadata the connection header's other fields in their order
//             (md5sum, callerid, latching, ...); message sequence = its place among its
//             connection's messages, publish time = log time = the record's time.
//   .db3      one schema per type: encoding "ros2msg" and the definition from the bag's
//             message_definitions table, else sensor_msgs/msg/PointCloud2's own
//             (PointCloud2Ros2MsgDefinition) for that type, else encoding "" and no data (the
//             MCAP specification's "no schema available"); a channel per topic row (id = its
//             place among the rows, from 1), metadata offered_qos_profiles when the bag has it;
//             messages ordered by timestamp then row id, sequence = the place among its topic's
//             messages, publish time = log time = the timestamp.
//   bag folder its files' contents one after another, each as above (bag_folder_content.cpp): a
//             schema or channel that a later file repeats yielded once, with the id first given;
//             a .db3's sequences counted on across the files; a metadata record repeated whole
//             (rosbag2's own, in every file) yielded once.
//   .bag.active a ROS 1 bag whose recorder died: its last chunk, whose sizes were never filled
//             in, read to the end of the file (ros1::UnfinishedChunk).
#pragma once
#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <variant>
#include <vector>

namespace lpir {

using DriveMap = std::vector<std::pair<std::string, std::string>>;  // in the order stored

struct DriveSchema {
  uint16_t id = 0;  // never 0
  std::string name, encoding, data;
};

struct DriveChannel {
  uint16_t id = 0;
  uint16_t schema_id = 0;  // 0: no schema
  std::string topic, message_encoding;
  DriveMap metadata;
};

struct DriveRecordMessage {
  uint16_t channel_id = 0;  // a channel yielded before it
  uint32_t sequence = 0;
  uint64_t log_time_ns = 0, publish_time_ns = 0;
  std::vector<uint8_t> data;
};

struct DriveMetadata {
  std::string name;
  DriveMap entries;
};

struct DriveAttachment {
  uint64_t log_time_ns = 0, create_time_ns = 0;
  std::string name, media_type;
  std::vector<uint8_t> data;
};

using DriveRecord =
    std::variant<DriveSchema, DriveChannel, DriveRecordMessage, DriveMetadata, DriveAttachment>;

enum class ContentStep { kRecord, kDamage, kEnd };

class DriveContent {
 public:
  virtual ~DriveContent() = default;
  // "ros2" or "ros1" (an MCAP's header profile as written there).
  virtual const std::string& profile() const = 0;
  // The next record (kRecord, *record filled), a damaged part (kDamage, *problem names the file,
  // where and what; its records are not yielded, reading goes on after it where its length says
  // where the next record starts, else the next call returns kEnd) or the end (kEnd). A schema
  // comes before the first channel that names it, a channel before its first message.
  virtual ContentStep Next(DriveRecord* record, std::string* problem) = 0;
};

// The content reader for `path` by its format (DriveFormatOf). IoError naming the file as
// OpenDrive's: missing, of another extension, no valid header.
std::unique_ptr<DriveContent> OpenDriveContent(const std::string& path);

std::unique_ptr<DriveContent> OpenMcapContent(const std::string& path);
std::unique_ptr<DriveContent> OpenRos1BagContent(const std::string& path);
std::unique_ptr<DriveContent> OpenDb3Content(const std::string& path);
std::unique_ptr<DriveContent> OpenBagFolderContent(const std::string& path);

}  // namespace lpir
