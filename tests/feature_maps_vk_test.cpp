// feature_maps, on Vulkan (shaders/feature_maps.comp) against the CPU reference
// (reference_cpu/feature_maps.cpp): pixel_filled and the six feature maps byte for byte.
// Inputs: hand-made images (tests/feature_maps_images.h: holes at the column wrap, holes whose
// neighbours' ranges sit exactly on, one ulp under and one ulp over hole_gap, equal ranges down a
// column (undefined slope), large and negative heights, rows of heights beyond 419 m among rows
// under it, images 1 and 2 pixels wide or 1 row high),
// and the reference's prepare, project, grid_reduce and coarse_segment on random clouds of 1 to
// 200000 points and the scenes of tests/stage_scenes.h (tests/stage_harness.h runs and compares).
#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

#include "tests/feature_maps_images.h"
#include "tests/stage_harness.h"
#include "tests/stage_scenes.h"
#include "tests/stage_test_util.h"

namespace lpir {
namespace {

// `in` holds the prepare, project, grid_reduce and coarse_segment buffers; runs feature_maps on
// both sides from them and compares.
void ExpectSameFeatures(const vk::Device& device, const Params& p, const Frame& in,
                        const std::string& what) {
  test::ExpectSameStage<vk::FeatureMapsStage>(device, p, nullptr, nullptr, in, what);
}

using test::HandMadeImage;
using test::HandOptions;
using test::SmallImage;

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
  std::vector<uint32_t> holes;
  ExpectSameFeatures(device(), p, test::HoleGapImage(p, &holes), "hand-made, around hole_gap");
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

// The reference sums a window's moments in doubles where every quantised value is at most 2^22
// (419.4304 m) and in int64 pixel by pixel where a row of the window holds a larger one: heights up
// to 400 m, rows 5 and 11 with a height of 450 m, one pixel exactly at the bound and one a step
// beyond it.
TEST_F(FeatureMapsVkHand, WideRowsAmongNarrowOnes) {
  const Params p = SmallImage(64, 16);
  HandOptions o;
  o.height_scale = 400.0f;
  Frame f = HandMadeImage(p, 7, o);
  auto set_height = [&](uint32_t v, uint32_t u, float z) {
    const uint32_t i = f.pixel_point[v * p.width + u];
    if (i != kNone) f.zt[i] = z;
  };
  for (uint32_t u = 0; u < p.width; u += 9) set_height(5, u, 450.0f), set_height(11, u, -450.0f);
  set_height(2, 3, 419.4304f);
  set_height(8, 40, -419.4306f);
  ExpectSameFeatures(device(), p, f, "hand-made, wide rows among narrow ones");
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

class FeatureMapsVk : public test::VkTest, public ::testing::WithParamInterface<size_t> {};

TEST_P(FeatureMapsVk, RandomCloudMatchesTheReference) {
  const size_t n = GetParam();
  const SensorProfile s = LoadSensorProfile("hdl64e", test::SensorsDir());
  const Params p = ParamsForSensor(s);
  const Tables t = MakeTables(s, p);
  Frame f;
  RunReference(test::StreetLikeCloud(n, uint32_t(n + 7)), p, t, f);
  ExpectSameFeatures(device(), p, f, "random");
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
