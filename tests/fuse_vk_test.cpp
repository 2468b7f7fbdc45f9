// fuse, on Vulkan (shaders/fuse.comp) against the CPU reference
// (reference_cpu/fuse.cpp): pixel_fused byte for byte (tests/stage_harness.h runs and compares).
// Inputs from the whole CPU pipeline (RunReference) on random clouds and the scenes of
// tests/stage_scenes.h, each also under other veto parameters; and hand-made images: occluders
// exactly on the veto's, the step spare's and the passed-under rule's thresholds, one ulp either
// side (tests/fuse_images.h, whose verdicts tests/fuse_test.cpp checks), in the top rows and with
// occ_rows beyond the image, and random images of every class.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "tests/fuse_images.h"
#include "tests/stage_harness.h"
#include "tests/stage_scenes.h"
#include "tests/stage_test_util.h"

namespace lpir {
namespace {

void ExpectSameFuse(const vk::Device& device, const Params& p, const Frame& in,
                    const std::string& what) {
  test::ExpectSameStage<vk::FuseStage>(device, p, nullptr, nullptr, in, what);
}

// The GPU must match the reference under the frame's parameters and under other veto settings.
void ExpectSameFuseVariants(const vk::Device& device, const Params& p, const Frame& f,
                            const std::string& what) {
  ExpectSameFuse(device, p, f, what);
  struct Variant {
    uint32_t rows;
    float margin, rise, grade, front, pass;
    uint32_t step_rows;
    float step, step_grade, step_reach;
  };
  const Variant variants[] = {{0, 0.3f, 0.075f, 0.0002f, 0.1f, 0.15f, 10, 0.15f, 0.1f, 3.0f},
                              {1, 0.1f, 0.1f, 0.0f, 0.3f, 1000.0f, 0, 0.15f, 0.1f, 3.0f},
                              {2, 0.3f, 0.075f, 0.0002f, 0.1f, 0.0f, 1, 0.3f, 0.0f, 1000.0f},
                              {3, 0.0f, 0.0f, 0.001f, 0.0f, 0.05f, 4, 0.0f, 1.0f, 0.5f},
                              {8, -0.5f, -0.05f, 0.01f, -0.2f, -0.1f, 3, -0.1f, -0.5f, -1.0f},
                              {200, 1.0f, 0.5f, 0.0f, 1000.0f, 0.5f, 200, 1.0f, 0.3f, 10.0f}};
  for (const Variant& var : variants) {
    Params q = p;
    q.occ_rows = var.rows, q.occ_margin = var.margin, q.occ_rise = var.rise;
    q.occ_grade = var.grade, q.occ_front = var.front, q.occ_pass = var.pass;
    q.occ_step_rows = var.step_rows, q.occ_step = var.step, q.occ_step_grade = var.step_grade;
    q.occ_step_reach = var.step_reach;
    ExpectSameFuse(device, q, f, what + ", variant occ_rows " + std::to_string(var.rows));
  }
}

class FuseVk : public test::VkTest {
 protected:
  void Images(const std::vector<test::FuseVerdicts>& images) {
    for (const test::FuseVerdicts& c : images) ExpectSameFuse(device(), c.im.p, c.im.f, c.what);
  }
};

TEST_F(FuseVk, RandomCloudsSmallSensor) {
  for (const test::RandomStreet& s : test::RandomStreets(test::SmallSensor(), {1, 2, 3}, 500, 3000))
    ExpectSameFuseVariants(device(), s.p, s.frame, s.what);
}

TEST_F(FuseVk, RandomCloudsHdl64) {
  const SensorProfile hdl64e = LoadSensorProfile("hdl64e", test::SensorsDir());
  for (const test::RandomStreet& s : test::RandomStreets(hdl64e, {7, 8}, 120000, 0))
    ExpectSameFuseVariants(device(), s.p, s.frame, s.what);
}

TEST_F(FuseVk, EmptyCloud) {
  const SensorProfile s = test::SmallSensor();
  const Params p = ParamsForSensor(s);
  Frame f;
  RunReference(Cloud(), p, MakeTables(s, p), f);
  ExpectSameFuse(device(), p, f, "empty cloud");
}

TEST_F(FuseVk, VetoAtItsExactThresholds) { Images(test::VetoThresholdImages()); }

TEST_F(FuseVk, StepSpareAtItsExactThresholds) { Images(test::StepSpareThresholdImages()); }

TEST_F(FuseVk, PassedUnderAtItsExactThresholds) { Images(test::PassedUnderThresholdImages()); }

TEST_F(FuseVk, TopRowsAndReachBeyondTheImage) {
  // Ground pixels on every row of a 5-row image under occluders on every row above: rows 0 ..
  // occ_rows - 1 see fewer rows than occ_rows (row 0 none); occ_rows beyond the image.
  for (uint32_t occ_rows : {0u, 1u, 2u, 4u, 5u, 9u, 0xFFFFFFFFu}) {
    test::FuseImage im(16, 5);
    im.p.occ_rows = occ_rows;
    for (uint32_t u = 0; u < 16; ++u)
      for (uint32_t v = 0; v < 5; ++v) {
        // Column u: the occluder row (higher, nearer) is row u % 5; every other pixel is ground.
        if (v == u % 5)
          im.Measure(v, u, kPixNonGround, false, 5.0f, 1.0f);
        else
          im.Measure(v, u, (u & 8) ? kPixUnknown : kPixGround, true, 20.0f, -1.7f);
      }
    ExpectSameFuse(device(), im.p, im.f, "top rows, occ_rows " + std::to_string(occ_rows));
  }
}

TEST_F(FuseVk, RandomImagesEveryClassAndOpinion) {
  // Classes 0-3, points with either coarse bit, hole-filled and empty pixels, ranges and heights
  // from a few values so that equality with reach and top happens, and unusual class values.
  std::mt19937 rng(42);
  for (uint32_t trial = 0; trial < 12; ++trial) {
    const uint32_t width = 1 + rng() % 700, beams = 1 + rng() % 70;
    test::FuseImage im(width, beams);
    im.p.occ_rows = rng() % 6;
    im.p.occ_margin = (rng() % 2) ? 0.0f : 0.3f;
    im.p.occ_rise = (rng() % 2) ? 0.0f : 0.075f;
    im.p.occ_grade = (rng() % 2) ? 0.0f : 0.0002f;
    const float fronts[] = {0.0f, 0.3f, 1000.0f};  // 10 + 0.3 = 10.3: range above == the bound
    im.p.occ_front = fronts[rng() % 3];
    const float passes[] = {0.0f, 0.15f, 1000.0f};  // -1.7 * (2.5 - 10) = 12.75 = 1.275 * 10
    im.p.occ_pass = passes[rng() % 3];
    im.p.occ_step_rows = rng() % 12;
    im.p.occ_step = (rng() % 2) ? 0.0f : 0.15f;  // -1.7 + 0.15 = -1.55: a height above == base
    im.p.occ_step_grade = (rng() % 2) ? 0.0f : 0.1f;
    im.p.occ_step_reach = (rng() % 2) ? 0.3f : 3.0f;  // 10 + 0.3 = 10.3: a range above == far
    const float values[] = {0.0f,   2.5f,  2.8f,    2.575f, 10.0f,  10.3f,
                            10.32f, -1.7f, -1.625f, 1.0f,   -1.55f, 13.0f};
    for (uint32_t v = 0; v < beams; ++v)
      for (uint32_t u = 0; u < width; ++u) {
        const uint32_t kind = rng() % 8;
        const float r = values[rng() % 12], z = values[rng() % 12];
        if (kind < 5) {
          im.Measure(v, u, rng() % 4, rng() % 2, r, z);
        } else if (kind < 7) {
          im.Fill(v, u, rng() % 4, r, z);
        } else {  // empty, with leftover features
          im.f.f_range[im.Pix(v, u)] = r;
          im.f.f_height[im.Pix(v, u)] = z;
          if (rng() % 4 == 0) im.f.pixel_class[im.Pix(v, u)] = 7;  // a class the rule never sees
        }
      }
    ExpectSameFuse(device(), im.p, im.f, "random image " + std::to_string(trial));
  }
}

class FuseVkScene : public test::StageScene {};

TEST_P(FuseVkScene, MatchesTheReference) { ExpectSameFuseVariants(device(), p, frame, what); }

LPIR_STAGE_SCENES(FuseVkScene);

}  // namespace
}  // namespace lpir
