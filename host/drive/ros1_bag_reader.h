// ROS 1 bag format 2.0 (.bag): "#ROSBAG V2.0" then records (bag header, chunks of none, bz2 or
// lz4, connections, index data, chunk info). The index at the end is used when present, else the
// chunks are scanned from the start. Messages come in the order of their receipt time.
#pragma once
#include <memory>
#include <string>

#include "host/drive/drive.h"

namespace lpir {

// `threads`: the chunk decompression's workers (ChunkPool; 1: Next decompresses itself).
std::unique_ptr<DriveReader> OpenRos1Bag(const std::string& path, unsigned threads = 1);

}  // namespace lpir
