// lpir-gseg devices: the Vulkan devices this machine offers, one line each (index, name, type,
// API version, usable or why not), what `segment` takes without --device under --backend auto (a
// GPU, else the CPU reference) and under --backend vulkan (any usable device). Exit code
// kExitCannotRun, the reason on stderr, when no device is usable.
#include <cstdio>
#include <string>
#include <vector>

#include "apps/cli/args.h"
#include "apps/cli/commands.h"
#include "apps/cli/exit_codes.h"
#include "host/vk/context.h"
#include "host/vk/device.h"
#include "host/vk/instance.h"

namespace lpir {

int RunDevices(int argc, char** argv) {
  const Args args(argc, argv, {"--help"}, {});
  if (args.Has("--help")) {
    std::fputs("usage: lpir-gseg devices\n", stdout);
    std::fputs(kExitCodesLine, stdout);
    return kExitOk;
  }
  vk::Result<vk::Instance> instance = vk::Instance::Create({});
  if (!instance.ok()) {
    std::fprintf(stderr, "lpir-gseg devices: no Vulkan device: %s\n",
                 instance.error().message.c_str());
    return kExitCannotRun;
  }
  const vk::Result<std::vector<std::string>> lines = vk::Device::Describe(instance.value());
  if (!lines.ok()) {
    std::fprintf(stderr, "lpir-gseg devices: no Vulkan device: %s\n",
                 lines.error().message.c_str());
    return kExitCannotRun;
  }
  for (const std::string& line : lines.value()) std::printf("%s\n", line.c_str());
  vk::Result<vk::Device> chosen = vk::Device::Create(instance.value());
  if (!chosen.ok()) {
    std::fprintf(stderr, "lpir-gseg devices: none usable: %s\n", chosen.error().message.c_str());
    return kExitCannotRun;
  }
  const vk::Result<vk::Device> gpu = vk::Device::Create(instance.value(), "", /*gpu_only=*/true);
  const std::string by_auto =
      gpu.ok() ? gpu.value().name() : "the CPU reference: " + gpu.error().message;
  std::printf("default (segment --backend auto without --device): %s\n", by_auto.c_str());
  std::printf("segment --backend vulkan without --device: %s\n", chosen.value().name().c_str());
  return kExitOk;
}

}  // namespace lpir
