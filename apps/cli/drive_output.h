// What segment writes for a recorded drive besides the labels: DIR/index.csv, a line per
// labelled message, and with --format mcap the drive's topic and its labels as one MCAP file.
#pragma once
#include <cstdio>
#include <memory>
#include <string>

#include "apps/cli/frame_source.h"
#include "host/drive/mcap_writer.h"
#include "reference_cpu/cloud.h"

namespace lpir {

// index.csv: the header "sequence,stamp_ns,topic,points,ground_fraction,ms,file", then a line per
// message in the order labelled (file: the output's name inside DIR; empty with --format mcap,
// whose messages all go into one file).
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

// An MCAP (zstd chunks, profile ros2) holding `topic`'s messages and, on "<topic>/ground", each
// labelled one with a uint8 `label` field added (AddLabelField); both channels CDR with the schema
// sensor_msgs/msg/PointCloud2 (ros2msg). A message keeps its sequence and log time on both.
class LabelledMcap {
 public:
  // IoError naming `path` when it cannot be created.
  LabelledMcap(const std::string& path, const std::string& topic);
  // The message as logged: CDR bytes unchanged; a ROS 1 message re-serialized as CDR from
  // in.cloud2 when `decoded` (a ROS 1 message that did not decode is left out).
  void Copy(const FrameInput& in, bool decoded);
  // The labelled message on <topic>/ground (from in.cloud2, one label per point).
  void AddLabelled(const FrameInput& in, const Labels& labels);
  // IoError naming the file when a write failed.
  void Close();

 private:
  std::string path_;
  McapWriter writer_;
  uint16_t topic_channel_ = 0, ground_channel_ = 0;
};

}  // namespace lpir
