// The stages split over threads (reference_cpu/threads.h) against the reference on one thread:
// every buffer of every stage byte for byte (tests/frame_compare.h) at 2, 3, 4 and 8 threads (more
// than this machine's cores included) and in the kernels' baseline build against their AVX2 one
// (reference_cpu/wide.h), on every real scan of ../shared/data with its sensor's
// profile, on a simulated street of every profile in sensors/ (the data's stand-in where it is
// absent), and on clouds smaller than the pieces; and grow's bands on a path of unknown pixels
// that crosses every band's edge many times.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <string>
#include <vector>

#include "apps/sim/scene.h"
#include "host/io/cloud_file.h"
#include "host/io/sensor_profile.h"
#include "reference_cpu/pipeline.h"
#include "reference_cpu/stages.h"
#include "reference_cpu/wide.h"
#include "tests/frame_compare.h"
#include "tests/stage_test_util.h"
#include "tests/test_util.h"

namespace fs = std::filesystem;

namespace lpir {
namespace {

const uint32_t kThreadCounts[] = {2, 3, 4, 8};

struct SensorSetup {
  Params params;
  Tables tables;
};
SensorSetup MakeSetup(const SensorProfile& sensor) {
  SensorSetup s{ParamsForSensor(sensor), {}};
  s.tables = MakeTables(sensor, s.params);
  return s;
}

// RunReference on one thread, then on one thread with the kernels' baseline build (without AVX2,
// reference_cpu/wide.h), then on each of kThreadCounts, into one frame reused from run to run
// (every stage rewrites all of its buffers), each compared with the first.
void ExpectSameAtEveryCount(const SensorSetup& s, const Cloud& cloud, const std::string& what) {
  Frame one, many;
  RunReference(cloud, s.params, s.tables, one);
  const bool wide = WideKernels();
  SetWideKernels(false);
  RunReference(cloud, s.params, s.tables, many);
  SetWideKernels(true);
  test::ExpectSameFrame(
      s.params, one, many, &cloud, what + ", baseline kernels",
      {wide ? "AVX2 kernels" : "baseline kernels (no AVX2 here)", "baseline kernels"});
  for (uint32_t threads : kThreadCounts) {
    RunReference(cloud, s.params, s.tables, many, nullptr, Threads{threads});
    const std::string label = std::to_string(threads) + " threads";
    test::ExpectSameFrame(s.params, one, many, &cloud, what + ", " + label,
                          {"1 thread", label.c_str()});
  }
}

// A real scan and its sensor's profile.
struct Scan {
  std::string file;  // below the data folder
  std::string sensor;
};
void PrintTo(const Scan& scan, std::ostream* os) { *os << scan.file << " as " << scan.sensor; }

// Every scan of ../shared/data that a profile fits: SemanticKITTI (HDL-64E), nuScenes and its
// lidarseg scenes and the PLY scans of an HDL-32E, RELLIS-3D's OS1-64 and VLP-32C; in name order.
// Empty without the data (the test below then stands in one entry that skips).
std::vector<Scan> RealScans() {
  std::vector<Scan> scans;
  const std::string data = test::DataDir();
  if (data.empty()) return {{"kitti/00/velodyne/000000.bin", "hdl64e"}};
  auto add = [&](const std::string& folder, const std::string& sensor) {
    std::error_code ec;
    for (const fs::directory_entry& e : fs::recursive_directory_iterator(data + "/" + folder, ec)) {
      const std::string name = e.path().filename().string();
      const std::string ext = e.path().extension().string();
      if (!e.is_regular_file() || (ext != ".bin" && ext != ".ply")) continue;
      if (folder == "nuscenes" && e.path().parent_path().filename() != "velodyne" &&
          name.find(".pcd.bin") == std::string::npos)
        continue;
      scans.push_back({fs::relative(e.path(), data).string(), sensor});
    }
  };
  add("kitti", "hdl64e");
  add("nuscenes", "hdl32e");
  add("hdl32e", "hdl32e");
  add("rellis3d/os1", "os1-64");
  add("rellis3d/vlp32c", "vlp32c");
  std::sort(scans.begin(), scans.end(),
            [](const Scan& a, const Scan& b) { return a.file < b.file; });
#ifdef LPIR_THREADS_TEST_EVERY
  // The ThreadSanitizer build (tests/CMakeLists.txt) looks for races, which every scan's
  // threads meet alike: every LPIR_THREADS_TEST_EVERY-th scan keeps its run short.
  std::vector<Scan> some;
  for (size_t k = 0; k < scans.size(); k += LPIR_THREADS_TEST_EVERY) some.push_back(scans[k]);
  scans.swap(some);
#endif
  return scans;
}

class RealScanThreads : public testing::TestWithParam<Scan> {};

TEST_P(RealScanThreads, EveryBufferEqualAtEveryCount) {
  const Scan scan = GetParam();
  LPIR_REQUIRE_DATA(scan.file);
  const SensorSetup s = MakeSetup(LoadSensorProfile(scan.sensor, test::SensorsDir()));
  const Cloud cloud = ReadCloud(test::DataFile(scan.file));
  ASSERT_GT(cloud.size(), 1000u);
  ExpectSameAtEveryCount(s, cloud, scan.file);
}

// "12_kitti_00_velodyne_000005_bin": letters and digits of the file's path.
std::string ScanName(const testing::TestParamInfo<Scan>& info) {
  std::string name = std::to_string(info.index) + "_";
  for (char c : info.param.file) name += std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
  return name;
}
INSTANTIATE_TEST_SUITE_P(Data, RealScanThreads, testing::ValuesIn(RealScans()), ScanName);

class ProfileThreads : public testing::TestWithParam<std::string> {};

// The urban street of seed 1, with ring fields and without.
TEST_P(ProfileThreads, SimulatedStreetEqualAtEveryCount) {
  const SensorProfile sensor = LoadSensorProfile(GetParam(), test::SensorsDir());
  const SensorSetup s = MakeSetup(sensor);
  SimOptions o;
  o.seed = 1;
  o.kind = kUrban;
  Cloud cloud = Simulate(sensor, o).cloud;
  ASSERT_GT(cloud.size(), 1000u);
  ExpectSameAtEveryCount(s, cloud, sensor.name + " street");
  cloud.ring.clear();
  ExpectSameAtEveryCount(s, cloud, sensor.name + " street without rings");
}

std::string ProfileName(const testing::TestParamInfo<std::string>& info) {
  std::string n = info.param;
  std::replace(n.begin(), n.end(), '-', '_');
  return n;
}
INSTANTIATE_TEST_SUITE_P(EveryProfile, ProfileThreads,
                         testing::ValuesIn(KnownSensorProfiles(test::SensorsDir())), ProfileName);

// Fewer points than threads, no points, and random clouds with invalid and noise points.
TEST(Threads, SmallAndEmptyClouds) {
  const SensorSetup s = MakeSetup(test::SmallSensor());
  for (size_t n : {size_t(0), size_t(1), size_t(3), size_t(7), size_t(5000), size_t(20000)})
    ExpectSameAtEveryCount(s, test::StreetLikeCloud(n, uint32_t(n) + 1),
                           std::to_string(n) + " points");
}

// Grow on a hand-made image of 64 rows (bands of 8 rows on 8 threads): one seed at the top of
// column 0 and a path of unknown pixels down column 0, up column 2, down column 4 and so on,
// joined at alternate ends through the odd columns, everything else non-ground. The path crosses
// every band's edge once per column, so the bands hand the growth to each other round after
// round; all of it grows, and every buffer matches one thread's.
TEST(Threads, GrowAcrossBandsRoundAfterRound) {
  SensorProfile sensor = test::SmallSensor();
  sensor.beams = 64;
  sensor.width = 64;
  sensor.elevation_deg.clear();
  for (unsigned b = 0; b < sensor.beams; ++b) sensor.elevation_deg.push_back(2.0f - 0.25f * b);
  const Params p = ParamsForSensor(sensor);
  const uint32_t w = p.width, h = p.beams;
  Frame in;
  in.pixel_fused.assign(w * h, kPixNonGround);
  in.f_height.assign(w * h, -1.7f);
  in.f_range.assign(w * h, 10.0f);
  size_t path = 0;
  for (uint32_t u = 0; u < w; u += 2) {
    for (uint32_t v = 0; v < h; ++v) in.pixel_fused[v * w + u] = kPixUnknown, ++path;
    if (u + 2 < w) {  // the joint: at the bottom after a column going down, else at the top
      const uint32_t v = (u / 2) % 2 == 0 ? h - 1 : 0;
      in.pixel_fused[v * w + u + 1] = kPixUnknown, ++path;
    }
  }
  in.pixel_fused[0] = kPixGround;
  Frame one = in;
  Grow(p, one);
  size_t grown = 0;
  for (uint32_t x : one.pixel_grown) grown += x == kPixGround;
  EXPECT_EQ(grown, path);
  for (uint32_t threads : kThreadCounts) {
    Frame many = in;
    Grow(p, many, Threads{threads});
    const std::string label = std::to_string(threads) + " threads";
    test::ExpectSameFrame(p, one, many, nullptr, "serpentine, " + label,
                          {"1 thread", label.c_str()});
  }
}

TEST(Threads, PiecesCoverTheRangeInOrder) {
  for (uint32_t n : {0u, 1u, 5u, 64u, 1000u, 123457u})
    for (uint32_t pieces : {1u, 2u, 3u, 8u, 13u}) {
      uint32_t next = 0;
      for (uint32_t k = 0; k < pieces; ++k) {
        const Range r = PieceOf(n, pieces, k);
        EXPECT_EQ(r.begin, next) << n << " in " << pieces;
        EXPECT_LE(r.end - r.begin, n / pieces + 1);
        next = r.end;
      }
      EXPECT_EQ(next, n);
    }
  EXPECT_EQ(PiecesFor(Threads{8}, 100000, 4096), 8u);
  EXPECT_EQ(PiecesFor(Threads{8}, 10000, 4096), 2u);  // no piece under 4096 items
  EXPECT_EQ(PiecesFor(Threads{8}, 10, 4096), 1u);
  EXPECT_EQ(PiecesFor(Threads{1}, 100000, 1), 1u);
}

}  // namespace
}  // namespace lpir
