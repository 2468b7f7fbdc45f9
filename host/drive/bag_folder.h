// A ROS 2 bag as `ros2 bag record` writes it: a folder holding metadata.yaml and the bag's files,
// <name>_0.mcap, <name>_1.mcap, ... (or .db3), split when a file grew past the recorder's limit.
// Read as one drive: the files in the order metadata.yaml lists them, each message numbered
// after every message of the files before it, the chunks numbered on across the files.
//
// Without a readable metadata.yaml (a recorder that died before writing it, a file damaged or in
// a form mini_yaml.h does not read) the folder's files named <anything>_<N>.mcap or .db3 are
// read in the order of N, and Notes() says so. A file metadata.yaml lists that is missing or
// cannot be opened is damage at its place: reported by Next after the files before it, and by
// ListingDamage.
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "host/drive/bag_metadata.h"
#include "host/drive/drive.h"

namespace lpir {

// The files of the bag in folder `path`, in the order they are read: those metadata.yaml lists
// (resolved), else the folder's files named <anything>_<N>.mcap or .db3 by N, with a note saying
// so and naming them. IoError as OpenBagFolder's for a bag compressed by rosbag2, another
// storage, or no file to read.
struct BagFiles {
  std::vector<std::string> files;
  std::vector<BagMetadata::Topic> topics;  // metadata.yaml's counts (none without it)
  std::vector<std::string> notes;          // how the files were found, when not from metadata.yaml
};
BagFiles ListBagFiles(const std::string& path);

// True for a folder rosbag2 wrote: it holds metadata.yaml, or (a recorder that died before
// writing metadata.yaml) <folder name>_0.mcap or <folder name>_0.db3.
bool IsBagFolder(const std::string& path);

// The bag in folder `path`, each of its files read with `threads` decompression threads
// (OpenDrive). IoError naming the folder or metadata.yaml: a bag compressed by rosbag2 itself
// (compression_mode FILE or MESSAGE), a storage other than mcap or sqlite3, no file to read, or
// not one of its files can be opened (the first one's problem given).
std::unique_ptr<DriveReader> OpenBagFolder(const std::string& path, unsigned threads);

}  // namespace lpir
