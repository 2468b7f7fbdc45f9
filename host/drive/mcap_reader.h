// ROS 2 MCAP (.mcap): magic, records, chunks (none, zstd, lz4) with their CRCs; the summary
// section (statistics, channels, chunk indexes) is used when present and valid, else the file
// is scanned from the start. Messages come in log-time order within the chosen channel.
#pragma once
#include <memory>
#include <string>

#include "host/drive/drive.h"

namespace lpir {

// `threads`: the chunk decompression's workers (ChunkPool; 1: Next decompresses itself).
std::unique_ptr<DriveReader> OpenMcap(const std::string& path, unsigned threads = 1);

}  // namespace lpir
