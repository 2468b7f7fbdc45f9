// classify_pixels, on Vulkan (shaders/classify_pixels.comp) against the CPU reference
// (reference_cpu/classify_pixels.cpp): pixel_class byte for byte. Inputs: hand-made feature images
// whose values sit exactly on, one ulp below and one ulp above every threshold of eqs. 8-11 in
// every combination (with the default thresholds and with thresholds at 0, -0 and subnormal, where
// a device that flushes subnormals would compare differently), and the reference's prepare,
// project, grid_reduce, coarse_segment and feature_maps on random clouds of 1 to 200000 points and
// the scenes of tests/stage_scenes.h (tests/stage_harness.h compares).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "reference_cpu/exact.h"
#include "tests/stage_harness.h"
#include "tests/stage_scenes.h"
#include "tests/stage_test_util.h"

namespace lpir {
namespace {

// `in` holds the feature_maps buffers; runs classify_pixels on both sides from them and compares
// pixel_class.
void ExpectSameClassify(const vk::Device& device, const Params& p, const Frame& in,
                        const std::string& what) {
  EXPECT_EQ(test::ExpectSameStage<vk::ClassifyPixelsStage>(device, p, nullptr, nullptr, in, what),
            test::StageBytes<vk::ClassifyPixelsStage>(in.n, p));
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
  f.f_range.assign(pixels, 0.0f);  // not read by classify_pixels
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
  ExpectSameClassify(device(), p, f, "hand-made, default thresholds");
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
    ExpectSameClassify(device(), p, f, "hand-made, zero / subnormal thresholds");
  }
}

TEST_F(ClassifyPixelsVkHand, PixelCountsThatAreNotMultiplesOfFour) {
  // The shader reads and writes four pixels at a time, then the last pixels % 4 one by one:
  // images cut from the hand-made one (classify_pixels looks at no neighbour) with 1, 3, 35, 39 and
  // 6141 pixels, and one of 4 and 8 (no tail).
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
    ExpectSameClassify(device(), p, cut, std::to_string(size[0]) + " x " + std::to_string(size[1]));
  }
}

// prepare, project, grid_reduce, coarse_segment and feature_maps of the reference (RunReference),
// and classify_pixels on both sides from them.
void ExpectSameOnCloud(const vk::Device& device, const Cloud& cloud, const Params& p,
                       const Tables& t, const std::string& what) {
  Frame f;
  RunReference(cloud, p, t, f);
  ExpectSameClassify(device, p, f, what);
}

class ClassifyPixelsVk : public test::VkTest, public ::testing::WithParamInterface<size_t> {};

TEST_P(ClassifyPixelsVk, RandomCloudMatchesTheReference) {
  const size_t n = GetParam();
  const SensorProfile s = LoadSensorProfile("hdl64e", test::SensorsDir());
  const Params p = ParamsForSensor(s);
  const Tables t = MakeTables(s, p);
  const Cloud cloud = test::StreetLikeCloud(n, uint32_t(n + 3));
  ExpectSameOnCloud(device(), cloud, p, t, "random");
}

INSTANTIATE_TEST_SUITE_P(Sizes, ClassifyPixelsVk,
                         ::testing::Values(size_t(1), size_t(2), size_t(65), size_t(1000),
                                           size_t(65536), size_t(200000)),
                         [](const ::testing::TestParamInfo<size_t>& info) {
                           return std::to_string(info.param);
                         });

class ClassifyPixelsVkScene : public test::StageScene {};

TEST_P(ClassifyPixelsVkScene, MatchesTheReference) { ExpectSameClassify(device(), p, frame, what); }

LPIR_STAGE_SCENES(ClassifyPixelsVkScene);

}  // namespace
}  // namespace lpir
