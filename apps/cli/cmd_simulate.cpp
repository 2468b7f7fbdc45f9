// `lpir-gseg simulate`: one scan of the synthetic street (or a flat calibration scene) seen by a
// sensor profile, written as a KITTI .bin and a SemanticKITTI .label file.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <stdexcept>
#include <string>

#include "apps/cli/args.h"
#include "apps/cli/commands.h"
#include "apps/cli/exit_codes.h"
#include "apps/sim/scene.h"
#include "host/io/kitti_bin.h"
#include "host/io/label_file.h"
#include "host/io/sensor_profile.h"

namespace lpir {

namespace {

const char kSimulateUsage[] =
    "usage: lpir-gseg simulate --sensor NAME --seed N [--pitch DEG] [--roll DEG]\n"
    "                          [--scene urban|flat|flat-objects] [--range-noise M]\n"
    "                          --out FILE.bin --labels FILE.label\n"
    "  Pitch and roll follow apps/sim/scene.h: positive pitch makes the ground rise ahead (+x),\n"
    "  positive roll makes it rise to the left (+y); |angle| <= 30 degrees.\n"
    "  (--opt VALUE and --opt=VALUE alike; -s --sensor, -o --out)\n";

uint32_t ParseSeed(const std::string& text) {
  bool digits = !text.empty() && text.size() <= 10;
  for (char c : text) digits = digits && c >= '0' && c <= '9';
  if (!digits || std::stoull(text) > 0xFFFFFFFFull)
    throw std::invalid_argument("--seed expects an integer in [0, 4294967295], got '" + text + "'");
  return static_cast<uint32_t>(std::stoull(text));
}

float ParseAngle(const Args& args, const std::string& key) {
  const double deg = args.GetNumber(key, 0.0);
  if (!std::isfinite(deg) || std::abs(deg) > 30.0)
    throw std::invalid_argument(key + " must lie within [-30, 30] degrees, got '" + args.Get(key) +
                                "'");
  return static_cast<float>(deg);
}

SceneKind ParseScene(const std::string& name) {
  if (name == "urban") return kUrban;
  if (name == "flat") return kFlat;
  if (name == "flat-objects") return kFlatWithObjects;
  throw std::invalid_argument("--scene expects urban, flat or flat-objects, got '" + name + "'");
}

}  // namespace

int RunSimulate(int argc, char** argv) {
  const Args args(
      argc, argv, {"--help"},
      {"--sensor", "--seed", "--pitch", "--roll", "--scene", "--range-noise", "--out", "--labels"});
  if (args.Has("--help")) {
    std::fputs(kSimulateUsage, stdout);
    std::fputs(kExitCodesLine, stdout);
    return kExitOk;
  }
  if (!args.positional().empty())
    throw std::invalid_argument("unexpected argument '" + args.positional()[0] + "'\n" +
                                kSimulateUsage);
  const std::string sensor_name = args.Require("--sensor");
  const std::string out_path = args.Require("--out");
  const std::string label_path = args.Require("--labels");

  SimOptions options;
  options.seed = ParseSeed(args.Require("--seed"));
  options.pitch_deg = ParseAngle(args, "--pitch");
  options.roll_deg = ParseAngle(args, "--roll");
  options.kind = ParseScene(args.Get("--scene", "urban"));
  const double noise = args.GetNumber("--range-noise", options.range_noise_m);
  if (!(noise >= 0.0 && noise <= 1.0))
    throw std::invalid_argument("--range-noise must lie within [0, 1] m");
  options.range_noise_m = static_cast<float>(noise);

  const SensorProfile sensor = LoadSensorProfile(sensor_name, SensorsDir());
  const SimScan scan = Simulate(sensor, options);
  WriteKittiBin(out_path, scan.cloud);
  WriteLabelFile(label_path, scan.labels);

  size_t ground = 0;
  for (uint32_t label : scan.labels) ground += IsSimGroundClass(label) ? 1 : 0;
  std::printf("simulate: %s seed %u: %zu points, %zu ground (%.1f %%) -> %s, %s\n",
              sensor.name.c_str(), options.seed, scan.cloud.size(), ground,
              scan.cloud.size() ? 100.0 * ground / scan.cloud.size() : 0.0, out_path.c_str(),
              label_path.c_str());
  return kExitOk;
}

}  // namespace lpir
