// lpir-gseg topics DRIVE...: the topics of recorded drives (.mcap, .db3, .bag, .bag.active, ROS 2
// bag folders, or folders of them) as a table each, one line a topic in the drive's order:
// topic, message type, message encoding, message count; with --chunks only each drive's chunk
// count (DriveReader::ChunkCount), for splitting it into `segment --chunks` runs. The damage the
// listing meets is named on stderr and the exit code is then 1 (kExitSomeFailed): the counts are
// those of the messages that could be read. A drive that cannot be read is an error naming it:
// alone, it stops the command (kExitCannotRun, as main turns an IoError); among several, it is
// one failure (exit 1) and the others are listed.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "apps/cli/args.h"
#include "apps/cli/commands.h"
#include "apps/cli/exit_codes.h"
#include "host/drive/bag_folder.h"
#include "host/drive/drive.h"
#include "host/drive/inputs.h"

namespace lpir {
namespace {

const char kHelp[] =
    "usage: lpir-gseg topics DRIVE... [--chunks] [--recursive]\n"
    "  DRIVE            a recorded drive: .mcap or .db3 (ROS 2), a ROS 2 bag folder\n"
    "                   (metadata.yaml and its .mcap or .db3 files), .bag or .bag.active (ROS 1);\n"
    "                   or a folder of them\n"
    "  -r, --recursive  folders: also the drives of their subfolders\n"
    "  --chunks         print only each drive's number of chunks (0 for a .db3), numbered from 1\n"
    "                   as `segment --chunks A:B` and the damage messages number them\n"
    "Prints a line per topic: its name, message type, encoding and message count (several\n"
    "drives: each table under the drive's name). Damage met while listing is named on stderr and\n"
    "the exit code is 1: the counts are then those of the messages that could be read.\n"
    "`lpir-gseg segment DRIVE --topic T` labels the sensor_msgs/PointCloud2 messages of one.\n";

// The drives the arguments name: each a drive, or a folder of them (ListInputs' drives, with
// `recursive` those of its subfolders too).
std::vector<std::string> Drives(const std::vector<std::string>& given, bool recursive) {
  std::vector<std::string> drives;
  for (const std::string& in : given) {
    std::error_code ec;
    if (!std::filesystem::is_directory(in, ec) || IsBagFolder(in)) {
      drives.push_back(in);
      continue;
    }
    const size_t before = drives.size();
    for (const RunInput& found : ListInputs({in}, recursive, nullptr))
      if (found.drive) drives.push_back(found.path);
    if (drives.size() == before)
      throw std::invalid_argument(in + ": folder holds no recorded drives");
  }
  return drives;
}

void PrintTable(const std::vector<DriveTopic>& topics) {
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
}

// Lists one drive; returns whether it is damaged (each damaged part named on stderr).
bool ListDrive(const std::string& drive, bool chunks, bool several) {
  const std::unique_ptr<DriveReader> reader = OpenDrive(drive, 1);
  if (chunks) {
    const unsigned long long count = reader->ChunkCount();
    if (several)
      std::printf("%s: %llu\n", drive.c_str(), count);
    else
      std::printf("%llu\n", count);
    return false;
  }
  const std::vector<DriveTopic> topics = reader->Topics();
  if (several) std::printf("%s:\n", drive.c_str());
  PrintTable(topics);
  std::fflush(stdout);
  for (const std::string& note : reader->Notes())
    std::fprintf(stderr, "lpir-gseg topics: note: %s\n", note.c_str());
  const std::vector<std::string> damage = reader->ListingDamage();
  for (const std::string& d : damage)
    std::fprintf(stderr, "lpir-gseg topics: error: %s\n", d.c_str());
  if (!damage.empty())
    std::fprintf(stderr,
                 "lpir-gseg topics: %s: damaged (%zu part%s, named above): the counts are those of "
                 "the messages that could be read\n",
                 drive.c_str(), damage.size(), damage.size() == 1 ? "" : "s");
  return !damage.empty();
}

}  // namespace

int RunTopics(int argc, char** argv) {
  const Args args(argc, argv, {"--help", "--chunks", "--recursive"}, {});
  if (args.Has("--help")) {
    std::fputs(kHelp, stdout);
    std::fputs(kExitCodesLine, stdout);
    return kExitOk;
  }
  if (args.positional().empty()) throw std::invalid_argument("give a DRIVE\n" + std::string(kHelp));
  const std::vector<std::string> drives = Drives(args.positional(), args.Has("--recursive"));
  const bool several = drives.size() > 1;
  size_t problems = 0;
  for (size_t k = 0; k < drives.size(); ++k) {
    if (several && k > 0 && !args.Has("--chunks")) std::printf("\n");
    try {
      problems += ListDrive(drives[k], args.Has("--chunks"), several);
    } catch (const std::exception& e) {
      if (!several) throw;
      std::fflush(stdout);
      std::fprintf(stderr, "lpir-gseg topics: error: %s\n", e.what());
      ++problems;
    }
  }
  if (several && problems)
    std::fprintf(stderr, "lpir-gseg topics: %zu of %zu drives with problems (each named above)\n",
                 problems, drives.size());
  return problems ? kExitSomeFailed : kExitOk;
}

}  // namespace lpir
