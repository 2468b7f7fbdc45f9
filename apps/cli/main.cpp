// lpir-gseg: LiDAR ground segmentation (LPIR-GSeg). Dispatches to one subcommand.
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <string>

#include "apps/cli/commands.h"
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
    "usage: lpir-gseg <command> [options]\n"
    "  segment INPUT... --sensor NAME --out DIR [--backend auto|vulkan|cpu] [--device D]\n"
    "          [--timings] [--format label|pcd|ply] [--images] [--gt PATH]\n"
    "  evaluate --pred DIR --gt PATH... --protocol dg|pp|pw|gg|all [--json] [--by-class]\n"
    "           [--by-range] [--ontology semantickitti|rellis3d]\n"
    "  simulate --sensor NAME --seed N [--pitch DEG --roll DEG] --out FILE.bin --labels "
    "FILE.label\n"
    "  calibrate SCAN... --sensor NAME [--write-profile FILE] [--json]\n"
    "  demo [--out DIR] [--backend auto|vulkan|cpu]\n"
    "  devices\n"
    "  bench [--runs N] [--json]\n"
    "  topics DRIVE     the topics of a recorded drive (.mcap, .db3, .bag)\n"
    "  --version        the version, the git commit built and which backends this machine has\n";

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
  return 0;
}
}  // namespace

int main(int argc, char** argv) {
  if (argc < 2 || !std::strcmp(argv[1], "--help") || !std::strcmp(argv[1], "-h")) {
    std::fputs(kUsage, argc < 2 ? stderr : stdout);
    return argc < 2 ? 2 : 0;
  }
  if (!std::strcmp(argv[1], "--version")) return PrintVersion();
  struct Command {
    const char* name;
    int (*run)(int, char**);
  };
  const Command commands[] = {{"segment", lpir::RunSegment},   {"evaluate", lpir::RunEvaluate},
                              {"simulate", lpir::RunSimulate}, {"calibrate", lpir::RunCalibrate},
                              {"demo", lpir::RunDemo},         {"devices", lpir::RunDevices},
                              {"bench", lpir::RunBench},       {"topics", lpir::RunTopics}};
  for (const Command& c : commands) {
    if (!std::strcmp(argv[1], c.name)) {
      try {
        return c.run(argc - 2, argv + 2);
      } catch (const std::exception& e) {
        std::fprintf(stderr, "lpir-gseg %s: error: %s\n", c.name, e.what());
        return 1;
      }
    }
  }
  std::fprintf(stderr, "lpir-gseg: unknown command '%s'\n%s", argv[1], kUsage);
  return 2;
}
