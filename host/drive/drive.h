// A recorded drive: a ROS 2 MCAP file (.mcap), a ROS 2 SQLite bag (.db3), a ROS 2 bag folder
// (metadata.yaml and its split .mcap or .db3 files: bag_folder.h) or a ROS 1 bag 2.0 (.bag, and
// .bag.active, the file a ROS 1 recorder leaves when it dies), read without ROS. A reader yields
// the serialized messages of one topic in the order they were logged; DecodeDriveCloud turns a
// sensor_msgs PointCloud2 message into a Cloud.
//
// Damage: Next reports a damaged part (truncated record or chunk, CRC mismatch, unknown
// compression, a malformed record) as DriveStep::kDamage with a problem naming the file, where
// (byte offset, chunk, message sequence when known) and what. Reading goes on after it where the
// format lets the reader find the next intact part (the next chunk of an indexed file), else the
// next call returns kEnd. Every message before the damage has been yielded by then.
#pragma once
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "reference_cpu/cloud.h"

namespace lpir {

// The serialization of a message's bytes.
enum class MessageEncoding { kCdr, kRos1 };

struct DriveTopic {
  std::string name;      // "/points"
  std::string type;      // as the drive names it: "sensor_msgs/msg/PointCloud2" (ROS 2),
                         // "sensor_msgs/PointCloud2" (ROS 1)
  std::string encoding;  // as the drive names it: "cdr", "ros1", ...
  uint64_t messages = 0;
};

struct DriveMessage {
  uint64_t sequence = 0;     // 0-based position among the chosen topic's yielded messages
  uint64_t log_time_ns = 0;  // when the recorder logged it
  std::string topic;
  MessageEncoding encoding = MessageEncoding::kCdr;
  std::vector<uint8_t> data;  // the serialized message (CDR: with its 4-byte encapsulation header)
};

enum class DriveStep { kMessage, kDamage, kEnd };

class DriveReader {
 public:
  virtual ~DriveReader() = default;
  // Every topic with its type and message count (from the summary or index when the file has
  // one, else from a scan). IoError naming the file when the file cannot be read at all.
  virtual std::vector<DriveTopic> Topics() = 0;
  // Restricts Next to `topic` and starts from the first message. IoError naming the file when
  // the drive has no such topic (the message lists those it has).
  virtual void SelectTopic(const std::string& topic) = 0;
  // The next message of the selected topic (kMessage, *message filled), a damaged part
  // (kDamage, *problem filled) or the end (kEnd).
  virtual DriveStep Next(DriveMessage* message, std::string* problem) = 0;

  // The drive's chunks, numbered from 1 as the damage problems number them (MCAP: in the order
  // Next reads them; ROS 1: in file order); 0 for a drive without chunks (.db3). From the summary
  // or index when the drive has one, else from a walk of the records (an unindexed ROS 1 bag:
  // the scan of Topics).
  virtual uint64_t ChunkCount() = 0;
  // True when SelectChunks finds where a range starts from the drive's index (an MCAP summary
  // with chunk indexes, a ROS 1 bag's index) without reading the chunks before it; false when it
  // reads them (or the drive has no chunks).
  virtual bool ChunksIndexed() = 0;
  // Restricts the selected topic to the messages in chunks first..last (1 <= first <= last <=
  // ChunkCount()) and starts from the first of them; call after SelectTopic (which clears the
  // restriction). A message's sequence counts every message of the topic before it, those of
  // the chunks outside the range included (from the index or message indexes, without
  // decompressing those chunks, when the drive has them; else by reading them), so that runs
  // over ranges that cover an undamaged drive yield together what one run yields. A damaged part
  // is reported by the range holding its chunk, one between chunks by the range of the chunk
  // before it (the first range: before every chunk). IoError naming the file for a drive without
  // chunks or a range outside 1..ChunkCount().
  virtual void SelectChunks(uint64_t first, uint64_t last) = 0;

  // The damaged parts the listing of Topics met, in file order, each naming the file, where and
  // what (Next reports them too, at their place): empty when Topics read the drive whole, or
  // took its listing from an index without reading the chunks. Call after Topics.
  virtual std::vector<std::string> ListingDamage() { return {}; }
  // How the drive is read where that is not the plain way, each a sentence naming the file: a
  // ROS 1 bag without an index (a recorder that died) scanned, a bag folder's files taken in the
  // order of their numbers. Call after Topics or SelectTopic.
  virtual std::vector<std::string> Notes() { return {}; }
};

// True for the file names OpenDrive accepts: .mcap, .db3, .bag, .bag.active.
bool IsDriveFile(const std::string& path);
// True for a drive: a drive file (IsDriveFile) or a ROS 2 bag folder (IsBagFolder).
bool IsDrive(const std::string& path);
enum class DriveFormat { kMcap, kDb3, kRos1Bag, kBagFolder };
// The format of `path`: a ROS 2 bag folder (kBagFolder), else by its file name (.bag and
// .bag.active: kRos1Bag). IoError naming it for a folder that is no bag, or another extension.
DriveFormat DriveFormatOf(const std::string& path);
// The reader for `path` by its format: a bag folder (OpenBagFolder), else a file. IoError naming
// the file when it is missing, of an unknown extension, or has no valid header (magic, version,
// schema). `read_threads`: the threads that decompress chunks ahead of Next (chunk_pool.h; 1:
// none, Next decompresses each chunk itself; 0: DefaultReadThreads()).
std::unique_ptr<DriveReader> OpenDrive(const std::string& path, unsigned read_threads = 0);

// The sensor_msgs/PointCloud2 in `message` as a Cloud (see pointcloud2.h for the rules).
// IoError naming `where` (file and message) for a malformed message or one whose fields do not
// hold x, y and z.
Cloud DecodeDriveCloud(const std::string& where, const DriveMessage& message);

}  // namespace lpir
