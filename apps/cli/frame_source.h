// Where segment's frames come from: cloud files in the order given, or the messages of one
// topic of a recorded drive in the order logged. Either way a frame is read whole before it is
// submitted, and a frame that cannot be read is a failure naming it, after which reading goes on.
#pragma once
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "host/drive/drive.h"
#include "host/drive/pointcloud2.h"
#include "host/io/cloud_file.h"
#include "reference_cpu/cloud.h"

namespace lpir {

// One frame between its reading and its writing.
struct FrameInput {
  std::string input;  // the file, or the drive
  std::string stem;   // the output files' stem: the file's, or "<sequence %06>_<stamp ns>"
  bool from_drive = false;
  bool has_message = false;  // a drive's message was read: sequence, stamps, topic, message hold
  uint64_t sequence = 0;     // DriveMessage::sequence
  int64_t stamp_ns = 0;      // the PointCloud2 header's stamp
  uint64_t log_time_ns = 0;  // DriveMessage::log_time_ns
  std::string topic;
  std::string note;  // what the reader filled in that the file lacks (ReadCloud's note), or empty
  Cloud cloud;
  DriveMessage message;  // the message as logged (kept only when the source is asked to)
  PointCloud2 cloud2;    // the message decoded (kept only then)
};

enum class SourceStep { kFrame, kFailed, kEnd };

class FrameSource {
 public:
  virtual ~FrameSource() = default;
  // The frames expected: the progress bar's total.
  virtual size_t count() const = 0;
  // "file" or "message", for the summary.
  virtual const char* unit() const = 0;
  // The next frame (kFrame, *in filled), one that could not be read (kFailed: *error names it and
  // the problem; *in holds what was read of it) or the end.
  virtual SourceStep Next(FrameInput* in, std::string* error) = 0;
};

// Cloud files (ReadCloud under `read`), in the order given.
std::unique_ptr<FrameSource> OpenFileSource(std::vector<std::string> files, ReadOptions read);

// The topic to segment in a drive with `topics`, listed with `damage` (ListingDamage): `topic`
// when given (std::invalid_argument naming `drive` unless it is there and a PointCloud2: the
// command line asks for what is not there), else the drive's only PointCloud2 topic
// (std::invalid_argument listing them when there are several; IoError naming `drive` when there
// is none: no option would help). A topic that is not there on a damaged drive is an IoError
// naming the damage, with or without `topic`: the damage may have taken it.
std::string ChooseCloudTopic(const std::string& drive, const std::vector<DriveTopic>& topics,
                             const std::string& topic, const std::vector<std::string>& damage);

// Chunks first..last of a drive (DriveReader::SelectChunks); first 0: every chunk.
struct ChunkRange {
  uint64_t first = 0, last = 0;
};

// The PointCloud2 messages of `topic` in `drive`, opened by `reader` (OpenDrive), in `chunks`;
// `count`, the topic's messages (DriveReader::Topics; 0 when unknown), is count(). A damaged part
// of the drive and a message that does not decode (DecodeDriveCloud's rules) are failures.
// keep_messages: FrameInput::message and cloud2 are filled (for writing the messages back).
// IoError naming the drive for a range it does not have.
std::unique_ptr<FrameSource> OpenDriveSource(const std::string& drive,
                                             std::unique_ptr<DriveReader> reader,
                                             const std::string& topic, ChunkRange chunks,
                                             size_t count, bool keep_messages);

// `source` read one frame ahead on a second thread: while the caller segments a frame, the next
// is read and decoded. Frames, failures and their order are `source`'s; at most one frame waits
// read. An exception from `source` reaches the caller's Next in its place.
std::unique_ptr<FrameSource> ReadAhead(std::unique_ptr<FrameSource> source);

}  // namespace lpir
