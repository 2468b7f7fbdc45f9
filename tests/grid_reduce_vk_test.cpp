// Stage 3, grid reduce, on Vulkan (shaders/grid_reduce.comp) against the CPU reference
// (reference_cpu/grid_reduce.cpp): point_cell, cell_zmin, cell_zmax and cell_count byte for byte.
// Inputs: the reference's stages 1-2 on random clouds of 1 to 200000 points (invalid points,
// reflection noise, points on and beyond the ring boundaries, dense clusters that put thousands
// of points in one cell), hand-made stage 1-2 buffers (every flag value, +-0 and subnormal
// heights, r2 on every ring boundary), the simulated street with an HDL-64E profile, and the real
// scans when ../shared/data is present.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "apps/sim/scene.h"
#include "host/gpu/grid_reduce.h"
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

// What a point is: its stage 1-2 inputs (and coordinates when a cloud is at hand).
std::string PointText(const Frame& f, const Cloud* cloud, const Params& p, size_t i) {
  std::string s = "point " + std::to_string(i) + ": flags " + std::to_string(f.flags[i]) + ", r2 " +
                  FloatText(f.r2[i]) + ", zt " + FloatText(f.zt[i]) + ", pixel " +
                  ValueText(f.point_pixel[i]);
  if (f.point_pixel[i] != kNone)
    s += " (row " + std::to_string(f.point_pixel[i] / p.width) + ", column " +
         std::to_string(f.point_pixel[i] % p.width) + ")";
  if (cloud && i < cloud->size())
    s += ", x " + FloatText(cloud->x(i)) + ", y " + FloatText(cloud->y(i)) + ", z " +
         FloatText(cloud->z(i));
  return s;
}

std::string CellText(const Params& p, size_t c) {
  const size_t near = size_t(p.rings_near) * p.sectors_near;
  if (c < near)
    return "cell " + std::to_string(c) + " (near ring " + std::to_string(c / p.sectors_near) +
           ", sector " + std::to_string(c % p.sectors_near) + ")";
  return "cell " + std::to_string(c) + " (far ring " + std::to_string((c - near) / p.sectors_far) +
         " = ring " + std::to_string(p.rings_near + (c - near) / p.sectors_far) + ", sector " +
         std::to_string((c - near) % p.sectors_far) + ")";
}

// Byte equality of one buffer; on a mismatch the first differing element, both values in decimal
// and hex, and what the element is (`describe`).
template <class Describe>
::testing::AssertionResult SameBytes(const char* buffer, const std::vector<uint32_t>& cpu,
                                     const std::vector<uint32_t>& gpu, Describe describe,
                                     uint64_t* compared) {
  if (cpu.size() != gpu.size())
    return ::testing::AssertionFailure()
           << "grid_reduce: buffer " << buffer << " has " << gpu.size() << " elements on the GPU, "
           << cpu.size() << " on the CPU";
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
         << "grid_reduce: buffer " << buffer << " differs at element " << first << " (" << count
         << " of " << cpu.size() << " differ): CPU " << ValueText(cpu[first]) << ", GPU "
         << ValueText(gpu[first]) << "; " << describe(first);
}

// Stage 3 on the GPU, as lpir::GridReduce(p, t, f): reads f.flags, f.r2, f.zt and f.point_pixel
// (f.n each), fills f.point_cell, f.cell_zmin, f.cell_zmax and f.cell_count.
vk::Status GridReduceOnGpu(const vk::Device& device, const Params& p, const Tables& t, Frame& f,
                           double* gpu_ns) {
  const uint32_t n = f.n, cells = CellCount(p);
  test::StageHarness h(device, "grid_reduce");
  vk::GridReduceBuffers b;
  b.params = h.Uniform(p);
  b.flags = h.In("flags", f.flags, n);
  b.r2 = h.In("r2", f.r2, n);
  b.zt = h.In("zt", f.zt, n);
  b.point_pixel = h.In("point_pixel", f.point_pixel, n);
  b.ring_bound2 = h.In("ring_bound2", t.ring_bound2, p.rings_near + p.rings_far);
  b.point_cell = h.Out(&f.point_cell, n);
  b.cell_zmin = h.Out(&f.cell_zmin, cells);
  b.cell_zmax = h.Out(&f.cell_zmax, cells);
  b.cell_count = h.Out(&f.cell_count, cells);
  return h.Run<vk::GridReduceStage>(
      b,
      [&](const vk::GridReduceStage& s, vk::CommandBuffer& cmd) { return s.Record(cmd, n, cells); },
      gpu_ns);
}

// `in` holds the stage 1-2 buffers; runs stage 3 on both sides from them and compares. Returns the
// number of values compared.
uint64_t ExpectSameGridReduce(const vk::Context& context, const Params& p, const Tables& t,
                              const Frame& in, const Cloud* cloud, const char* what) {
  Frame cpu = in, gpu = in;
  GridReduce(p, t, cpu);
  double gpu_ns = 0;
  const vk::Status status = GridReduceOnGpu(context.device(), p, t, gpu, &gpu_ns);
  EXPECT_TRUE(status.ok()) << status.message();
  if (!status.ok()) return 0;
  uint64_t compared = 0;
  auto point = [&](size_t i) { return PointText(in, cloud, p, i); };
  auto cell = [&](size_t c) { return CellText(p, c); };
  EXPECT_TRUE(SameBytes("point_cell", cpu.point_cell, gpu.point_cell, point, &compared));
  EXPECT_TRUE(SameBytes("cell_zmin", cpu.cell_zmin, gpu.cell_zmin, cell, &compared));
  EXPECT_TRUE(SameBytes("cell_zmax", cpu.cell_zmax, gpu.cell_zmax, cell, &compared));
  EXPECT_TRUE(SameBytes("cell_count", cpu.cell_count, gpu.cell_count, cell, &compared));
  size_t in_cells = 0, occupied = 0;
  uint32_t densest = 0;
  for (uint32_t c : cpu.point_cell) in_cells += c != kNone;
  for (uint32_t n : cpu.cell_count) occupied += n != 0, densest = std::max(densest, n);
  std::printf(
      "[grid_reduce] %s: %u points (%zu in a cell), %zu of %u cells occupied, densest %u: %llu "
      "values compared, GPU %.3f ms\n",
      what, in.n, in_cells, occupied, CellCount(p), densest,
      static_cast<unsigned long long>(compared), gpu_ns / 1e6);
  return compared;
}

// Stages 1-2 of the reference on `cloud`, then the comparison.
uint64_t ExpectSameOnCloud(const vk::Context& context, const Cloud& cloud, const Params& p,
                           const Tables& t, const char* what) {
  Frame f;
  Prepare(cloud, p, f);
  Project(cloud, p, t, f);
  return ExpectSameGridReduce(context, p, t, f, &cloud, what);
}

// A 16-beam sensor seeing to 140 m, beyond the grid's last ring (120 m), slightly tilted.
SensorProfile WideSensor() {
  SensorProfile s = test::SmallSensor();
  s.max_range = 140.0f;
  s.k_xz = 0.03f;
  return s;
}

// A random cloud: a third scattered everywhere, a third in a few dense clusters (thousands of
// points in one cell), the rest special: invalid, noise, on the ring boundaries, past the grid.
Cloud RandomCloud(size_t n, bool with_ring, const Params& p, const Tables& t, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> xy(-145.0f, 145.0f), height(-4.0f, 4.0f), unit(0.0f, 1.0f);
  std::uniform_real_distribution<float> angle(0.0f, 6.2831853f);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  float cx[8], cy[8];
  for (int k = 0; k < 8; ++k) {
    const float r = 1.5f + unit(rng) * 120.0f, a = angle(rng);
    cx[k] = r * std::cos(a), cy[k] = r * std::sin(a);
  }
  Cloud cloud;
  cloud.xyzi.reserve(4 * n);
  for (size_t i = 0; i < n; ++i) {
    float x = xy(rng), y = xy(rng), z = height(rng), in = unit(rng) * 255.0f;
    const uint32_t kind = rng() % 30;
    if (kind < 10) {  // a dense cluster, 5 cm across, some exact repeats
      const int k = int(rng() % 8);
      x = cx[k] + 0.05f * unit(rng), y = cy[k] + 0.05f * unit(rng);
      if (rng() % 4 == 0) z = -1.5f;
    } else if (kind == 10) {
      x = nan;
    } else if (kind == 11) {
      y = inf;
    } else if (kind == 12) {
      x = 0.0f, y = 0.0f, z = 0.0f;
    } else if (kind == 13) {  // reflection noise
      z = p.h_noise - 0.5f * unit(rng), in = 0.0f;
    } else if (kind == 14 || kind == 15) {  // on a ring boundary: r2 == bound2 exactly, or just in
      const uint32_t ring = rng() % uint32_t(t.ring_bound2.size());
      const float r = std::sqrt(t.ring_bound2[ring]);
      x = (rng() & 1) ? r : -r, y = 0.0f;
      if (kind == 15) x = std::nextafter(x, 0.0f);
      if (rng() & 1) std::swap(x, y);
    } else if (kind == 16) {  // past the last ring, inside the sensor's range
      const float r = 121.0f + 18.0f * unit(rng), a = angle(rng);
      x = r * std::cos(a), y = r * std::sin(a);
    } else if (kind == 17) {  // on a column boundary
      x = -10.0f, y = 0.0f;
    }
    cloud.Push(x, y, z, in);
    if (with_ring) cloud.ring.push_back(int32_t(rng() % (p.beams + 2)) - 1);
  }
  return cloud;
}

struct CloudCase {
  size_t points;
  bool ring;
};

class GridReduceVk : public test::VkTest, public ::testing::WithParamInterface<CloudCase> {};

TEST_P(GridReduceVk, RandomCloudMatchesTheReference) {
  const CloudCase c = GetParam();
  const SensorProfile s = WideSensor();
  const Params p = ParamsForSensor(s);
  const Tables t = MakeTables(s, p);
  const Cloud cloud = RandomCloud(c.points, c.ring, p, t, uint32_t(c.points * 2 + c.ring + 7));
  EXPECT_EQ(ExpectSameOnCloud(context(), cloud, p, t, "random"), c.points + 3ull * CellCount(p));
}

INSTANTIATE_TEST_SUITE_P(
    Sizes, GridReduceVk,
    ::testing::Values(CloudCase{1, false}, CloudCase{2, true}, CloudCase{63, false},
                      CloudCase{64, false}, CloudCase{65, true}, CloudCase{1000, false},
                      CloudCase{4099, true}, CloudCase{65536, false}, CloudCase{120001, true},
                      CloudCase{200000, false}, CloudCase{200000, true}),
    [](const ::testing::TestParamInfo<CloudCase>& info) {
      return std::to_string(info.param.points) + (info.param.ring ? "_ring" : "_xyzi");
    });

class GridReduceVkFrame : public test::VkTest {};

// Stage 1-2 buffers made by hand: every flag value (only exactly kPointValid gets a cell), r2 on,
// just below and just above every ring boundary, heights with +-0, subnormals, infinities and
// huge values, every pixel of the image. The reference never sees most of these from stage 1,
// but its stage 3 is defined on them all.
TEST_F(GridReduceVkFrame, HandMadeBuffersMatchTheReference) {
  const SensorProfile s = WideSensor();
  const Params p = ParamsForSensor(s);
  const Tables t = MakeTables(s, p);
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  const float specials_z[] = {0.0f,
                              -0.0f,
                              exact::FromBits(1u),
                              exact::FromBits(0x80000001u),
                              -1e30f,
                              1e30f,
                              std::numeric_limits<float>::infinity(),
                              -std::numeric_limits<float>::infinity(),
                              -1.7f,
                              -1.7f,
                              2.0f};
  const uint32_t flag_values[] = {0u, 1u, 1u, 1u, 1u, 2u, 3u, 4u, 5u};
  const uint32_t pixels = p.width * p.beams;
  for (uint32_t n : {1u, 100u, 77777u, 150000u}) {
    Frame f;
    f.n = n;
    f.flags.resize(n), f.r2.resize(n), f.zt.resize(n), f.point_pixel.resize(n);
    for (uint32_t i = 0; i < n; ++i) {
      f.flags[i] = flag_values[rng() % 9];
      const uint32_t ring = rng() % uint32_t(t.ring_bound2.size());
      float r2 = t.ring_bound2[ring];
      switch (rng() % 6) {
        case 0:
          r2 = std::nextafter(r2, 0.0f);
          break;
        case 1:
          r2 = std::nextafter(r2, 1e30f);
          break;
        case 2:
          r2 = unit(rng) * 150.0f * 150.0f;
          break;  // also past the last ring
        case 3:
          r2 = (rng() & 1) ? 0.0f : exact::FromBits(0x00400000u);
          break;
        default:
          break;
      }
      f.r2[i] = r2;
      f.zt[i] = (rng() % 3 == 0) ? specials_z[rng() % 11] : (unit(rng) - 0.5f) * 8.0f;
      f.point_pixel[i] = i < pixels ? i : rng() % pixels;  // every pixel, so every column
    }
    EXPECT_EQ(ExpectSameGridReduce(context(), p, t, f, nullptr, "hand-made"),
              n + 3ull * CellCount(p));
  }
}

SimOptions Scene(uint32_t seed, float pitch, bool rings) {
  SimOptions o;
  o.seed = seed;
  o.pitch_deg = pitch;
  o.emit_rings = rings;
  return o;
}

TEST_F(GridReduceVkFrame, SimulatedStreetHdl64e) {
  const SensorProfile s = LoadSensorProfile("hdl64e", test::SensorsDir());
  const Params p = ParamsForSensor(s);
  const Tables t = MakeTables(s, p);
  for (const SimOptions& o : {Scene(1, 0.0f, false), Scene(2, 1.5f, true)}) {
    const SimScan scan = Simulate(s, o);
    EXPECT_EQ(ExpectSameOnCloud(context(), scan.cloud, p, t, "simulated street"),
              scan.cloud.size() + 3ull * CellCount(p));
  }
}

TEST_F(GridReduceVkFrame, Kitti07Frame964) {
  LPIR_REQUIRE_DATA("kitti/07/velodyne/000964.bin");
  const Cloud cloud = ReadKittiBin(test::DataFile("kitti/07/velodyne/000964.bin"));
  const SensorProfile s = LoadSensorProfile("hdl64e", test::SensorsDir());
  const Params p = ParamsForSensor(s);
  const Tables t = MakeTables(s, p);
  EXPECT_EQ(ExpectSameOnCloud(context(), cloud, p, t, "kitti 07/000964"),
            cloud.size() + 3ull * CellCount(p));
}

TEST_F(GridReduceVkFrame, Rellis3dOuster) {
  LPIR_REQUIRE_DATA("rellis3d/os1/000104.bin");
  const Cloud cloud = ReadKittiBin(test::DataFile("rellis3d/os1/000104.bin"));
  const SensorProfile s = LoadSensorProfile("os1-64", test::SensorsDir());
  const Params p = ParamsForSensor(s);
  const Tables t = MakeTables(s, p);
  EXPECT_EQ(ExpectSameOnCloud(context(), cloud, p, t, "rellis3d os1/000104"),
            cloud.size() + 3ull * CellCount(p));
}

}  // namespace
}  // namespace lpir
