// lpir-gseg: LiDAR ground segmentation (LPIR-GSeg). Dispatches to one subcommand, or answers
// --help, --version and `help [COMMAND|exit-codes]`; what a subcommand throws becomes a message
// and an exit code (apps/cli/exit_codes.h).
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <stdexcept>
#include <string>
#include <vector>

#include "apps/cli/commands.h"
#include "apps/cli/exit_codes.h"
#include "host/io/suggest.h"
#include "host/vk/device.h"
#include "host/vk/instance.h"

namespace lpir {
const char* SensorsDir() {
  const char* env = std::getenv("LPIR_SENSORS_DIR");
  return env && *env ? env : LPIR_SENSORS_DIR;
}
}  // namespace lpir

namespace {
const char kUsage[] =
    "usage: lpir-gseg <command> [options]   (lpir-gseg help COMMAND: all of its options)\n"
    "  segment INPUT... --sensor NAME --out DIR [--backend auto|vulkan|cpu] [--device D]\n"
    "          [--timings] [--format label|pcd|ply] [--images] [--gt PATH] [--quiet|--verbose]\n"
    "          [--report FILE.csv|.json] [--recursive] [--set NAME=VALUE]...; INPUTs are\n"
    "          clouds, recorded drives (with [--topic T] [--format mcap|bag]) or folders of them\n"
    "  evaluate --pred DIR --gt PATH... [--protocol dg|pp|pw|gg|all] [--json] [--by-class]\n"
    "           [--by-range] [--ontology semantickitti|rellis3d]\n"
    "  simulate --sensor NAME --seed N [--pitch DEG --roll DEG] --out FILE.bin --labels "
    "FILE.label\n"
    "  calibrate SCAN... --sensor NAME [--write-profile FILE] [--json]\n"
    "  demo [--out DIR] [--backend auto|vulkan|cpu] [--runs N] [--set NAME=VALUE]...\n"
    "  devices\n"
    "  bench [--runs N] [--json]\n"
    "  topics DRIVE... [--recursive]  the topics of recorded drives (.mcap, .db3, .bag, bag\n"
    "          folders) or folders of them\n"
    "  help [COMMAND|exit-codes]   a command's help (as COMMAND --help), or the exit codes\n"
    "  --version        the version, the git commit built and which backends this machine has\n"
    "options: --opt VALUE or --opt=VALUE; short forms -s --sensor, -o --out, -b --backend,\n"
    "  -f --format, -t --topic, -p --protocol, -r --recursive, -q --quiet, -v --verbose,\n"
    "  -h --help\n";

// "lpir-gseg 0.1.0 (commit abc123)", then one line per backend: the CPU reference is always
// there; Vulkan names the device `segment --backend vulkan` takes, or says why there is none.
int PrintVersion() {
  std::string commit = LPIR_GIT_COMMIT;
  std::printf("lpir-gseg %s (commit %s)\n", LPIR_VERSION,
              commit.empty() ? "unknown" : commit.c_str());
  std::printf("backend cpu: available (the reference)\n");
  std::string vulkan;
  lpir::vk::Result<lpir::vk::Instance> instance = lpir::vk::Instance::Create({});
  if (!instance.ok()) {
    vulkan = "unavailable: " + instance.error().message;
  } else {
    lpir::vk::Result<lpir::vk::Device> device = lpir::vk::Device::Create(instance.value());
    vulkan = device.ok() ? "available: " + device.value().name()
                         : "unavailable: " + device.error().message;
  }
  std::printf("backend vulkan: %s\n", vulkan.c_str());
  return lpir::kExitOk;
}

struct Command {
  const char* name;
  int (*run)(int, char**);
};
const Command kCommands[] = {{"segment", lpir::RunSegment},   {"evaluate", lpir::RunEvaluate},
                             {"simulate", lpir::RunSimulate}, {"calibrate", lpir::RunCalibrate},
                             {"demo", lpir::RunDemo},         {"devices", lpir::RunDevices},
                             {"bench", lpir::RunBench},       {"topics", lpir::RunTopics}};

// The command called `name`, or null.
const Command* FindCommand(const char* name) {
  for (const Command& c : kCommands)
    if (!std::strcmp(name, c.name)) return &c;
  return nullptr;
}

// " (did you mean segment?)" for a mistyped command, or "".
std::string CommandSuggestion(const char* typed) {
  std::vector<std::string> names;
  for (const Command& c : kCommands) names.push_back(c.name);
  return lpir::DidYouMean(typed, names);
}

// Runs `c` on its arguments; what it throws becomes a message on stderr and an exit code:
// RefusedError kExitRefused, std::invalid_argument kExitUsage (with where to find the options),
// anything else kExitCannotRun (apps/cli/exit_codes.h).
int Run(const Command& c, int argc, char** argv) {
  try {
    return c.run(argc, argv);
  } catch (const lpir::RefusedError& e) {
    std::fprintf(stderr, "lpir-gseg %s: refused: %s\n", c.name, e.what());
    return lpir::kExitRefused;
  } catch (const std::invalid_argument& e) {
    std::fprintf(stderr, "lpir-gseg %s: error: %s\n(lpir-gseg help %s: its options)\n", c.name,
                 e.what(), c.name);
    return lpir::kExitUsage;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "lpir-gseg %s: error: %s\n", c.name, e.what());
    return lpir::kExitCannotRun;
  }
}

// lpir-gseg --help: the commands, then the exit codes.
int PrintOverview(std::FILE* to) {
  std::fputs(kUsage, to);
  std::fputs("\n", to);
  std::fputs(lpir::kExitCodesHelp, to);
  return lpir::kExitOk;
}

// lpir-gseg help [TOPIC]: no topic the overview; a command's name its --help, the same text;
// "exit-codes" the table. An unknown topic, or more than one, is a usage error.
int Help(int argc, char** argv) {
  if (argc == 0) return PrintOverview(stdout);
  if (argc == 1 && !std::strcmp(argv[0], "exit-codes")) {
    std::fputs(lpir::kExitCodesHelp, stdout);
    return lpir::kExitOk;
  }
  const Command* c = argc == 1 ? FindCommand(argv[0]) : nullptr;
  if (!c) {
    std::string known;
    for (const Command& k : kCommands) known += std::string(known.empty() ? "" : ", ") + k.name;
    std::fprintf(
        stderr, "lpir-gseg help: %s; known: %s, exit-codes\n",
        argc == 1
            ? ("no command '" + std::string(argv[0]) + "'" + CommandSuggestion(argv[0])).c_str()
            : "give one command (lpir-gseg help COMMAND)",
        known.c_str());
    return lpir::kExitUsage;
  }
  char help_flag[] = "--help";
  char* help_argv[] = {help_flag, nullptr};
  return Run(*c, 1, help_argv);
}
}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fputs(kUsage, stderr);
    return lpir::kExitUsage;
  }
  if (!std::strcmp(argv[1], "--help") || !std::strcmp(argv[1], "-h")) return PrintOverview(stdout);
  if (!std::strcmp(argv[1], "--version")) return PrintVersion();
  if (!std::strcmp(argv[1], "help")) return Help(argc - 2, argv + 2);
  if (const Command* c = FindCommand(argv[1])) return Run(*c, argc - 2, argv + 2);
  std::fprintf(stderr, "lpir-gseg: unknown command '%s'%s\n%s", argv[1],
               CommandSuggestion(argv[1]).c_str(), kUsage);
  return lpir::kExitUsage;
}
