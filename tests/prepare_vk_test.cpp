// Stage 1, prepare, on Vulkan (shaders/prepare.comp) against the CPU reference
// (reference_cpu/prepare.cpp): every output buffer byte for byte, on random clouds of 1 to 200000
// points full of invalid points (NaN, Inf, origin, out of range, bad rings, subnormals) and on the
// real scans when ../shared/data is present.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "host/gpu/prepare.h"
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
std::string ValueText(float f) { return FloatText(f); }

std::string PointText(const Cloud& cloud, size_t i) {
  std::string s = "point " + std::to_string(i) + ": x " + FloatText(cloud.x(i)) + ", y " +
                  FloatText(cloud.y(i)) + ", z " + FloatText(cloud.z(i)) + ", intensity " +
                  FloatText(cloud.intensity(i));
  if (!cloud.ring.empty()) s += ", ring " + std::to_string(cloud.ring[i]);
  return s;
}

// Byte equality of one per-point buffer; on a mismatch, the first differing point in full.
template <class T>
::testing::AssertionResult SameBytes(const char* buffer, const std::vector<T>& cpu,
                                     const std::vector<T>& gpu, const Cloud& cloud,
                                     uint64_t* compared) {
  if (cpu.size() != gpu.size())
    return ::testing::AssertionFailure() << "prepare: buffer " << buffer << " has " << gpu.size()
                                         << " elements on the GPU, " << cpu.size() << " on the CPU";
  *compared += cpu.size();
  if (cpu.empty() || std::memcmp(cpu.data(), gpu.data(), cpu.size() * sizeof(T)) == 0)
    return ::testing::AssertionSuccess();
  size_t first = cpu.size(), count = 0;
  for (size_t i = 0; i < cpu.size(); ++i)
    if (std::memcmp(&cpu[i], &gpu[i], sizeof(T)) != 0) {
      if (first == cpu.size()) first = i;
      ++count;
    }
  return ::testing::AssertionFailure()
         << "prepare: buffer " << buffer << " differs at element " << first << " (" << count
         << " of " << cpu.size() << " differ): CPU " << ValueText(cpu[first]) << ", GPU "
         << ValueText(gpu[first]) << "; " << PointText(cloud, first);
}

// Stage 1 on the GPU, as lpir::Prepare(cloud, p, f): fills f.n, f.flags, f.zt and f.r2.
vk::Status PrepareOnGpu(const vk::Device& device, const Cloud& cloud, const Params& p, Frame& f,
                        double* gpu_ns) {
  const uint32_t n = uint32_t(cloud.size());
  Params params = p;
  params.has_ring = cloud.ring.empty() ? 0u : 1u;  // as reference_cpu/pipeline.cpp sets it
  test::StageHarness h(device, "prepare");
  vk::PrepareBuffers b;
  b.params = h.Uniform(params);
  b.points = h.In("xyzi", cloud.xyzi, 4 * size_t(n));
  b.ring = h.In("ring", cloud.ring, params.has_ring ? n : 0);
  b.flags = h.Out(&f.flags, n);
  b.zt = h.Out(&f.zt, n);
  b.r2 = h.Out(&f.r2, n);
  f.n = n;
  return h.Run<vk::PrepareStage>(
      b, [&](const vk::PrepareStage& s, vk::CommandBuffer& cmd) { return s.Record(cmd, n); },
      gpu_ns);
}

bool Subnormal(float f) { return (exact::Bits(f) & 0x7F800000u) == 0 && (exact::Bits(f) << 1); }

// Runs both sides and compares flags, zt and r2. Returns the number of values compared;
// `subnormals` (optional) gets the number of subnormal outputs of the reference.
uint64_t ExpectSamePrepare(const vk::Context& context, const Cloud& cloud, const Params& p,
                           size_t* subnormals = nullptr) {
  Frame cpu, gpu;
  Prepare(cloud, p, cpu);
  double gpu_ns = 0;
  const vk::Status status = PrepareOnGpu(context.device(), cloud, p, gpu, &gpu_ns);
  EXPECT_TRUE(status.ok()) << status.message();
  if (!status.ok()) return 0;
  EXPECT_EQ(gpu.n, cpu.n);
  uint64_t compared = 0;
  EXPECT_TRUE(SameBytes("flags", cpu.flags, gpu.flags, cloud, &compared));
  EXPECT_TRUE(SameBytes("zt", cpu.zt, gpu.zt, cloud, &compared));
  EXPECT_TRUE(SameBytes("r2", cpu.r2, gpu.r2, cloud, &compared));
  size_t valid = 0, noise = 0, tiny = 0;
  for (uint32_t f : cpu.flags) valid += (f & kPointValid) != 0, noise += (f & kPointNoise) != 0;
  for (uint32_t i = 0; i < cpu.n; ++i) tiny += Subnormal(cpu.zt[i]);
  if (subnormals) *subnormals = tiny;
  std::printf(
      "[prepare] %zu points (%zu valid, %zu noise, %zu subnormal outputs): %llu values "
      "compared, GPU %.3f ms\n",
      cloud.size(), valid, noise, tiny, static_cast<unsigned long long>(compared), gpu_ns / 1e6);
  return compared;
}

// A random cloud: mostly ordinary points, and about a third of every kind of point stage 1 must
// reject or treat with care.
Cloud RandomCloud(size_t n, bool with_ring, const Params& p, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> xy(-130.0f, 130.0f), height(-4.0f, 4.0f), unit(0.0f, 1.0f);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  const float sub = exact::FromBits(0x00012345u);  // a subnormal
  const float min_range = std::sqrt(p.min_range2), max_range = std::sqrt(p.max_range2);
  Cloud cloud;
  cloud.xyzi.reserve(4 * n);
  for (size_t i = 0; i < n; ++i) {
    float x = xy(rng), y = xy(rng), z = height(rng), in = unit(rng) * 255.0f;
    // clang-format off
    switch (rng() % 40) {
      case 0: x = nan; break;
      case 1: y = -inf; break;
      case 2: z = inf; break;
      case 3: in = nan; break;
      case 4: x = 0.0f, y = -0.0f, z = 0.0f; break;           // the origin (no return)
      case 5: x = -0.0f, y = 0.0f, z = -0.0f, in = 0.0f; break;
      case 6: x = min_range, y = 0.0f; break;                 // on the range limits
      case 7: x = 0.0f, y = -max_range; break;
      case 8: x = std::nextafter(max_range, 1e9f), y = 0.0f; break;
      case 9: z = 1e30f; break;                               // absurd height
      case 10: x = 1e20f; break;                              // r2 overflows to Inf
      case 11: z = p.h_noise - unit(rng), in = unit(rng) * 2.0f; break;  // reflection noise
      case 12: z = -max_range; break;                         // z^2 on the limit
      case 13: x = sub, y = 10.0f, z = sub; break;            // subnormal coordinates
      case 14: in = sub; break;                               // subnormal intensity
      case 15: x = 1e-20f, y = 10.0f; break;                  // x * x underflows
      case 16: z = -0.0f; break;
      case 17: x = 0.5f * min_range, y = 0.0f, z = 0.0f; break;  // too near
      case 18: in = -inf; break;
      case 19: x = std::round(x), y = std::round(y), z = std::round(z); break;
      default: break;
    }
    // clang-format on
    cloud.Push(x, y, z, in);
    if (with_ring) cloud.ring.push_back(int32_t(rng() % (p.beams + 4)) - 2);
  }
  return cloud;
}

Params TiltedParams() {
  SensorProfile s = test::SmallSensor();
  s.k_xz = 0.05f;
  s.k_yz = -0.02f;
  return ParamsForSensor(s);
}

struct CloudCase {
  size_t points;
  bool ring;
};

class PrepareVk : public test::VkTest, public ::testing::WithParamInterface<CloudCase> {};

TEST_P(PrepareVk, RandomCloudMatchesTheReference) {
  const CloudCase c = GetParam();
  const Params p = TiltedParams();
  const Cloud cloud = RandomCloud(c.points, c.ring, p, uint32_t(c.points * 2 + c.ring));
  size_t subnormals = 0;
  EXPECT_EQ(ExpectSamePrepare(context(), cloud, p, &subnormals), 3 * c.points);
  if (c.points >= 4000) {
    EXPECT_EQ(subnormals, 0u) << "prepare flushes subnormal outputs (cases 13-15 feed them)";
  }
}

INSTANTIATE_TEST_SUITE_P(
    Sizes, PrepareVk,
    ::testing::Values(CloudCase{1, false}, CloudCase{2, true}, CloudCase{63, false},
                      CloudCase{64, true}, CloudCase{65, false}, CloudCase{1000, true},
                      CloudCase{4099, false}, CloudCase{65536, true}, CloudCase{120001, false},
                      CloudCase{200000, true}, CloudCase{200000, false}),
    [](const ::testing::TestParamInfo<CloudCase>& info) {
      return std::to_string(info.param.points) + (info.param.ring ? "_ring" : "_xyzi");
    });

class PrepareVkScan : public test::VkTest {};

TEST_F(PrepareVkScan, UntiltedDefaultsMatchTheReference) {
  const Params p = DefaultParams();
  const Cloud cloud = RandomCloud(100000, false, p, 99);
  size_t subnormals = 0;
  EXPECT_EQ(ExpectSamePrepare(context(), cloud, p, &subnormals), 300000u);
  EXPECT_EQ(subnormals, 0u);  // untilted: zt = z - 0 with a subnormal z is flushed on both sides
}

TEST_F(PrepareVkScan, Kitti07Frame964) {
  LPIR_REQUIRE_DATA("kitti/07/velodyne/000964.bin");
  const Cloud cloud = ReadKittiBin(test::DataFile("kitti/07/velodyne/000964.bin"));
  const Params p = ParamsForSensor(LoadSensorProfile("hdl64e", test::SensorsDir()));
  EXPECT_EQ(ExpectSamePrepare(context(), cloud, p), 3 * cloud.size());
}

TEST_F(PrepareVkScan, KittiUnknownFrame56) {
  LPIR_REQUIRE_DATA("kitti/unknown/velodyne/000056.bin");
  const Cloud cloud = ReadKittiBin(test::DataFile("kitti/unknown/velodyne/000056.bin"));
  const Params p = ParamsForSensor(LoadSensorProfile("hdl64e", test::SensorsDir()));
  EXPECT_EQ(ExpectSamePrepare(context(), cloud, p), 3 * cloud.size());
}

TEST_F(PrepareVkScan, NuScenesSweepWithRings) {
  const char* file = "nuscenes/n015-2018-07-24-11-22-45+0800__LIDAR_TOP__1532402927647951.pcd.bin";
  LPIR_REQUIRE_DATA(file);
  const Cloud cloud = ReadKittiBin(test::DataFile(file), BinLayout::kNuScenes5);
  ASSERT_EQ(cloud.ring.size(), cloud.size());
  const Params p = ParamsForSensor(LoadSensorProfile("hdl32e", test::SensorsDir()));
  EXPECT_EQ(ExpectSamePrepare(context(), cloud, p), 3 * cloud.size());
}

TEST_F(PrepareVkScan, Rellis3dOuster) {  // 53,364 of its 131,072 points are 0,0,0: no return
  LPIR_REQUIRE_DATA("rellis3d/os1/000104.bin");
  const Cloud cloud = ReadKittiBin(test::DataFile("rellis3d/os1/000104.bin"));
  const Params p = ParamsForSensor(LoadSensorProfile("os1-64", test::SensorsDir()));
  EXPECT_EQ(ExpectSamePrepare(context(), cloud, p), 3 * cloud.size());
}

}  // namespace
}  // namespace lpir
