// What segment writes for a recorded drive besides the labels: DIR/index.csv, a line per
// labelled message, and with --format mcap|bag the whole drive with its labelled clouds.
#pragma once
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "apps/cli/frame_source.h"
#include "reference_cpu/cloud.h"

namespace lpir {

// index.csv: the header "sequence,stamp_ns,topic,points,ground_fraction,ms,file", then a line per
// message in the order labelled (file: the output's name inside DIR; empty with --format mcap,
// whose messages all go into one file, and --format bag).
class DriveIndex {
 public:
  // IoError naming `path` when it cannot be created.
  explicit DriveIndex(const std::string& path);
  ~DriveIndex();
  DriveIndex(const DriveIndex&) = delete;
  DriveIndex& operator=(const DriveIndex&) = delete;
  void Add(const FrameInput& in, size_t ground, double ms, const std::string& file);
  // IoError naming the file when a write failed.
  void Close();

 private:
  std::string path_;
  std::FILE* file_ = nullptr;
};

// segment --format mcap|bag: the drive written back whole, every record of every channel as it
// was (DriveContent, in the input's order: schemas, channels with their metadata, messages with
// their sequence, log and publish times and bytes, metadata and attachments), and for every
// labelled message of `topic` its three clouds (SplitByLabel) on <topic>/labelled,
// <topic>/ground and <topic>/nonground, in the topic's own encoding (CDR, or ROS 1), with its log
// time and sequence. Each labelled message's clouds follow every input message logged at or
// before it. Ids are given anew in the order first written (MCAP: schemas from 1, channels from 0;
// a bag: conn ids from 0).
//   mcap: zstd chunks, the input's profile (an MCAP's own, "ros1" for a bag, "ros2" for a .db3);
//   bag:  a ROS 1 bag (Ros1BagWriter), for a ROS 1 bag input only: its connections' headers
//         (type, md5sum, message_definition, callerid, latching, ...) as they were.
class LabelledDrive {
 public:
  enum class Format { kMcap, kBag };
  // IoError naming the drive when it cannot be opened, or `path` when it cannot be created.
  LabelledDrive(const std::string& drive, const std::string& path, const std::string& topic,
                Format format);
  ~LabelledDrive();
  LabelledDrive(const LabelledDrive&) = delete;
  LabelledDrive& operator=(const LabelledDrive&) = delete;
  // Copies the input up to in.log_time_ns, then writes the message's three clouds (from in.cloud2
  // and in.message.encoding, one label per point). IoError naming the message for a cloud
  // SplitByLabel refuses.
  void AddLabelled(const FrameInput& in, const Labels& labels);
  // Copies the rest and closes the file. IoError naming the file when a write failed.
  void Close();
  // The damaged parts of the input met while copying since the last call (their records are not
  // in the output), each naming the drive, the place, and the output.
  std::vector<std::string> TakeProblems();

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace lpir
