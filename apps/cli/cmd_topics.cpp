// lpir-gseg topics DRIVE: the topics of a recorded drive (.mcap, .db3, .bag) as a table, one line
// each in the drive's order: topic, message type, message encoding, message count; with --chunks
// only the drive's chunk count (DriveReader::ChunkCount), for splitting it into `segment
// --chunks` runs. A drive that cannot be read is an error naming it (exit kExitCannotRun, as main
// turns an IoError).
#include <algorithm>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include "apps/cli/args.h"
#include "apps/cli/commands.h"
#include "apps/cli/exit_codes.h"
#include "host/drive/drive.h"

namespace lpir {
namespace {

const char kHelp[] =
    "usage: lpir-gseg topics DRIVE [--chunks]\n"
    "  DRIVE            a recorded drive: .mcap or .db3 (ROS 2), .bag (ROS 1)\n"
    "  --chunks         print only the drive's number of chunks (0 for a .db3), numbered from 1\n"
    "                   as `segment --chunks A:B` and the damage messages number them\n"
    "Prints a line per topic: its name, message type, encoding and message count. `lpir-gseg\n"
    "segment DRIVE --topic T` labels the sensor_msgs/PointCloud2 messages of one of them.\n";

}  // namespace

int RunTopics(int argc, char** argv) {
  const Args args(argc, argv, {"--help", "--chunks"}, {});
  if (args.Has("--help")) {
    std::fputs(kHelp, stdout);
    std::fputs(kExitCodesLine, stdout);
    return kExitOk;
  }
  if (args.positional().size() != 1)
    throw std::invalid_argument("give one DRIVE\n" + std::string(kHelp));
  const std::string& drive = args.positional()[0];
  if (args.Has("--chunks")) {
    std::printf("%llu\n", static_cast<unsigned long long>(OpenDrive(drive, 1)->ChunkCount()));
    return kExitOk;
  }
  const std::vector<DriveTopic> topics = OpenDrive(drive, 1)->Topics();
  const std::string head[] = {"topic", "type", "encoding", "messages"};
  size_t w[3] = {head[0].size(), head[1].size(), head[2].size()};
  for (const DriveTopic& t : topics) {
    w[0] = std::max(w[0], t.name.size());
    w[1] = std::max(w[1], t.type.size());
    w[2] = std::max(w[2], t.encoding.size());
  }
  std::printf("%-*s  %-*s  %-*s  %s\n", int(w[0]), head[0].c_str(), int(w[1]), head[1].c_str(),
              int(w[2]), head[2].c_str(), head[3].c_str());
  for (const DriveTopic& t : topics)
    std::printf("%-*s  %-*s  %-*s  %llu\n", int(w[0]), t.name.c_str(), int(w[1]), t.type.c_str(),
                int(w[2]), t.encoding.c_str(), static_cast<unsigned long long>(t.messages));
  if (topics.empty()) std::printf("(no topics)\n");
  return kExitOk;
}

}  // namespace lpir
