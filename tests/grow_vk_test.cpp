// grow, on Vulkan (shaders/grow.comp) against the CPU reference
// (reference_cpu/grow.cpp): pixel_grown, pixel_comp and pixel_label byte for byte
// (tests/stage_harness.h runs and compares). Inputs: over a thousand random label images and the
// adversarial ones of tests/grow_images.h, all through one stage bound once (its buffers keep the
// last image's values: every output word must be written), and the whole CPU pipeline
// (RunReference) on the scenes of tests/stage_scenes.h. The passes are fixed, so every image runs
// the same five dispatches; the components (union-find) carry the reference's lowest-pixel labels.
#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <string>

#include "tests/grow_images.h"
#include "tests/stage_harness.h"
#include "tests/stage_scenes.h"

namespace lpir {
namespace {

// One GrowStage for images of up to 2^16 pixels.
class GrowVk : public test::VkTest {
 protected:
  test::StageHarness<vk::GrowStage> Bench() {
    return {device(), {0, 1u << 16, CellCount(DefaultParams())}, nullptr};
  }
};

TEST_F(GrowVk, ThousandRandomImages) {
  test::StageHarness<vk::GrowStage> h = Bench();
  std::mt19937 rng(20261202);
  size_t lifted = 0, kept_vetoed = 0;  // vetoed pixels the reference lifted / left non-ground
  for (uint32_t k = 0; k < 1000; ++k) {
    const test::GrowImage im =
        k < 30 ? test::RandomGrowImage(k, k % 2 ? 0.05f : 0.0f, {1, 48, 1, 16}, true)
               : test::MixedGrowImage(rng, k % 10 == 0 ? 700 : 96, k % 10 == 0 ? 70 : 24);
    test::ExpectSameStage(h, im.p, nullptr, nullptr, im.f, "random image " + std::to_string(k));
    if (HasFailure()) break;
    Frame cpu = im.f;
    Grow(im.p, cpu);
    for (size_t i = 0; i < cpu.pixel_label.size(); ++i)
      if (im.f.pixel_fused[i] == kPixVetoed) {
        lifted += cpu.pixel_label[i] == kPixGround;
        kept_vetoed += cpu.pixel_label[i] == kPixNonGround;
      }
  }
  EXPECT_GT(lifted, 0u) << "no image exercised the veto's lift";
  EXPECT_GT(kept_vetoed, 0u) << "no image kept a vetoed pixel non-ground";
}

TEST_F(GrowVk, AdversarialImages) {
  test::StageHarness<vk::GrowStage> h = Bench();
  for (const test::SeededAdversary& a : test::SeededAdversaries())
    test::ExpectSameStage(h, a.im.p, nullptr, nullptr, a.im.f, a.name);
}

class GrowVkScene : public test::StageScene {};

TEST_P(GrowVkScene, MatchesTheReference) {
  test::ExpectSameStage<vk::GrowStage>(device(), p, nullptr, nullptr, frame, what);
  Params q = p;
  q.grow_grade = 0.05f;
  q.min_component = 64;
  test::ExpectSameStage<vk::GrowStage>(device(), q, nullptr, nullptr, frame,
                                       what + ", grade 0.05, min 64");
}

LPIR_STAGE_SCENES(GrowVkScene);

}  // namespace
}  // namespace lpir
