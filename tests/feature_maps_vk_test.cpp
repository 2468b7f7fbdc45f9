// Stage 5, feature maps, on Vulkan (shaders/feature_maps.comp) against the CPU reference
// (reference_cpu/feature_maps.cpp): pixel_filled and the six feature maps byte for byte.
// Inputs: hand-made images (holes at the column wrap, holes whose neighbours' ranges sit exactly
// on, one ulp under and one ulp over hole_gap, equal ranges down a column (undefined slope), large
// and negative heights, images 1 and 2 pixels wide or 1 row high), and the
// reference's stages 1-4 on random clouds of 1 to 200000 points and the scenes of
// tests/stage_scenes.h (tests/stage_harness.h compares).
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

#include "reference_cpu/exact.h"
#include "tests/stage_harness.h"
#include "tests/stage_scenes.h"
#include "tests/stage_test_util.h"

namespace lpir {
namespace {

// `in` holds the stage 1-4 buffers; runs stage 5 on both sides from them and compares
// pixel_filled and the six maps.
void ExpectSameFeatures(const vk::Device& device, const Params& p, const Frame& in,
                        const std::string& what) {
  EXPECT_EQ(test::ExpectSameStage<vk::FeatureMapsStage>(device, p, nullptr, nullptr, in, what),
            test::StageBytes<vk::FeatureMapsStage>(in.n, p));
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
    ExpectSameFeatures(device(), p, HandMadeImage(p, 1, o),
                       "hand-made, wrap holes, width " + std::to_string(width));
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
  ExpectSameFeatures(device(), p, f, "hand-made, ranges around hole_gap");
}

TEST_F(FeatureMapsVkHand, EqualRangesDownAColumnGiveUndefinedSlopes) {
  const Params p = SmallImage(300, 24);
  HandOptions o;
  o.equal_down = true;
  o.empty = 0.2f;
  ExpectSameFeatures(device(), p, HandMadeImage(p, 3, o), "hand-made, equal ranges");
}

TEST_F(FeatureMapsVkHand, LargeHeights) {
  const Params p = SmallImage(2048, 64);
  for (uint32_t seed : {4u, 5u, 6u}) {
    HandOptions o;
    o.height_scale = seed == 4 ? 1000.0f : seed == 5 ? 8191.5f : 123.456f;
    o.empty = 0.1f * float(seed - 3);
    ExpectSameFeatures(device(), p, HandMadeImage(p, seed, o), "hand-made, large heights");
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
      ExpectSameFeatures(device(), p, HandMadeImage(p, seed++, o), "hand-made, tiny");
    }
  }
}

TEST_F(FeatureMapsVkHand, EveryPixelEmpty) {
  const Params p = SmallImage(128, 8);
  HandOptions o;
  o.empty = 1.0f;
  o.wrap_holes = false;
  ExpectSameFeatures(device(), p, HandMadeImage(p, 30, o), "hand-made, empty");
}

// Stages 1-4 of the reference (RunReference), and stage 5 on both sides from them.
void ExpectSameOnCloud(const vk::Device& device, const Cloud& cloud, const Params& p,
                       const Tables& t, const std::string& what) {
  Frame f;
  RunReference(cloud, p, t, f);
  ExpectSameFeatures(device, p, f, what);
}

class FeatureMapsVk : public test::VkTest, public ::testing::WithParamInterface<size_t> {};

TEST_P(FeatureMapsVk, RandomCloudMatchesTheReference) {
  const size_t n = GetParam();
  const SensorProfile s = LoadSensorProfile("hdl64e", test::SensorsDir());
  const Params p = ParamsForSensor(s);
  const Tables t = MakeTables(s, p);
  const Cloud cloud = test::StreetLikeCloud(n, uint32_t(n + 7));
  ExpectSameOnCloud(device(), cloud, p, t, "random");
}

INSTANTIATE_TEST_SUITE_P(Sizes, FeatureMapsVk,
                         ::testing::Values(size_t(1), size_t(2), size_t(65), size_t(1000),
                                           size_t(65536), size_t(200000)),
                         [](const ::testing::TestParamInfo<size_t>& info) {
                           return std::to_string(info.param);
                         });

class FeatureMapsVkScene : public test::StageScene {};

TEST_P(FeatureMapsVkScene, MatchesTheReference) { ExpectSameFeatures(device(), p, frame, what); }

LPIR_STAGE_SCENES(FeatureMapsVkScene);

}  // namespace
}  // namespace lpir
