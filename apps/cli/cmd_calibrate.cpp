// lpir-gseg calibrate SCAN... --sensor NAME [--write-profile FILE] [--json] [options]: the mount
// tilt (paper III-B.3, eqs. 2-3) from scans of flat ground, by host/eval/calibrate.h, and
// optionally the sensor profile with it, for `segment --sensor FILE`. Exit codes
// (apps/cli/exit_codes.h): 0 accepted, 3 refused (the reason on stderr: what was measured and
// what to do; no profile written), 4 errors (unreadable scan, bad profile file), 2 usage.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <vector>

#include "apps/cli/args.h"
#include "apps/cli/commands.h"
#include "apps/cli/exit_codes.h"
#include "apps/cli/help_text.h"
#include "host/eval/calibrate.h"
#include "host/io/cloud_file.h"
#include "host/io/sensor_profile.h"

namespace lpir {
namespace {

const char kHelp[] =
    "usage: lpir-gseg calibrate SCAN... --sensor NAME [--write-profile FILE] [--json]\n"
    "                           [--set-height] [--max-b-diff M] [--min-inlier-fraction F]\n"
    "                           [--max-distance M]\n"
    "  (--opt VALUE and --opt=VALUE alike; -s --sensor)\n"
    "  SCAN...            scans of flat, open ground ({clouds}; several are pooled)\n"
    "  --sensor NAME      sensor profile (name or file): beam width, sensor_height, ranges\n"
    "  --write-profile F  on success, write the profile with k_xz k_yz b_x b_y to F\n"
    "                     (then: lpir-gseg segment ... --sensor F)\n"
    "  --set-height       also set the written profile's sensor_height to (b_x + b_y) / 2\n"
    "  --max-b-diff M     largest |b_x - b_y| accepted, metres (default 0.01: paper III-B.3)\n"
    "  --min-inlier-fraction F  flatness: share of each line's gated points that must lie\n"
    "                     within 5 cm of it (default 0.6)\n"
    "  --max-distance M   farthest planar distance used, metres (default 30)\n"
    "  --nuscenes         .bin files hold 5 floats per point\n"
    "  --json             one JSON object on stdout: accepted, refusal, reason, k_xz, k_yz,\n"
    "                     b_x, b_y, pitch_deg, roll_deg, xoz/yoz fits, band points\n"
    "Convention (apps/sim/scene.h, host/eval/calibrate.h): flat ground in the sensor frame is\n"
    "z = k_xz x + k_yz y - b; pitch = atan(k_xz) > 0: the ground rises ahead (+x); roll =\n"
    "atan(k_yz) > 0: it rises to the left (+y); b_x, b_y > 0: the sensor's height above the\n"
    "ground along its own z axis. `simulate --pitch P --roll R` reads back as P, R.\n"
    "Method: front/rear/left/right bands 3 range-image columns either side, distance and height\n"
    "gates, seeded RANSAC line fits in XOZ and YOZ with least-squares refits. Refused (exit 3)\n"
    "when too few points survive the gates, the ground is not flat enough, or |b_x - b_y| is\n"
    "above the limit.\n";

std::string JsonString(const std::string& s) {
  std::string out = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') {
      out += '\\', out += c;
    } else if (static_cast<unsigned char>(c) < 0x20) {
      char buf[8];
      std::snprintf(buf, sizeof(buf), "\\u%04x", c);
      out += buf;
    } else {
      out += c;
    }
  }
  return out + "\"";
}

std::string Num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%.9g", v);
  return buf;
}

std::string LineJson(const CalibLine& l) {
  return "{\"k\": " + Num(l.k) + ", \"b\": " + Num(l.b) +
         ", \"points\": " + std::to_string(l.points) +
         ", \"inliers\": " + std::to_string(l.inliers) +
         ", \"inlier_fraction\": " + Num(l.inlier_fraction) + ", \"rms_m\": " + Num(l.rms) + "}";
}

void PrintJson(const Calibration& c, const SensorProfile& s, const std::string& written) {
  std::string j = "{\"sensor\": " + JsonString(s.name) + ", \"scans\": " + std::to_string(c.scans) +
                  ", \"accepted\": " + (c.ok() ? "true" : "false") +
                  ", \"refusal\": " + JsonString(CalibRefusalName(c.refusal)) +
                  ", \"reason\": " + JsonString(c.reason) + ", \"k_xz\": " + Num(c.k_xz) +
                  ", \"k_yz\": " + Num(c.k_yz) + ", \"b_x\": " + Num(c.b_x) +
                  ", \"b_y\": " + Num(c.b_y) + ", \"pitch_deg\": " + Num(c.pitch_deg) +
                  ", \"roll_deg\": " + Num(c.roll_deg) + ", \"xoz\": " + LineJson(c.xoz) +
                  ", \"yoz\": " + LineJson(c.yoz) + ", \"band_points\": {";
  for (int d = 0; d < 4; ++d)
    j += std::string(d ? ", " : "") + "\"" + CalibDirectionName(d) +
         "\": " + std::to_string(c.band_points[d]);
  j += "}, \"noise_points\": " + std::to_string(c.noise_points) +
       ", \"profile_written\": " + JsonString(written) + "}\n";
  std::fputs(j.c_str(), stdout);
}

void PrintText(const Calibration& c, const SensorProfile& s) {
  std::printf(
      "calibrate: %s, %u scan%s: band points front %u, rear %u, left %u, right %u; "
      "%u reflection-noise points dropped\n",
      s.name.c_str(), c.scans, c.scans == 1 ? "" : "s", c.band_points[0], c.band_points[1],
      c.band_points[2], c.band_points[3], c.noise_points);
  if (c.xoz.inliers == 0 && c.yoz.inliers == 0) return;
  std::printf(
      "  XOZ (front + rear): k_xz %+.6f  pitch %+.4f deg  b_x %.4f m  inliers %u/%u "
      "(%.1f %%)  RMS %.2f cm\n",
      c.k_xz, c.pitch_deg, c.b_x, c.xoz.inliers, c.xoz.points, 100.0 * c.xoz.inlier_fraction,
      100.0 * c.xoz.rms);
  std::printf(
      "  YOZ (left + right): k_yz %+.6f  roll  %+.4f deg  b_y %.4f m  inliers %u/%u "
      "(%.1f %%)  RMS %.2f cm\n",
      c.k_yz, c.roll_deg, c.b_y, c.yoz.inliers, c.yoz.points, 100.0 * c.yoz.inlier_fraction,
      100.0 * c.yoz.rms);
  std::printf("  |b_x - b_y| %.2f cm; profile sensor_height %.3f m\n",
              100.0 * std::abs(c.b_x - c.b_y), s.sensor_height);
}

}  // namespace

int RunCalibrate(int argc, char** argv) {
  const Args args(
      argc, argv, {"--json", "--set-height", "--nuscenes", "--help"},
      {"--sensor", "--write-profile", "--max-b-diff", "--min-inlier-fraction", "--max-distance"});
  if (args.Has("--help")) {
    std::fputs(HelpText(kHelp).c_str(), stdout);
    std::fputs(kExitCodesLine, stdout);
    return kExitOk;
  }
  if (args.positional().empty())
    throw std::invalid_argument("no scan given: calibrate SCAN... --sensor NAME\n" +
                                HelpText(kHelp));
  const SensorProfile sensor = LoadSensorProfile(args.Require("--sensor"), SensorsDir());
  CalibrateOptions options;
  const double b_diff = args.GetNumber("--max-b-diff", options.max_b_diff);
  if (!(b_diff > 0 && b_diff <= 1))
    throw std::invalid_argument("--max-b-diff must lie in (0, 1] m");
  options.max_b_diff = float(b_diff);
  const double fraction = args.GetNumber("--min-inlier-fraction", options.min_inlier_fraction);
  if (!(fraction >= 0 && fraction <= 1))
    throw std::invalid_argument("--min-inlier-fraction must lie in [0, 1]");
  options.min_inlier_fraction = float(fraction);
  const double max_distance = args.GetNumber("--max-distance", options.max_distance);
  if (!(max_distance > options.min_distance && max_distance <= 1000))
    throw std::invalid_argument("--max-distance must lie in (" + Num(options.min_distance) +
                                ", 1000] m");
  options.max_distance = float(max_distance);

  ReadOptions read;
  if (args.Has("--nuscenes")) read.bin_layout = BinLayout::kNuScenes5;
  std::vector<Cloud> scans;
  for (const std::string& path : args.positional()) scans.push_back(ReadCloud(path, read));

  const Calibration c = Calibrate(scans, sensor, options);
  std::string written;
  if (c.ok() && args.Has("--write-profile")) {
    written = args.Get("--write-profile");
    WriteSensorProfile(written, ApplyCalibration(sensor, c, args.Has("--set-height")));
  }
  if (args.Has("--json")) {
    PrintJson(c, sensor, written);
  } else {
    PrintText(c, sensor);
  }
  if (!c.ok()) {
    std::fprintf(stderr, "lpir-gseg calibrate: refused: %s%s\n", c.reason.c_str(),
                 c.refusal == CalibRefusal::kHeightsDisagree
                     ? " (or accept a larger difference with --max-b-diff M)"
                 : c.refusal == CalibRefusal::kNotFlat
                     ? " (or accept rougher ground with --min-inlier-fraction F)"
                     : "");
    if (args.Has("--write-profile"))
      std::fprintf(stderr, "lpir-gseg calibrate: %s not written\n",
                   args.Get("--write-profile").c_str());
    return kExitRefused;
  }
  if (!args.Has("--json")) {
    std::printf("accepted: pitch %+.4f deg, roll %+.4f deg", c.pitch_deg, c.roll_deg);
    if (!written.empty()) std::printf(" -> %s", written.c_str());
    std::printf("\n");
  }
  return kExitOk;
}

}  // namespace lpir
