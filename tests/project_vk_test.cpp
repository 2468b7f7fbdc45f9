// Stage 2, project, on Vulkan (shaders/project.comp) against the CPU reference
// (reference_cpu/project.cpp): point_pixel, pixel_key and pixel_point byte for byte, both sides
// fed the reference's stage 1 outputs, on random clouds of 1 to 200000 points (invalid and noise
// points, duplicates, points on column boundary directions and on the axes, subnormal
// coordinates, with and without rings) and on the real scans when ../shared/data is present.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "host/gpu/project.h"
#include "host/io/cloud_file.h"
#include "host/io/kitti_bin.h"
#include "host/io/sensor_profile.h"
#include "reference_cpu/exact.h"
#include "reference_cpu/stages.h"
#include "tests/stage_harness.h"
#include "tests/stage_test_util.h"
#include "tests/test_util.h"
#include "tests/vk_test_util.h"

namespace lpir {
namespace {

std::string FloatText(float f) {
  char text[64];
  std::snprintf(text, sizeof(text), "%.9g (0x%08x)", double(f), exact::Bits(f));
  return text;
}
std::string ValueText(uint32_t u) {
  char text[48];
  std::snprintf(text, sizeof(text), "%u (0x%08x)", u, u);
  return text;
}

std::string PointText(const Cloud& cloud, const Frame& f, size_t i) {
  std::string s = "point " + std::to_string(i) + ": x " + FloatText(cloud.x(i)) + ", y " +
                  FloatText(cloud.y(i)) + ", z " + FloatText(cloud.z(i)) + ", flags " +
                  std::to_string(f.flags[i]) + ", r2 " + FloatText(f.r2[i]);
  if (!cloud.ring.empty()) s += ", ring " + std::to_string(cloud.ring[i]);
  return s;
}

std::string PixelText(const Params& p, size_t pix) {
  return "pixel " + std::to_string(pix) + ": row " + std::to_string(pix / p.width) + ", column " +
         std::to_string(pix % p.width);
}

// Byte equality of one buffer; on a mismatch, the first differing element with its point or pixel.
::testing::AssertionResult SameBytes(const char* buffer, bool per_point,
                                     const std::vector<uint32_t>& cpu,
                                     const std::vector<uint32_t>& gpu, const Cloud& cloud,
                                     const Frame& f, const Params& p, uint64_t* compared) {
  if (cpu.size() != gpu.size())
    return ::testing::AssertionFailure() << "project: buffer " << buffer << " has " << gpu.size()
                                         << " elements on the GPU, " << cpu.size() << " on the CPU";
  *compared += cpu.size();
  if (cpu.empty() || std::memcmp(cpu.data(), gpu.data(), cpu.size() * 4) == 0)
    return ::testing::AssertionSuccess();
  size_t first = cpu.size(), count = 0;
  for (size_t i = 0; i < cpu.size(); ++i)
    if (cpu[i] != gpu[i]) {
      if (first == cpu.size()) first = i;
      ++count;
    }
  return ::testing::AssertionFailure()
         << "project: buffer " << buffer << " differs at element " << first << " (" << count
         << " of " << cpu.size() << " differ): CPU " << ValueText(cpu[first]) << ", GPU "
         << ValueText(gpu[first]) << "; "
         << (per_point ? PointText(cloud, f, first) : PixelText(p, first));
}

// Stage 2 on the GPU, as lpir::Project(cloud, p, t, f): reads f.flags and f.r2 (stage 1), fills
// f.point_pixel, f.pixel_key and f.pixel_point.
vk::Status ProjectOnGpu(const vk::Device& device, const Cloud& cloud, const Params& p,
                        const Tables& t, Frame& f, double* gpu_ns) {
  const uint32_t n = uint32_t(cloud.size());
  const size_t pixels = size_t(p.width) * p.beams;
  Params params = p;
  params.has_ring = cloud.ring.empty() ? 0u : 1u;  // as reference_cpu/pipeline.cpp sets it
  test::StageHarness h(device, "project");
  vk::ProjectBuffers b;
  b.params = h.Uniform(params);
  b.points = h.In("xyzi", cloud.xyzi, 4 * size_t(n));
  b.ring = h.In("ring", cloud.ring, params.has_ring ? n : 0);
  b.flags = h.In("flags", f.flags, n);
  b.r2 = h.In("r2", f.r2, n);
  b.column_dir = h.In("column_dir", t.column_dir, 2 * size_t(p.width));
  b.beam_bound = h.In("beam_bound", t.beam_bound, p.beams - 1);
  b.beam_origin = h.In("beam_origin", t.beam_origin, p.beams - 1);
  b.point_pixel = h.Out(&f.point_pixel, n);
  b.pixel_key = h.Out(&f.pixel_key, pixels);
  b.pixel_point = h.Out(&f.pixel_point, pixels);
  b.project_exact = h.Scratch(vk::ProjectStage::ExactListBytes(n));
  return h.Run<vk::ProjectStage>(
      b, [&](const vk::ProjectStage& s, vk::CommandBuffer& cmd) { return s.Record(cmd, n); },
      gpu_ns);
}

// Runs the CPU Prepare, then both Projects on its outputs, and compares the three buffers.
// Returns the number of values compared.
uint64_t ExpectSameProject(const vk::Context& context, const Cloud& cloud, const Params& p,
                           const Tables& t) {
  Frame cpu;
  Prepare(cloud, p, cpu);
  Frame gpu = cpu;  // the same stage 1 bytes
  Project(cloud, p, t, cpu);
  double gpu_ns = 0;
  const vk::Status status = ProjectOnGpu(context.device(), cloud, p, t, gpu, &gpu_ns);
  EXPECT_TRUE(status.ok()) << status.message();
  if (!status.ok()) return 0;
  uint64_t compared = 0;
  EXPECT_TRUE(
      SameBytes("point_pixel", true, cpu.point_pixel, gpu.point_pixel, cloud, cpu, p, &compared));
  EXPECT_TRUE(
      SameBytes("pixel_key", false, cpu.pixel_key, gpu.pixel_key, cloud, cpu, p, &compared));
  EXPECT_TRUE(
      SameBytes("pixel_point", false, cpu.pixel_point, gpu.pixel_point, cloud, cpu, p, &compared));
  size_t valid = 0, noise = 0, filled = 0, contested = 0;
  for (uint32_t f : cpu.flags) valid += (f & kPointValid) != 0, noise += (f & kPointNoise) != 0;
  std::vector<uint32_t> per_pixel(cpu.pixel_key.size(), 0);
  for (uint32_t i = 0; i < cpu.n; ++i)
    if (cpu.point_pixel[i] != kNone && !(cpu.flags[i] & kPointNoise))
      ++per_pixel[cpu.point_pixel[i]];
  for (uint32_t c : per_pixel) filled += c != 0, contested += c > 1;
  std::printf(
      "[project] %zu points (%zu valid, %zu noise), %zu pixels (%zu filled, %zu contested): %llu "
      "values compared, GPU %.3f ms\n",
      cloud.size(), valid, noise, cpu.pixel_key.size(), filled, contested,
      static_cast<unsigned long long>(compared), gpu_ns / 1e6);
  return compared;
}

// A random cloud: ordinary points, invalid and noise points, exact duplicates of earlier points
// (ties on r2), points on column boundary directions and on the axes, subnormal coordinates.
Cloud RandomCloud(size_t n, bool with_ring, const Params& p, const Tables& t, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> xy(-110.0f, 110.0f), height(-4.0f, 4.0f), unit(0.0f, 1.0f);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  const float sub = exact::FromBits(0x00012345u);  // a subnormal
  const float min_range = std::sqrt(p.min_range2), max_range = std::sqrt(p.max_range2);
  Cloud cloud;
  cloud.xyzi.reserve(4 * n);
  for (size_t i = 0; i < n; ++i) {
    float x = xy(rng), y = xy(rng), z = height(rng), in = unit(rng) * 255.0f;
    int32_t ring = int32_t(rng() % p.beams);
    const uint32_t k = 1 + rng() % (p.width - 1);  // a column boundary
    const float scale = 1.0f + unit(rng) * 80.0f;
    // clang-format off
    switch (rng() % 32) {
      case 0: x = nan; break;
      case 1: z = inf; break;
      case 2: x = 0.0f, y = -0.0f, z = 0.0f; break;           // the origin (no return)
      case 3: x = 0.5f * min_range, y = 0.0f; break;          // too near
      case 4: x = std::nextafter(max_range, 1e9f), y = 0.0f; break;  // too far
      case 5: z = p.h_noise - unit(rng), in = unit(rng) * 2.0f; break;  // reflection noise
      case 6: case 7: case 8:                                 // a duplicate (ties)
        if (i > 0) {
          const size_t j = rng() % i;
          x = cloud.x(j), y = cloud.y(j), z = cloud.z(j), in = cloud.intensity(j);
          if (with_ring) ring = cloud.ring[j];
        }
        break;
      case 9: case 10:                                        // on a boundary direction
        x = t.column_dir[2 * k] * scale, y = t.column_dir[2 * k + 1] * scale; break;
      case 11: x = t.column_dir[2 * k], y = t.column_dir[2 * k + 1]; break;  // the entry itself
      case 12: y = 0.0f; break;                               // on the axes
      case 13: x = 0.0f; break;
      case 14: y = -0.0f; break;
      case 15: x = -0.0f; break;
      case 16: y = sub; break;                                // just off an axis
      case 17: y = -sub; break;
      case 18: x = -sub; break;
      case 19: x = 1e-20f, y = -10.0f; break;                 // products in the subnormal range
      case 20: z = 1e-21f; break;
      case 21: z = -1e-21f; break;
      case 22: z = sub; break;
      case 23: x = std::round(x), y = std::round(y), z = std::round(z); break;
      case 24: z = 0.0f; break;
      default: break;
    }
    // clang-format on
    cloud.Push(x, y, z, in);
    if (with_ring) cloud.ring.push_back(rng() % 50 == 0 ? int32_t(p.beams) : ring);  // some bad
  }
  return cloud;
}

struct Sensor {
  Params p;
  Tables t;
};

Sensor SmallSensorSetup() {
  SensorProfile s = test::SmallSensor();
  Sensor setup{ParamsForSensor(s), {}};
  setup.t = MakeTables(s, setup.p);
  return setup;
}

Sensor ProfileSensorSetup(const std::string& name) {
  const SensorProfile s = LoadSensorProfile(name, test::SensorsDir());
  Sensor setup{ParamsForSensor(s), {}};
  setup.t = MakeTables(s, setup.p);
  return setup;
}

struct CloudCase {
  size_t points;
  bool ring;
};

class ProjectVk : public test::VkTest, public ::testing::WithParamInterface<CloudCase> {};

TEST_P(ProjectVk, RandomCloudMatchesTheReference) {
  const CloudCase c = GetParam();
  const Sensor s = SmallSensorSetup();
  const Cloud cloud = RandomCloud(c.points, c.ring, s.p, s.t, uint32_t(c.points * 2 + c.ring));
  const uint64_t pixels = uint64_t(s.p.width) * s.p.beams;
  EXPECT_EQ(ExpectSameProject(context(), cloud, s.p, s.t), c.points + 2 * pixels);
}

TEST_P(ProjectVk, RandomCloudHdl64eMatchesTheReference) {  // 2048 columns, laser origins
  const CloudCase c = GetParam();
  const Sensor s = ProfileSensorSetup("hdl64e");
  const Cloud cloud = RandomCloud(c.points, c.ring, s.p, s.t, uint32_t(c.points * 3 + c.ring));
  const uint64_t pixels = uint64_t(s.p.width) * s.p.beams;
  EXPECT_EQ(ExpectSameProject(context(), cloud, s.p, s.t), c.points + 2 * pixels);
}

INSTANTIATE_TEST_SUITE_P(
    Sizes, ProjectVk,
    ::testing::Values(CloudCase{1, false}, CloudCase{2, true}, CloudCase{63, false},
                      CloudCase{64, true}, CloudCase{65, false}, CloudCase{1000, true},
                      CloudCase{4099, false}, CloudCase{65536, true}, CloudCase{120001, false},
                      CloudCase{200000, true}, CloudCase{200000, false}),
    [](const ::testing::TestParamInfo<CloudCase>& info) {
      return std::to_string(info.param.points) + (info.param.ring ? "_ring" : "_xyzi");
    });

class ProjectVkScan : public test::VkTest {};

// Every boundary direction at several scales, and the axes, in one cloud: the column walk's
// hardest inputs, many sharing a pixel (ties broken by index).
TEST_F(ProjectVkScan, BoundaryDirectionsAndAxes) {
  for (const std::string name : {"small", "hdl64e"}) {
    const Sensor s = name == "small" ? SmallSensorSetup() : ProfileSensorSetup(name);
    Cloud cloud;
    for (float scale : {1.0f, 3.0f, 7.5f, 20.0f, 20.0f, 33.3f}) {
      for (uint32_t k = 0; k < s.p.width; ++k)
        cloud.Push(s.t.column_dir[2 * k] * scale, s.t.column_dir[2 * k + 1] * scale, -1.5f, 50.0f);
      for (float a : {scale, -scale, 0.0f, -0.0f})
        for (float b : {scale, -scale, 0.0f, -0.0f}) cloud.Push(a, b, -1.0f, 10.0f);
    }
    EXPECT_GT(ExpectSameProject(context(), cloud, s.p, s.t), 0u) << name;
  }
}

TEST_F(ProjectVkScan, Kitti07Frame964) {
  LPIR_REQUIRE_DATA("kitti/07/velodyne/000964.bin");
  const Cloud cloud = ReadKittiBin(test::DataFile("kitti/07/velodyne/000964.bin"));
  const Sensor s = ProfileSensorSetup("hdl64e");
  EXPECT_EQ(ExpectSameProject(context(), cloud, s.p, s.t),
            cloud.size() + 2 * uint64_t(s.p.width) * s.p.beams);
}

TEST_F(ProjectVkScan, Rellis3dVlp32c) {
  LPIR_REQUIRE_DATA("rellis3d/vlp32c/000104.bin");
  const Cloud cloud = ReadKittiBin(test::DataFile("rellis3d/vlp32c/000104.bin"));
  const Sensor s = ProfileSensorSetup("vlp32c");
  EXPECT_EQ(ExpectSameProject(context(), cloud, s.p, s.t),
            cloud.size() + 2 * uint64_t(s.p.width) * s.p.beams);
}

TEST_F(ProjectVkScan, Hdl32ePly) {
  LPIR_REQUIRE_DATA("hdl32e/source.ply");
  const Cloud cloud = ReadCloud(test::DataFile("hdl32e/source.ply"));
  const Sensor s = ProfileSensorSetup("hdl32e");
  std::printf("[project] hdl32e/source.ply: %zu points, %s rings\n", cloud.size(),
              cloud.ring.empty() ? "no" : "with");
  EXPECT_EQ(ExpectSameProject(context(), cloud, s.p, s.t),
            cloud.size() + 2 * uint64_t(s.p.width) * s.p.beams);
}

}  // namespace
}  // namespace lpir
