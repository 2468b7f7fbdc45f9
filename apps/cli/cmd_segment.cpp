// lpir-gseg segment INPUT... --sensor NAME --out DIR [options]: labels every point of every input
// cloud (files, or folders of them) and writes DIR/<stem>.label, or the cloud with a label field.
// A file that cannot be read or segmented is reported and skipped; the exit code is then 1 and the
// last line counts the failures.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "apps/cli/args.h"
#include "apps/cli/commands.h"
#include "apps/cli/progress.h"
#include "apps/cli/truth.h"
#include "apps/viz/images.h"
#include "host/io/cloud_file.h"
#include "host/io/io_error.h"
#include "host/io/label_file.h"
#include "host/io/sensor_profile.h"
#include "host/segmenter.h"

namespace fs = std::filesystem;

namespace lpir {
namespace {

const char kHelp[] =
    "usage: lpir-gseg segment INPUT... --sensor NAME --out DIR [options]\n"
    "  INPUT            cloud files (.bin KITTI, .pcd, .ply) or folders of them\n"
    "  --sensor NAME    sensor profile (hdl64e, hdl32e, vlp32c, os1-64, ...) or a profile file\n"
    "  --out DIR        where DIR/<stem>.label (uint32 per point: 1 ground, 0 non-ground) go\n"
    "  --format F       label (default), pcd or ply: the cloud with a label field instead\n"
    "  --nuscenes       .bin files hold 5 floats per point (x y z intensity ring); files named\n"
    "                   *.pcd.bin are read that way without it, other .bin files as KITTI\n"
    "  --images         also write pictures of every stage to DIR/images/\n"
    "  --gt PATH        ground truth .label file or folder (matched by stem) for the pictures\n"
    "  --max-points N   largest cloud accepted (default 1048576)\n"
    "  --quiet          no per-frame lines\n";

// Input clouds: files as given, folders expanded to their cloud files in name order.
std::vector<std::string> ListInputs(const std::vector<std::string>& inputs) {
  std::vector<std::string> files;
  for (const std::string& in : inputs) {
    std::error_code ec;
    if (fs::is_directory(in, ec)) {
      std::vector<std::string> found;
      for (const auto& entry : fs::directory_iterator(in, ec))
        if (entry.is_regular_file() && IsCloudFile(entry.path().string()))
          found.push_back(entry.path().string());
      if (found.empty()) throw std::invalid_argument(in + ": folder holds no cloud files");
      std::sort(found.begin(), found.end());
      files.insert(files.end(), found.begin(), found.end());
    } else {
      files.push_back(in);  // a missing file is reported when it is read
    }
  }
  return files;
}

}  // namespace

int RunSegment(int argc, char** argv) {
  const Args args(argc, argv, {"--images", "--nuscenes", "--quiet", "--help"},
                  {"--sensor", "--out", "--format", "--gt", "--max-points"});
  if (args.Has("--help")) {
    std::fputs(kHelp, stdout);
    return 0;
  }
  if (args.positional().empty()) throw std::invalid_argument("no INPUT given\n" + std::string(kHelp));
  const std::string format = args.Get("--format", "label");
  if (format != "label" && format != "pcd" && format != "ply")
    throw std::invalid_argument("--format must be label, pcd or ply, not '" + format + "'");
  const double max_points = args.GetNumber("--max-points", double(kDefaultMaxPoints));
  if (!(max_points >= 1) || max_points > 1e9)
    throw std::invalid_argument("--max-points must be between 1 and 1e9");
  const std::string out_dir = args.Require("--out");
  Segmenter segmenter(LoadSensorProfile(args.Require("--sensor"), SensorsDir()),
                      size_t(max_points));
  const std::vector<std::string> files = ListInputs(args.positional());
  fs::create_directories(out_dir);
  ReadOptions read_options;
  if (args.Has("--nuscenes")) read_options.bin_layout = BinLayout::kNuScenes5;
  const bool quiet = args.Has("--quiet");

  std::printf("segmenting %zu file%s with sensor '%s' on the CPU reference\n", files.size(),
              files.size() == 1 ? "" : "s", segmenter.sensor().name.c_str());
  Progress progress(files.size(), files.size() > 1);
  size_t failures = 0;
  for (const std::string& file : files) {
    const std::string stem = fs::path(file).stem().string();
    try {
      const Cloud cloud = ReadCloud(file, read_options);
      const auto t0 = std::chrono::steady_clock::now();
      const Frame& frame = segmenter.Segment(cloud);
      const double ms =
          std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
      size_t ground = 0, invalid = 0;
      for (uint32_t i = 0; i < frame.n; ++i) {
        ground += frame.label[i];
        invalid += frame.why[i] == kWhyInvalid;
      }
      if (format == "label") {
        std::vector<uint32_t> labels(frame.label.begin(), frame.label.end());
        WriteLabelFile((fs::path(out_dir) / (stem + ".label")).string(), labels);
      } else {
        WriteLabelledCloud((fs::path(out_dir) / (stem + "." + format)).string(), cloud, frame.label,
                           format == "pcd" ? CloudFormat::kPcd : CloudFormat::kPly);
      }
      if (args.Has("--images")) {
        std::vector<uint8_t> truth;
        if (args.Has("--gt")) truth = LoadTruth(args.Get("--gt"), stem, cloud.size());
        WriteImages((fs::path(out_dir) / "images").string(), stem, cloud, frame,
                    segmenter.params(), truth.empty() ? nullptr : &truth);
      }
      if (!quiet) {
        std::printf("%s: %zu points, %.1f %% ground, %.2f ms", stem.c_str(), cloud.size(),
                    cloud.size() ? 100.0 * double(ground) / double(cloud.size()) : 0.0, ms);
        if (invalid)
          std::printf(" (%zu invalid points: NaN/Inf, at the origin or out of range; non-ground)",
                      invalid);
        std::printf("\n");
      }
    } catch (const IoError& e) {  // names the file already
      ++failures;
      std::fprintf(stderr, "lpir-gseg segment: error: %s\n", e.what());
    } catch (const std::exception& e) {
      ++failures;
      std::fprintf(stderr, "lpir-gseg segment: error: %s: %s\n", file.c_str(), e.what());
    }
    progress.Step(stem);
  }
  if (failures) {
    std::fprintf(stderr, "lpir-gseg segment: %zu of %zu files failed\n", failures, files.size());
    return 1;
  }
  std::printf("wrote %zu %s file%s to %s\n", files.size(), format.c_str(),
              files.size() == 1 ? "" : "s", out_dir.c_str());
  return 0;
}

}  // namespace lpir
