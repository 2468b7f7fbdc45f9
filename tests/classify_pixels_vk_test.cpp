// Stage 6, classify pixels, on Vulkan (shaders/classify_pixels.comp) against the CPU reference
// (reference_cpu/classify_pixels.cpp): pixel_class byte for byte. Inputs: hand-made feature images
// whose values sit exactly on, one ulp below and one ulp above every threshold of eqs. 8-11 in
// every combination (with the default thresholds and with thresholds at 0, -0 and subnormal, where
// a device that flushes subnormals would compare differently), and the reference's stages 1-5 on
// random clouds of 1 to 200000 points, the simulated street (HDL-64E) and the real scans when
// ../shared/data is present.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "apps/sim/scene.h"
#include "host/gpu/classify_pixels.h"
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

std::string PixelText(const Frame& f, const Params& p, size_t pix) {
  return "pixel " + std::to_string(pix) + " (row " + std::to_string(pix / p.width) + ", column " +
         std::to_string(pix % p.width) + "): filled " + std::to_string(f.pixel_filled[pix]) +
         ", edge_l " + FloatText(f.f_edge_l[pix]) + ", edge_r " + FloatText(f.f_edge_r[pix]) +
         ", slope " + FloatText(f.f_slope[pix]) + ", varz " + FloatText(f.f_varz[pix]);
}

// Stage 6 on the GPU, as lpir::ClassifyPixels(p, f): reads f.pixel_filled and the four maps it
// uses, fills f.pixel_class.
vk::Status ClassifyPixelsOnGpu(const vk::Device& device, const Params& p, Frame& f,
                               double* gpu_ns) {
  const uint32_t pixels = p.width * p.beams;
  test::StageHarness h(device, "classify_pixels");
  vk::ClassifyPixelsBuffers b;
  b.params = h.Uniform(p);
  b.pixel_filled = h.In("pixel_filled", f.pixel_filled, pixels);
  b.f_edge_l = h.In("f_edge_l", f.f_edge_l, pixels);
  b.f_edge_r = h.In("f_edge_r", f.f_edge_r, pixels);
  b.f_slope = h.In("f_slope", f.f_slope, pixels);
  b.f_varz = h.In("f_varz", f.f_varz, pixels);
  b.pixel_class = h.Out(&f.pixel_class, pixels);
  return h.Run<vk::ClassifyPixelsStage>(
      b,
      [&](const vk::ClassifyPixelsStage& s, vk::CommandBuffer& cmd) {
        return s.Record(cmd, pixels);
      },
      gpu_ns);
}

// `in` holds the stage 5 buffers; runs stage 6 on both sides from them and compares pixel_class.
// Returns the number of values compared.
uint64_t ExpectSameClassify(const vk::Context& context, const Params& p, const Frame& in,
                            const char* what) {
  Frame cpu = in, gpu = in;
  ClassifyPixels(p, cpu);
  double gpu_ns = 0;
  const vk::Status status = ClassifyPixelsOnGpu(context.device(), p, gpu, &gpu_ns);
  EXPECT_TRUE(status.ok()) << status.message();
  if (!status.ok()) return 0;
  const std::vector<uint32_t>& a = cpu.pixel_class;
  const std::vector<uint32_t>& b = gpu.pixel_class;
  EXPECT_EQ(a.size(), b.size()) << "classify_pixels: pixel_class sizes differ";
  if (a.size() != b.size()) return 0;
  if (!a.empty() && std::memcmp(a.data(), b.data(), 4 * a.size()) != 0) {
    size_t first = a.size(), count = 0;
    for (size_t i = 0; i < a.size(); ++i)
      if (a[i] != b[i]) {
        if (first == a.size()) first = i;
        ++count;
      }
    ADD_FAILURE() << "classify_pixels: buffer pixel_class differs at element " << first << " ("
                  << count << " of " << a.size() << " differ): CPU " << ValueText(a[first])
                  << ", GPU " << ValueText(b[first]) << "; " << PixelText(in, p, first);
  }
  size_t classes[8] = {};
  for (uint32_t c : a) classes[c & 7]++;
  std::printf(
      "[classify_pixels] %s: %zu pixels (%zu non-ground, %zu ground, %zu unknown, %zu empty, %zu "
      "bank): %zu values compared, GPU %.3f ms\n",
      what, a.size(), classes[0], classes[1], classes[2], classes[3], classes[kPixBank], a.size(),
      gpu_ns / 1e6);
  return a.size();
}

// Values around a threshold t: t itself, one ulp either side, and a few steps further.
void Around(float t, std::vector<float>& out) {
  const float inf = std::numeric_limits<float>::infinity();
  out.push_back(t);
  out.push_back(std::nextafter(t, -inf));
  out.push_back(std::nextafter(t, inf));
}

// Every combination of the candidate values of each feature, then random picks among them to the
// end of the image. Candidates: each threshold (banks' included) and its neighbours, +-0,
// subnormals, -1 (undefined slope), infinities, a NaN.
Frame HandMadeImage(const Params& p, uint32_t seed, size_t* combinations) {
  const float inf = std::numeric_limits<float>::infinity();
  const float sub = exact::FromBits(0x00000101u);
  const std::vector<float> common = {0.0f, -0.0f, sub,   -sub,
                                     inf,  -inf,  1e30f, std::numeric_limits<float>::quiet_NaN()};
  auto candidates = [&](float low, float high) {
    std::vector<float> v;
    Around(low, v);
    Around(high, v);
    v.push_back(low + (high - low) * 0.5f);
    v.push_back(low * 0.5f);
    v.push_back(high * 2.0f);
    v.insert(v.end(), common.begin(), common.end());
    return v;
  };
  std::vector<float> edge;
  Around(p.t_edge, edge);
  edge.insert(edge.end(), {0.0f, -0.0f, sub, 10.0f, -inf, std::numeric_limits<float>::quiet_NaN()});
  std::vector<float> slope = candidates(p.t_slope_low, p.t_slope_high);
  slope.insert(slope.end(), {-1.0f, -1e-30f, std::nextafter(0.0f, -1.0f)});
  Around(p.bank_slope, slope);
  std::vector<float> varz = candidates(p.t_stdz_low, p.t_stdz_high);
  Around(p.bank_rough, varz);
  const uint32_t filled[] = {0u, 1u, 2u};
  const size_t combos = edge.size() * edge.size() * slope.size() * varz.size() * 3;
  *combinations = combos;
  const uint32_t pixels = p.width * p.beams;
  EXPECT_GE(pixels, combos) << "the image is too small for every combination";
  Frame f;
  f.pixel_filled.resize(pixels);
  f.f_edge_l.resize(pixels), f.f_edge_r.resize(pixels), f.f_slope.resize(pixels);
  f.f_varz.resize(pixels);
  f.f_range.assign(pixels, 0.0f);  // not read by stage 6
  std::mt19937 rng(seed);
  for (uint32_t pix = 0; pix < pixels; ++pix) {
    size_t k = pix < combos ? pix : size_t(rng()) % combos;
    auto take = [&k](size_t n) {
      const size_t i = k % n;
      k /= n;
      return i;
    };
    f.pixel_filled[pix] = filled[take(3)];
    f.f_edge_l[pix] = edge[take(edge.size())];
    f.f_edge_r[pix] = edge[take(edge.size())];
    f.f_slope[pix] = slope[take(slope.size())];
    f.f_varz[pix] = varz[take(varz.size())];
  }
  return f;
}

// A big image (2048 x 768 pixels) so that every combination fits.
Params BigImage(Params p) {
  p.width = 2048;
  p.beams = 768;
  return p;
}

class ClassifyPixelsVkHand : public test::VkTest {};

TEST_F(ClassifyPixelsVkHand, EveryThresholdExactlyWithTheDefaults) {
  const Params p = BigImage(DefaultParams());
  size_t combos = 0;
  const Frame f = HandMadeImage(p, 1, &combos);
  std::printf("[classify_pixels] %zu combinations\n", combos);
  EXPECT_EQ(ExpectSameClassify(context(), p, f, "hand-made, default thresholds"),
            size_t(p.width) * p.beams);
}

TEST_F(ClassifyPixelsVkHand, ZeroAndSubnormalThresholds) {
  // Thresholds where IEEE comparison and a flushing device part ways: +-0 and subnormals, equal
  // low and high, and negative values.
  struct T {
    float edge, slope_low, slope_high, z_low, z_high, bank_slope, bank_rough;
  };
  const float sub = exact::FromBits(0x00000101u), sub2 = exact::FromBits(0x00400000u);
  const T cases[] = {
      {0.0f, 0.0f, sub, -0.0f, sub2, sub2, sub},
      {-0.0f, -0.0f, 0.0f, sub, sub, 0.0f, -0.0f},
      {sub, sub, sub2, 0.0f, 1e-30f, sub, 1e-30f},
      {-1.0f, -0.5f, 0.5f, -sub2, -sub, 1.0f, sub2},
  };
  uint32_t seed = 10;
  for (const T& t : cases) {
    Params p = BigImage(DefaultParams());
    p.t_edge = t.edge;
    p.t_slope_low = t.slope_low, p.t_slope_high = t.slope_high;
    p.t_stdz_low = t.z_low, p.t_stdz_high = t.z_high;
    p.bank_slope = t.bank_slope, p.bank_rough = t.bank_rough;
    size_t combos = 0;
    const Frame f = HandMadeImage(p, seed++, &combos);
    EXPECT_EQ(ExpectSameClassify(context(), p, f, "hand-made, zero / subnormal thresholds"),
              size_t(p.width) * p.beams);
  }
}

TEST_F(ClassifyPixelsVkHand, PixelCountsThatAreNotMultiplesOfFour) {
  // The shader reads and writes four pixels at a time, then the last pixels % 4 one by one:
  // images cut from the hand-made one (stage 6 looks at no neighbour) with 1, 3, 35, 39 and 6141
  // pixels, and one of 4 and 8 (no tail).
  const Params big = BigImage(DefaultParams());
  size_t combos = 0;
  const Frame f = HandMadeImage(big, 3, &combos);
  const uint32_t sizes[][2] = {{1, 1}, {3, 1}, {5, 7}, {13, 3}, {2047, 3}, {4, 1}, {2, 4}};
  for (const auto& size : sizes) {
    Params p = big;
    p.width = size[0], p.beams = size[1];
    const size_t pixels = size_t(p.width) * p.beams;
    Frame cut = f;
    for (auto* v : {&cut.f_edge_l, &cut.f_edge_r, &cut.f_slope, &cut.f_varz, &cut.f_range})
      v->resize(pixels);
    cut.pixel_filled.resize(pixels);
    const std::string what = std::to_string(size[0]) + " x " + std::to_string(size[1]);
    EXPECT_EQ(ExpectSameClassify(context(), p, cut, what.c_str()), pixels) << what;
  }
}

// Stages 1-5 of the reference (RunReference, then stage 6 again from its stage 5 buffers).
uint64_t ExpectSameOnCloud(const vk::Context& context, const Cloud& cloud, const Params& p,
                           const Tables& t, const char* what) {
  Frame f;
  RunReference(cloud, p, t, f);
  const std::vector<uint32_t> pipeline_class = f.pixel_class;
  const uint64_t compared = ExpectSameClassify(context, p, f, what);
  ClassifyPixels(p, f);
  EXPECT_EQ(f.pixel_class, pipeline_class) << "re-running stage 6 on the CPU changed its output";
  return compared;
}

class ClassifyPixelsVk : public test::VkTest, public ::testing::WithParamInterface<size_t> {};

TEST_P(ClassifyPixelsVk, RandomCloudMatchesTheReference) {
  const size_t n = GetParam();
  const SensorProfile s = LoadSensorProfile("hdl64e", test::SensorsDir());
  const Params p = ParamsForSensor(s);
  const Tables t = MakeTables(s, p);
  const Cloud cloud = test::StreetLikeCloud(n, uint32_t(n + 3));
  EXPECT_EQ(ExpectSameOnCloud(context(), cloud, p, t, "random"), uint64_t(p.width) * p.beams);
}

INSTANTIATE_TEST_SUITE_P(Sizes, ClassifyPixelsVk,
                         ::testing::Values(size_t(1), size_t(2), size_t(65), size_t(1000),
                                           size_t(65536), size_t(200000)),
                         [](const ::testing::TestParamInfo<size_t>& info) {
                           return std::to_string(info.param);
                         });

class ClassifyPixelsVkScan : public test::VkTest {};

TEST_F(ClassifyPixelsVkScan, SimulatedStreetHdl64e) {
  const SensorProfile s = LoadSensorProfile("hdl64e", test::SensorsDir());
  const Params p = ParamsForSensor(s);
  const Tables t = MakeTables(s, p);
  for (uint32_t seed : {1u, 2u}) {
    SimOptions o;
    o.seed = seed;
    o.pitch_deg = seed == 2 ? 1.5f : 0.0f;
    const SimScan scan = Simulate(s, o);
    EXPECT_EQ(ExpectSameOnCloud(context(), scan.cloud, p, t, "simulated street"),
              uint64_t(p.width) * p.beams);
  }
}

TEST_F(ClassifyPixelsVkScan, Kitti07Frame964) {
  LPIR_REQUIRE_DATA("kitti/07/velodyne/000964.bin");
  const Cloud cloud = ReadKittiBin(test::DataFile("kitti/07/velodyne/000964.bin"));
  const SensorProfile s = LoadSensorProfile("hdl64e", test::SensorsDir());
  const Params p = ParamsForSensor(s);
  const Tables t = MakeTables(s, p);
  EXPECT_EQ(ExpectSameOnCloud(context(), cloud, p, t, "kitti 07/000964"),
            uint64_t(p.width) * p.beams);
}

TEST_F(ClassifyPixelsVkScan, Rellis3dOuster) {
  LPIR_REQUIRE_DATA("rellis3d/os1/000104.bin");
  const Cloud cloud = ReadKittiBin(test::DataFile("rellis3d/os1/000104.bin"));
  const SensorProfile s = LoadSensorProfile("os1-64", test::SensorsDir());
  const Params p = ParamsForSensor(s);
  const Tables t = MakeTables(s, p);
  EXPECT_EQ(ExpectSameOnCloud(context(), cloud, p, t, "rellis3d os1/000104"),
            uint64_t(p.width) * p.beams);
}

}  // namespace
}  // namespace lpir
