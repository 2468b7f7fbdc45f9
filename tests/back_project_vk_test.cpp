// back_project, on Vulkan (shaders/back_project.comp) against the CPU reference
// (reference_cpu/back_project.cpp): label and why of every point. The GPU writes one byte per
// point, label | why << 1, four points a word; the test compares those bytes with the
// reference's label_why byte for byte (the last word's padding must be 0), then the unpacked
// label and why too.
// Inputs from the whole CPU pipeline (RunReference) on random clouds and the scenes of
// tests/stage_scenes.h (tests/stage_harness.h runs and compares); each also with the gates set
// exactly to measured dr / dz values of lost points (and one ulp below), so that equality is
// exercised; and hand-made frames covering every flag, winner / lost, coarse and pixel-label
// combination.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "reference_cpu/exact.h"
#include "tests/stage_harness.h"
#include "tests/stage_scenes.h"
#include "tests/stage_test_util.h"

namespace lpir {
namespace {

// back_project on both sides (tests/stage_harness.h compares label_why), then what the harness does
// not: the padding of label_why's last word is 0 (the harness fills it with 0xEE before), and the
// reference's label and why pack into its label_why (the GPU unpacks them from those bytes).
void ExpectSameBackProject(const vk::Device& device, const Params& p, const Frame& in,
                           const Cloud* cloud, const std::string& what) {
  test::StageHarness<vk::BackProjectStage> h(device, test::FrameLimits::Of(in.n, p), nullptr);
  test::ExpectSameStage(h, p, nullptr, cloud, in, what);
  std::vector<uint8_t> words;
  const vk::Status read =
      h.bench().Bytes("label_why", vk::BackProjectStage::LabelWhyBytes(in.n), &words);
  EXPECT_TRUE(read.ok()) << what << ": " << read.message();
  for (size_t i = in.n; i < words.size(); ++i) EXPECT_EQ(words[i], 0) << what << ": padding " << i;
  Frame cpu = in;
  BackProject(p, cpu);
  std::vector<uint8_t> packed(cpu.n);
  for (uint32_t i = 0; i < cpu.n; ++i) packed[i] = PackLabelWhy(cpu.label[i], cpu.why[i]);
  EXPECT_EQ(packed, cpu.label_why) << what << ": the reference's label and why";
}

// The frame's parameters, then gates set exactly on measured dr and dz of lost points (so that
// dr == gate and dz == gate occur) and one ulp below them, then zero and huge gates.
void ExpectSameBackProjectVariants(const vk::Device& device, const Params& p, const Frame& f,
                                   const Cloud* cloud, const std::string& what) {
  ExpectSameBackProject(device, p, f, cloud, what);
  std::vector<float> dr, dz;
  for (uint32_t i = 0; i < f.n; ++i) {
    if ((f.flags[i] & 3u) != kPointValid) continue;
    const uint32_t pix = f.point_pixel[i];
    if (f.pixel_label[pix] != kPixGround || f.pixel_point[pix] == i || f.coarse[i] != 0) continue;
    dr.push_back(std::fabs(exact::Sqrt(f.r2[i]) - f.f_range[pix]));
    dz.push_back(std::fabs(f.zt[i] - f.f_height[pix]));
  }
  std::sort(dr.begin(), dr.end());
  std::sort(dz.begin(), dz.end());
  struct Gates {
    float range, height;
    const char* name;
  };
  std::vector<Gates> gates = {{0.0f, 0.0f, "zero gates"}, {1e30f, 1e30f, "huge gates"}};
  if (!dr.empty()) {
    const float r = dr[dr.size() / 2], z = dz[dz.size() / 2];
    const float r3 = dr[dr.size() / 4], z3 = dz[3 * dz.size() / 4];
    gates.push_back({r, z, "gates on median dr, dz"});
    gates.push_back({std::nextafter(r, 0.0f), std::nextafter(z, 0.0f), "one ulp below them"});
    gates.push_back({r3, 1e30f, "range gate on a dr quartile"});
    gates.push_back({1e30f, z3, "height gate on a dz quartile"});
    gates.push_back({r3, z3, "both on quartiles"});
  }
  for (const Gates& g : gates) {
    Params q = p;
    q.bp_range_gate = g.range;
    q.bp_height_gate = g.height;
    ExpectSameBackProject(device, q, f, cloud, what + ", " + g.name);
  }
}

class BackProjectVk : public test::VkTest {};

TEST_F(BackProjectVk, RandomCloudsSmallSensor) {
  for (const test::RandomStreet& s : test::RandomStreets(test::SmallSensor(), {1, 2, 3}, 1, 4000))
    ExpectSameBackProjectVariants(device(), s.p, s.frame, &s.cloud, s.what);
}

TEST_F(BackProjectVk, RandomCloudsHdl64) {
  const SensorProfile hdl64e = LoadSensorProfile("hdl64e", test::SensorsDir());
  for (const test::RandomStreet& s : test::RandomStreets(hdl64e, {7, 8}, 150001, 0))
    ExpectSameBackProjectVariants(device(), s.p, s.frame, &s.cloud, s.what);
}

TEST_F(BackProjectVk, EmptyCloud) {
  const SensorProfile s = test::SmallSensor();
  const Params p = ParamsForSensor(s);
  Frame f;
  RunReference(Cloud(), p, MakeTables(s, p), f);
  ExpectSameBackProject(device(), p, f, nullptr, "empty cloud");
}

TEST_F(BackProjectVk, HandMadeEveryCase) {
  // One pixel per case, the winner at point 0 of each pixel and lost points after it: every flag
  // (0, valid, noise, noise without valid, stray high bits), every pixel label, winner or lost,
  // coarse 0 / 1, and lost points exactly on the gates and one ulp outside.
  // Gates, range and height chosen so that z +- gate and the squares of r +- gate are exact: the
  // lost points then lie exactly on the gates (dr == gate, dz == gate) or one ulp beyond.
  Params p = DefaultParams();
  p.width = 32;
  p.beams = 4;
  p.bp_range_gate = 0.25f;
  p.bp_height_gate = 0.125f;
  const uint32_t pixels = p.width * p.beams;
  Frame f;
  f.pixel_point.assign(pixels, kNone);
  f.pixel_label.assign(pixels, kPixEmpty);
  f.f_range.assign(pixels, 0.0f);
  f.f_height.assign(pixels, 0.0f);
  auto add = [&](uint32_t flags, uint32_t pix, float range, float zt, uint32_t coarse) {
    f.flags.push_back(flags);
    f.point_pixel.push_back((flags & kPointValid) ? pix : kNone);
    f.r2.push_back((flags & kPointValid) ? range * range : 0.0f);
    f.zt.push_back((flags & kPointValid) ? zt : 0.0f);
    f.coarse.push_back(coarse);
    return f.n++;
  };
  uint32_t pix = 0;
  const float r = 12.0f, z = -1.5f;
  for (uint32_t label : {kPixNonGround, kPixGround, kPixUnknown, kPixEmpty, 9u}) {
    for (uint32_t coarse : {0u, 1u}) {
      const uint32_t winner = add(kPointValid, pix, r, z, coarse);
      f.pixel_point[pix] = winner;
      f.pixel_label[pix] = label;
      f.f_range[pix] = exact::Sqrt(r * r);
      f.f_height[pix] = z;
      // Lost points: within, on and beyond the gates.
      const float sr = exact::Sqrt(r * r);
      const float gate_z[] = {z + p.bp_height_gate, z - p.bp_height_gate,
                              std::nextafter(z + p.bp_height_gate, 1e9f),
                              std::nextafter(z - p.bp_height_gate, -1e9f), z};
      for (float zz : gate_z)
        for (uint32_t c2 : {0u, 1u}) add(kPointValid, pix, r, zz, c2);
      // Ranges whose exact Sqrt lands exactly on, and just beyond, f_range +- gate.
      for (float target :
           {sr + p.bp_range_gate, sr - p.bp_range_gate, std::nextafter(sr + p.bp_range_gate, 1e9f),
            std::nextafter(sr - p.bp_range_gate, 0.0f)})
        for (uint32_t c2 : {0u, 1u}) add(kPointValid, pix, target, z, c2);
      for (uint32_t flags : {0u, 2u, 3u, 4u, 5u, 7u, 0x80000001u}) add(flags, pix, r, z, coarse);
      ++pix;
    }
  }
  ASSERT_LE(pix, pixels);
  // Re-derive the gate check of the 'exact' range cases: dr must sometimes equal the gate.
  size_t on_gate = 0;
  for (uint32_t i = 0; i < f.n; ++i) {
    if (f.point_pixel[i] == kNone) continue;
    const uint32_t q = f.point_pixel[i];
    const float dr = std::fabs(exact::Sqrt(f.r2[i]) - f.f_range[q]);
    const float dz = std::fabs(f.zt[i] - f.f_height[q]);
    on_gate += (dr == p.bp_range_gate) + (dz == p.bp_height_gate);
  }
  EXPECT_GT(on_gate, 0u) << "no lost point lies exactly on a gate";
  std::printf("[back_project] hand-made: %zu gate equalities\n", on_gate);
  ExpectSameBackProject(device(), p, f, nullptr, "hand-made");
  Params q = p;
  q.bp_range_gate = 0.0f;
  q.bp_height_gate = 0.0f;
  ExpectSameBackProject(device(), q, f, nullptr, "hand-made, zero gates");
  const Params d = DefaultParams();
  q.bp_range_gate = d.bp_range_gate;
  q.bp_height_gate = d.bp_height_gate;
  ExpectSameBackProject(device(), q, f, nullptr, "hand-made, default gates");
}

class BackProjectVkScene : public test::StageScene {};

TEST_P(BackProjectVkScene, MatchesTheReference) {
  ExpectSameBackProjectVariants(device(), p, frame, &cloud, what);
}

LPIR_STAGE_SCENES(BackProjectVkScene);

}  // namespace
}  // namespace lpir
