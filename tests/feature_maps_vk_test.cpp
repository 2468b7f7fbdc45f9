// Stage 5, feature maps, on Vulkan (shaders/feature_maps.comp) against the CPU reference
// (reference_cpu/feature_maps.cpp): pixel_filled and the six feature maps byte for byte.
// Inputs: hand-made images (holes at the column wrap, holes whose neighbours' ranges sit exactly
// on, one ulp under and one ulp over hole_gap, equal ranges down a column (undefined slope), large
// and negative heights, images 1 and 2 pixels wide or 1 row high), and the
// reference's stages 1-4 on random clouds of 1 to 200000 points, the simulated street (HDL-64E)
// and the real scans when ../shared/data is present.
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
#include "host/gpu/feature_maps.h"
#include "host/io/kitti_bin.h"
#include "host/io/sensor_profile.h"
#include "reference_cpu/exact.h"
#include "reference_cpu/pipeline.h"
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

// The inputs of the 3x3 neighbourhood of `pix` (columns wrapping), and the CPU's measured /
// filled maps there.
std::string NeighbourhoodText(const Frame& in, const Frame& cpu, const Params& p, size_t pix) {
  const uint32_t w = p.width, h = p.beams;
  const uint32_t v = uint32_t(pix / w), u = uint32_t(pix % w);
  std::string text = "pixel " + std::to_string(pix) + " (row " + std::to_string(v) + ", column " +
                     std::to_string(u) + "); 3x3 neighbourhood:";
  for (int dv = -1; dv <= 1; ++dv) {
    const int vv = int(v) + dv;
    if (vv < 0 || vv >= int(h)) continue;
    for (int du = -1; du <= 1; ++du) {
      const uint32_t uu = uint32_t((int64_t(u) + du + w) % w);
      const size_t q = size_t(vv) * w + uu;
      const uint32_t i = in.pixel_point[q];
      text += "\n  (" + std::to_string(vv) + ", " + std::to_string(uu) + ") point ";
      if (i == kNone) {
        text += "none";
      } else {
        text += std::to_string(i) + ": r2 " + FloatText(in.r2[i]) + ", zt " + FloatText(in.zt[i]);
      }
      text += "; CPU filled " + std::to_string(cpu.pixel_filled[q]) + ", range " +
              FloatText(cpu.f_range[q]) + ", height " + FloatText(cpu.f_height[q]);
    }
  }
  return text;
}

template <typename T>
uint32_t BitsOf(T value) {
  uint32_t u;
  std::memcpy(&u, &value, 4);
  return u;
}
std::string Text(uint32_t u) { return ValueText(u); }
std::string Text(float f) { return FloatText(f); }

// Compares one buffer; on a difference, reports the first one with its neighbourhood.
template <typename T>
bool ExpectSameBuffer(const char* name, const std::vector<T>& a, const std::vector<T>& b,
                      const Frame& in, const Frame& cpu, const Params& p) {
  EXPECT_EQ(a.size(), b.size()) << "feature_maps: " << name << " sizes differ";
  if (a.size() != b.size()) return false;
  if (a.empty() || std::memcmp(a.data(), b.data(), 4 * a.size()) == 0) return true;
  size_t first = a.size(), count = 0;
  for (size_t i = 0; i < a.size(); ++i)
    if (BitsOf(a[i]) != BitsOf(b[i])) {
      if (first == a.size()) first = i;
      ++count;
    }
  ADD_FAILURE() << "feature_maps: buffer " << name << " differs at element " << first << " ("
                << count << " of " << a.size() << " differ): CPU " << Text(a[first]) << ", GPU "
                << Text(b[first]) << "; " << NeighbourhoodText(in, cpu, p, first);
  return false;
}

// Stage 5 on the GPU, as lpir::FeatureMaps(p, f): reads f.r2, f.zt (f.n each) and
// f.pixel_point, fills f.pixel_filled and the six maps.
vk::Status FeatureMapsOnGpu(const vk::Device& device, const Params& p, Frame& f, double* gpu_ns) {
  const uint32_t n = f.n;
  const size_t pixels = size_t(p.width) * p.beams;
  test::StageHarness h(device, "feature_maps");
  vk::FeatureMapsBuffers b;
  b.params = h.Uniform(p);
  b.pixel_point = h.In("pixel_point", f.pixel_point, pixels);
  b.r2 = h.In("r2", f.r2, n);
  b.zt = h.In("zt", f.zt, n);
  b.pixel_filled = h.Out(&f.pixel_filled, pixels);
  b.f_range = h.Out(&f.f_range, pixels);
  b.f_height = h.Out(&f.f_height, pixels);
  b.f_slope = h.Out(&f.f_slope, pixels);
  b.f_edge_l = h.Out(&f.f_edge_l, pixels);
  b.f_edge_r = h.Out(&f.f_edge_r, pixels);
  b.f_varz = h.Out(&f.f_varz, pixels);
  b.feature_pack = h.Scratch(vk::FeatureMapsStage::PackBytes(pixels));
  return h.Run<vk::FeatureMapsStage>(
      b,
      [&](const vk::FeatureMapsStage& s, vk::CommandBuffer& cmd) {
        return s.Record(cmd, p.width, p.beams);
      },
      gpu_ns);
}

// `in` holds the stage 1-4 buffers; runs stage 5 on both sides from them and compares
// pixel_filled and the six maps. Returns the number of values compared.
uint64_t ExpectSameFeatures(const vk::Context& context, const Params& p, const Frame& in,
                            const char* what) {
  Frame cpu = in, gpu = in;
  FeatureMaps(p, cpu);
  double gpu_ns = 0;
  const vk::Status status = FeatureMapsOnGpu(context.device(), p, gpu, &gpu_ns);
  EXPECT_TRUE(status.ok()) << status.message();
  if (!status.ok()) return 0;
  bool same = ExpectSameBuffer("pixel_filled", cpu.pixel_filled, gpu.pixel_filled, in, cpu, p);
  const struct {
    const char* name;
    std::vector<float> Frame::*map;
  } maps[] = {{"f_range", &Frame::f_range},   {"f_height", &Frame::f_height},
              {"f_slope", &Frame::f_slope},   {"f_edge_l", &Frame::f_edge_l},
              {"f_edge_r", &Frame::f_edge_r}, {"f_varz", &Frame::f_varz}};
  for (const auto& m : maps) same &= ExpectSameBuffer(m.name, cpu.*m.map, gpu.*m.map, in, cpu, p);
  size_t kinds[3] = {}, undefined_slope = 0;
  for (size_t i = 0; i < cpu.pixel_filled.size(); ++i) {
    kinds[cpu.pixel_filled[i] % 3]++;
    if (cpu.pixel_filled[i] && cpu.f_slope[i] < 0.0f) ++undefined_slope;
  }
  std::printf(
      "[feature_maps] %s: %zu pixels (%zu measured, %zu filled, %zu empty, %zu undefined "
      "slopes): %zu values compared%s, GPU %.3f ms\n",
      what, cpu.pixel_filled.size(), kinds[1], kinds[2], kinds[0], undefined_slope,
      7 * cpu.pixel_filled.size(), same ? "" : " (DIFFER)", gpu_ns / 1e6);
  return same ? 7 * cpu.pixel_filled.size() : 0;
}

// A hand-made image of `p.width` x `p.beams` pixels: one point per measured pixel (numbered in a
// shuffled order), empty pixels with probability `empty`, heights from `value`.
struct HandOptions {
  float empty = 0.3f;
  float base_range = 10.0f;   // ranges base_range + small steps, so that holes get filled
  float range_step = 0.02f;   // per column
  float height_scale = 1.0f;  // heights in +-height_scale
  bool equal_down = false;    // a pixel's range equals the one below (undefined slope)
  bool wrap_holes = true;     // holes at columns 0 and width - 1 with measured neighbours
};

Frame HandMadeImage(const Params& p, uint32_t seed, const HandOptions& o) {
  const uint32_t w = p.width, h = p.beams, pixels = w * h;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  Frame f;
  f.pixel_point.assign(pixels, kNone);
  std::vector<uint32_t> measured;
  for (uint32_t pix = 0; pix < pixels; ++pix)
    if (unit(rng) >= o.empty) measured.push_back(pix);
  // Wrap holes: column 0 empty with columns w-1 and 1 measured on even rows, column w-1 empty
  // with columns w-2 and 0 measured on odd rows.
  std::vector<uint8_t> is_measured(pixels, 0);
  for (uint32_t pix : measured) is_measured[pix] = 1;
  if (o.wrap_holes && w >= 3) {
    for (uint32_t v = 0; v < h; ++v) {
      const uint32_t row = v * w;
      if (v % 2 == 0) {
        is_measured[row] = 0, is_measured[row + w - 1] = 1, is_measured[row + 1] = 1;
      } else {
        is_measured[row + w - 1] = 0, is_measured[row + w - 2] = 1, is_measured[row] = 1;
      }
    }
  }
  measured.clear();
  for (uint32_t pix = 0; pix < pixels; ++pix)
    if (is_measured[pix]) measured.push_back(pix);
  // Points in a shuffled order (the winner's index carries no meaning here), one extra point that
  // no pixel names.
  std::vector<uint32_t> order(measured.size());
  for (size_t k = 0; k < order.size(); ++k) order[k] = uint32_t(k);
  std::shuffle(order.begin(), order.end(), rng);
  f.n = uint32_t(measured.size() + 1);
  f.r2.assign(f.n, 25.0f);
  f.zt.assign(f.n, 7.0f);
  std::vector<float> range(pixels, 0.0f);
  for (size_t k = 0; k < measured.size(); ++k) {
    const uint32_t pix = measured[k], i = order[k];
    const uint32_t v = pix / w, u = pix % w;
    f.pixel_point[pix] = i;
    float r = o.base_range + o.range_step * float(u % 7) + 0.5f * float(v) + 0.01f * unit(rng);
    if (o.equal_down) r = o.base_range + o.range_step * float(u);  // same down every column
    range[pix] = r;
    f.r2[i] = r * r;
    f.zt[i] = o.height_scale * (2.0f * unit(rng) - 1.0f);
    if (rng() % 16 == 0) f.zt[i] = (rng() % 2 ? 1.0f : -1.0f) * o.height_scale;  // extremes
    if (rng() % 32 == 0) f.zt[i] = 0.0f;
  }
  return f;
}

Params SmallImage(uint32_t width, uint32_t beams) {
  Params p = DefaultParams();
  p.width = width;
  p.beams = beams;
  return p;
}

class FeatureMapsVkHand : public test::VkTest {};

TEST_F(FeatureMapsVkHand, HolesAtTheColumnWrap) {
  // 512 columns: four pixels an invocation in the first pass; 510: one.
  for (uint32_t width : {512u, 510u}) {
    const Params p = SmallImage(width, 32);
    HandOptions o;
    o.empty = 0.35f;
    EXPECT_EQ(ExpectSameFeatures(context(), p, HandMadeImage(p, 1, o),
                                 ("hand-made, wrap holes, width " + std::to_string(width)).c_str()),
              7u * width * 32);
  }
}

TEST_F(FeatureMapsVkHand, HoleGapExactlyAndOneUlpAround) {
  const Params p = SmallImage(1024, 16);
  HandOptions o;
  o.empty = 0.0f;  // only the holes punched below (and the wrap holes)
  Frame f = HandMadeImage(p, 2, o);
  // Holes at every fourth column with both neighbours measured; the right neighbour's r2 placed
  // so that the ranges (Sqrt(r2)) differ by hole_gap, give or take up to 3 ulps of r2.
  for (uint32_t v = 0; v < p.beams; ++v)
    for (uint32_t u = 1; u + 1 < p.width; u += 4) f.pixel_point[v * p.width + u] = kNone;
  {
    std::mt19937 rng(5);
    for (uint32_t v = 0; v < p.beams; ++v)
      for (uint32_t u = 1; u + 1 < p.width; u += 4) {
        const uint32_t pix = v * p.width + u;
        const uint32_t il = f.pixel_point[pix - 1], ir = f.pixel_point[pix + 1];
        if (il == kNone || ir == kNone) continue;
        const float rl = exact::Sqrt(f.r2[il]);
        const float target = rl + p.hole_gap;
        float r2 = target * target;
        const int nudge = int(rng() % 7) - 3;
        for (int k = 0; k < nudge; ++k) r2 = std::nextafter(r2, 1e30f);
        for (int k = 0; k > nudge; --k) r2 = std::nextafter(r2, 0.0f);
        f.r2[ir] = r2;
      }
  }
  {
    // Both sides of the boundary are covered: some punched holes filled, some left empty.
    Frame cpu = f;
    FeatureMaps(p, cpu);
    size_t filled = 0, left = 0;
    for (uint32_t v = 0; v < p.beams; ++v)
      for (uint32_t u = 1; u + 1 < p.width; u += 4) {
        const uint32_t pix = v * p.width + u;
        if (f.pixel_point[pix - 1] == kNone || f.pixel_point[pix + 1] == kNone) continue;
        (cpu.pixel_filled[pix] == 2u ? filled : left)++;
      }
    std::printf("[feature_maps] holes around hole_gap: %zu filled, %zu left empty\n", filled, left);
    EXPECT_GT(filled, 0u);
    EXPECT_GT(left, 0u);
  }
  EXPECT_EQ(ExpectSameFeatures(context(), p, f, "hand-made, ranges around hole_gap"),
            7u * 1024 * 16);
}

TEST_F(FeatureMapsVkHand, EqualRangesDownAColumnGiveUndefinedSlopes) {
  const Params p = SmallImage(300, 24);
  HandOptions o;
  o.equal_down = true;
  o.empty = 0.2f;
  EXPECT_EQ(ExpectSameFeatures(context(), p, HandMadeImage(p, 3, o), "hand-made, equal ranges"),
            7u * 300 * 24);
}

TEST_F(FeatureMapsVkHand, LargeHeights) {
  const Params p = SmallImage(2048, 64);
  for (uint32_t seed : {4u, 5u, 6u}) {
    HandOptions o;
    o.height_scale = seed == 4 ? 1000.0f : seed == 5 ? 8191.5f : 123.456f;
    o.empty = 0.1f * float(seed - 3);
    EXPECT_EQ(
        ExpectSameFeatures(context(), p, HandMadeImage(p, seed, o), "hand-made, large heights"),
        7u * 2048 * 64);
  }
}

TEST_F(FeatureMapsVkHand, TinyImages) {
  // One and two columns (the wrap makes a pixel its own neighbour, or both neighbours the same
  // pixel), one row (nothing below: every slope undefined), and a single pixel.
  const uint32_t sizes[][2] = {{1, 8}, {2, 8}, {3, 5}, {64, 1}, {1, 1}, {2, 1}};
  uint32_t seed = 20;
  for (const auto& s : sizes) {
    const Params p = SmallImage(s[0], s[1]);
    for (float empty : {0.0f, 0.5f}) {
      HandOptions o;
      o.empty = empty;
      o.range_step = 0.0f;
      EXPECT_EQ(ExpectSameFeatures(context(), p, HandMadeImage(p, seed++, o), "hand-made, tiny"),
                7u * s[0] * s[1]);
    }
  }
}

TEST_F(FeatureMapsVkHand, EveryPixelEmpty) {
  const Params p = SmallImage(128, 8);
  HandOptions o;
  o.empty = 1.0f;
  o.wrap_holes = false;
  EXPECT_EQ(ExpectSameFeatures(context(), p, HandMadeImage(p, 30, o), "hand-made, empty"),
            7u * 128 * 8);
}

// Stages 1-4 of the reference (RunReference, then stage 5 again from its buffers).
uint64_t ExpectSameOnCloud(const vk::Context& context, const Cloud& cloud, const Params& p,
                           const Tables& t, const char* what) {
  Frame f;
  RunReference(cloud, p, t, f);
  const std::vector<float> pipeline_varz = f.f_varz;
  const uint64_t compared = ExpectSameFeatures(context, p, f, what);
  FeatureMaps(p, f);
  EXPECT_EQ(f.f_varz, pipeline_varz) << "re-running stage 5 on the CPU changed its output";
  return compared;
}

class FeatureMapsVk : public test::VkTest, public ::testing::WithParamInterface<size_t> {};

TEST_P(FeatureMapsVk, RandomCloudMatchesTheReference) {
  const size_t n = GetParam();
  const SensorProfile s = LoadSensorProfile("hdl64e", test::SensorsDir());
  const Params p = ParamsForSensor(s);
  const Tables t = MakeTables(s, p);
  const Cloud cloud = test::StreetLikeCloud(n, uint32_t(n + 7));
  EXPECT_EQ(ExpectSameOnCloud(context(), cloud, p, t, "random"), 7 * uint64_t(p.width) * p.beams);
}

INSTANTIATE_TEST_SUITE_P(Sizes, FeatureMapsVk,
                         ::testing::Values(size_t(1), size_t(2), size_t(65), size_t(1000),
                                           size_t(65536), size_t(200000)),
                         [](const ::testing::TestParamInfo<size_t>& info) {
                           return std::to_string(info.param);
                         });

class FeatureMapsVkScan : public test::VkTest {};

TEST_F(FeatureMapsVkScan, SimulatedStreetHdl64e) {
  const SensorProfile s = LoadSensorProfile("hdl64e", test::SensorsDir());
  const Params p = ParamsForSensor(s);
  const Tables t = MakeTables(s, p);
  for (uint32_t seed : {1u, 2u, 3u}) {
    SimOptions o;
    o.seed = seed;
    o.pitch_deg = seed == 2 ? 1.5f : 0.0f;
    const SimScan scan = Simulate(s, o);
    EXPECT_EQ(ExpectSameOnCloud(context(), scan.cloud, p, t, "simulated street"),
              7 * uint64_t(p.width) * p.beams);
  }
}

TEST_F(FeatureMapsVkScan, Kitti07Frame964) {
  LPIR_REQUIRE_DATA("kitti/07/velodyne/000964.bin");
  const Cloud cloud = ReadKittiBin(test::DataFile("kitti/07/velodyne/000964.bin"));
  const SensorProfile s = LoadSensorProfile("hdl64e", test::SensorsDir());
  const Params p = ParamsForSensor(s);
  const Tables t = MakeTables(s, p);
  EXPECT_EQ(ExpectSameOnCloud(context(), cloud, p, t, "kitti 07/000964"),
            7 * uint64_t(p.width) * p.beams);
}

TEST_F(FeatureMapsVkScan, KittiUnknown56) {
  LPIR_REQUIRE_DATA("kitti/unknown/velodyne/000056.bin");
  const Cloud cloud = ReadKittiBin(test::DataFile("kitti/unknown/velodyne/000056.bin"));
  const SensorProfile s = LoadSensorProfile("hdl64e", test::SensorsDir());
  const Params p = ParamsForSensor(s);
  const Tables t = MakeTables(s, p);
  EXPECT_EQ(ExpectSameOnCloud(context(), cloud, p, t, "kitti unknown/000056"),
            7 * uint64_t(p.width) * p.beams);
}

TEST_F(FeatureMapsVkScan, Rellis3dOuster) {
  LPIR_REQUIRE_DATA("rellis3d/os1/000104.bin");
  const Cloud cloud = ReadKittiBin(test::DataFile("rellis3d/os1/000104.bin"));
  const SensorProfile s = LoadSensorProfile("os1-64", test::SensorsDir());
  const Params p = ParamsForSensor(s);
  const Tables t = MakeTables(s, p);
  EXPECT_EQ(ExpectSameOnCloud(context(), cloud, p, t, "rellis3d os1/000104"),
            7 * uint64_t(p.width) * p.beams);
}

}  // namespace
}  // namespace lpir
