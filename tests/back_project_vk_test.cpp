// Stage 9, back-project, on Vulkan (shaders/back_project.comp) against the CPU reference
// (reference_cpu/back_project.cpp): label and why of every point. The GPU writes one byte per
// point, label | why << 1, four points a word; the test compares those bytes with the
// reference's label_why byte for byte (the last word's padding must be 0), then the unpacked
// label and why too.
// Inputs from the whole CPU pipeline (RunReference) on random clouds, the simulated HDL-64E
// scenes and the real scans when ../shared/data is present; each also with the gates set exactly
// to measured dr / dz values of lost points (and one ulp below), so that equality is exercised;
// and hand-made frames covering every flag, winner / lost, coarse and pixel-label combination.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "apps/sim/scene.h"
#include "host/gpu/back_project.h"
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

// Point i's inputs (and its cloud coordinates when known), for a mismatch report.
std::string PointText(const Params& p, const Frame& f, const Cloud* cloud, uint32_t i) {
  std::string s = "point " + std::to_string(i);
  if (cloud && i < cloud->size())
    s += " (x " + FloatText(cloud->x(i)) + ", y " + FloatText(cloud->y(i)) + ", z " +
         FloatText(cloud->z(i)) + ")";
  s += ": flags " + std::to_string(f.flags[i]) + ", r2 " + FloatText(f.r2[i]) + ", zt " +
       FloatText(f.zt[i]) + ", coarse " + std::to_string(f.coarse[i]);
  const uint32_t pix = f.point_pixel[i];
  s += ", pixel " + ValueText(pix);
  if (pix != kNone && pix < f.pixel_label.size()) {
    s += " (row " + std::to_string(pix / p.width) + ", column " + std::to_string(pix % p.width) +
         "): label " + std::to_string(f.pixel_label[pix]) + ", winner " +
         ValueText(f.pixel_point[pix]) + ", range " + FloatText(f.f_range[pix]) + ", height " +
         FloatText(f.f_height[pix]) + "; sqrt(r2) " + FloatText(exact::Sqrt(f.r2[i]));
  }
  return s;
}

struct Counts {
  uint64_t compared = 0, mismatches = 0;
};
Counts g_total;

// The GPU's label_why bytes (n rounded up to a word) against the reference's n bytes, and the
// padding past n against 0.
size_t CompareBytes(const std::vector<uint8_t>& cpu, const std::vector<uint8_t>& gpu,
                    const Params& p, const Frame& in, const Cloud* cloud, const std::string& what) {
  const size_t n = cpu.size();
  EXPECT_EQ(gpu.size(), vk::BackProjectStage::LabelWhyBytes(n)) << what << ": label_why bytes";
  if (gpu.size() != vk::BackProjectStage::LabelWhyBytes(n)) return 0;
  size_t first = n, count = 0;
  for (size_t i = 0; i < n; ++i)
    if (cpu[i] != gpu[i]) {
      if (first == n) first = i;
      ++count;
    }
  for (size_t i = n; i < gpu.size(); ++i) EXPECT_EQ(gpu[i], 0) << what << ": padding byte " << i;
  g_total.compared += n;
  g_total.mismatches += count;
  EXPECT_EQ(count, 0u) << "back_project (" << what << "): buffer label_why differs at element "
                       << first << " (" << count << " of " << n << " differ): CPU "
                       << (first < n ? ValueText(cpu[first]) : "") << ", GPU "
                       << (first < n ? ValueText(gpu[first]) : "") << "; "
                       << (first < n ? PointText(p, in, cloud, uint32_t(first)) : "");
  return n;
}

// Stage 9 on the GPU, as lpir::BackProject(p, f): *words gets the LabelWhyBytes(n) bytes the
// shader wrote (the last word's padding included), f.label_why their first n, f.label and f.why
// unpacked from them. An error when a byte is no PackLabelWhy of a label and a why.
vk::Status BackProjectOnGpu(const vk::Device& device, const Params& p, Frame& f,
                            std::vector<uint8_t>* words, double* gpu_ns) {
  const uint32_t n = f.n;
  const size_t pixels = size_t(p.width) * p.beams;
  test::StageHarness h(device, "back_project");
  vk::BackProjectBuffers b;
  b.params = h.Uniform(p);
  b.flags = h.In("flags", f.flags, n);
  b.point_pixel = h.In("point_pixel", f.point_pixel, n);
  b.pixel_point = h.In("pixel_point", f.pixel_point, pixels);
  b.pixel_label = h.In("pixel_label", f.pixel_label, pixels);
  b.f_range = h.In("f_range", f.f_range, pixels);
  b.f_height = h.In("f_height", f.f_height, pixels);
  b.r2 = h.In("r2", f.r2, n);
  b.zt = h.In("zt", f.zt, n);
  b.coarse = h.In("coarse", f.coarse, n);
  b.label_why = h.Out(words, vk::BackProjectStage::LabelWhyBytes(n));
  LPIR_VK_RETURN_IF_ERROR(h.Run<vk::BackProjectStage>(
      b, [&](const vk::BackProjectStage& s, vk::CommandBuffer& cmd) { return s.Record(cmd, n); },
      gpu_ns));
  f.label_why.assign(words->begin(), words->begin() + n);
  f.label.resize(n);
  f.why.resize(n);
  for (uint32_t i = 0; i < n; ++i) {
    const uint8_t byte = f.label_why[i];
    if (WhyOf(byte) > kWhyNoise || LabelOf(byte) != (WhyOf(byte) == kWhyGround))
      return vk::UsageError("back_project", "point " + std::to_string(i) + ": byte " +
                                                std::to_string(byte) + " is no label and why");
    f.label[i] = LabelOf(byte);
    f.why[i] = WhyOf(byte);
  }
  return vk::Status();
}

// Runs lpir::BackProject and BackProjectOnGpu on the same inputs and compares label_why, then
// the unpacked label and why. Returns the number of bytes compared (1 per point).
uint64_t ExpectSameBackProject(const vk::Context& context, const Params& p, const Frame& in,
                               const Cloud* cloud, const std::string& what) {
  Frame cpu = in, gpu = in;
  cpu.label.clear(), cpu.why.clear(), cpu.label_why.clear();
  gpu.label.assign(in.n, 0xEE), gpu.why.assign(in.n, 0xEE), gpu.label_why.assign(in.n, 0xEE);
  BackProject(p, cpu);
  std::vector<uint8_t> words(in.n, 0xEE);
  double gpu_ns = 0;
  const vk::Status status = BackProjectOnGpu(context.device(), p, gpu, &words, &gpu_ns);
  EXPECT_TRUE(status.ok()) << what << ": " << status.message();
  if (!status.ok()) return 0;
  const uint64_t compared = CompareBytes(cpu.label_why, words, p, in, cloud, what);
  EXPECT_EQ(gpu.label_why, cpu.label_why) << what << ": Frame label_why";
  EXPECT_EQ(gpu.label, cpu.label) << what << ": unpacked label";
  EXPECT_EQ(gpu.why, cpu.why) << what << ": unpacked why";
  size_t why[4] = {0, 0, 0, 0}, lost_gated = 0;
  for (uint32_t i = 0; i < in.n; ++i) {
    EXPECT_EQ(cpu.label_why[i], PackLabelWhy(cpu.label[i], cpu.why[i])) << what << ": point " << i;
    if (cpu.why[i] < 4) ++why[cpu.why[i]];
    if ((in.flags[i] & 3u) == kPointValid && in.pixel_label[in.point_pixel[i]] == kPixGround &&
        in.pixel_point[in.point_pixel[i]] != i && in.coarse[i] == 0)
      ++lost_gated;
  }
  std::printf(
      "[back_project] %s: %u points (non-ground %zu, ground %zu, invalid %zu, noise %zu; %zu "
      "through the gates), gates %g / %g: %llu bytes compared, GPU %.3f ms\n",
      what.c_str(), in.n, why[0], why[1], why[2], why[3], lost_gated, double(p.bp_range_gate),
      double(p.bp_height_gate), static_cast<unsigned long long>(compared), gpu_ns / 1e6);
  return compared;
}

// The frame's parameters, then gates set exactly on measured dr and dz of lost points (so that
// dr == gate and dz == gate occur) and one ulp below them, then zero and huge gates.
void ExpectSameBackProjectVariants(const vk::Context& context, const Params& p, const Frame& f,
                                   const Cloud* cloud, const std::string& what) {
  {
    Frame again = f;
    BackProject(p, again);
    EXPECT_EQ(again.label, f.label) << what << ": RunReference's label";
    EXPECT_EQ(again.why, f.why) << what << ": RunReference's why";
    EXPECT_EQ(again.label_why, f.label_why) << what << ": RunReference's label_why";
  }
  EXPECT_EQ(ExpectSameBackProject(context, p, f, cloud, what), uint64_t(f.n));
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
    EXPECT_EQ(ExpectSameBackProject(context, q, f, cloud, what + ", " + g.name), uint64_t(f.n));
  }
}

// A random street-like cloud with many points sharing pixels (lost points), invalid and noise
// points.
Cloud RandomCloud(size_t n, float sensor_height, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  Cloud cloud;
  for (size_t i = 0; i < n; ++i) {
    const float az = unit(rng) * 6.2831853f, r = 3.0f + 50.0f * unit(rng) * unit(rng);
    float x = r * std::cos(az), y = r * std::sin(az), z = -sensor_height + 0.05f * unit(rng);
    float in = unit(rng) * 0.9f;
    switch (rng() % 12) {
      case 0:
      case 1:
      case 2:
        z = -sensor_height + 3.0f * unit(rng);
        break;
      case 3:
        z += 0.1f * r * unit(rng);
        break;
      case 4:
        if (rng() % 4 == 0) x = 0.0f, y = 0.0f, z = 0.0f;  // invalid
        break;
      case 5:
        if (rng() % 4 == 0) z = -sensor_height - 1.0f, in = 0.0f;  // reflection noise
        break;
      case 6:
        if (i > 0) {  // a second return next to the previous point: a lost point, near its winner
          x = cloud.x(i - 1) * (1.0f + 0.002f * unit(rng));
          y = cloud.y(i - 1) * (1.0f + 0.002f * unit(rng));
          z = cloud.z(i - 1) + 0.3f * (unit(rng) - 0.5f);
        }
        break;
      default:
        break;
    }
    cloud.Push(x, y, z, in);
  }
  return cloud;
}

class BackProjectVk : public test::VkTest {};

TEST_F(BackProjectVk, RandomCloudsSmallSensor) {
  const SensorProfile s = test::SmallSensor();
  const Params p = ParamsForSensor(s);
  const Tables t = MakeTables(s, p);
  for (uint32_t seed : {1u, 2u, 3u}) {
    const Cloud cloud = RandomCloud(1 + 4000 * seed, s.sensor_height, seed);
    Frame f;
    RunReference(cloud, p, t, f);
    ExpectSameBackProjectVariants(context(), p, f, &cloud,
                                  "small sensor, random cloud " + std::to_string(seed));
  }
}

TEST_F(BackProjectVk, RandomCloudsHdl64) {
  const SensorProfile s = LoadSensorProfile("hdl64e", test::SensorsDir());
  const Params p = ParamsForSensor(s);
  const Tables t = MakeTables(s, p);
  for (uint32_t seed : {7u, 8u}) {
    const Cloud cloud = RandomCloud(150001, s.sensor_height, seed);
    Frame f;
    RunReference(cloud, p, t, f);
    ExpectSameBackProjectVariants(context(), p, f, &cloud,
                                  "hdl64e, random cloud " + std::to_string(seed));
  }
}

TEST_F(BackProjectVk, EmptyCloud) {
  const SensorProfile s = test::SmallSensor();
  const Params p = ParamsForSensor(s);
  Frame f;
  RunReference(Cloud(), p, MakeTables(s, p), f);
  EXPECT_EQ(ExpectSameBackProject(context(), p, f, nullptr, "empty cloud"), 0u);
}

TEST_F(BackProjectVk, SimulatedScenesHdl64) {
  const SensorProfile s = LoadSensorProfile("hdl64e", test::SensorsDir());
  const Params p = ParamsForSensor(s);
  const Tables t = MakeTables(s, p);
  const struct {
    SceneKind kind;
    uint32_t seed;
    const char* name;
  } scenes[] = {{kUrban, 1, "urban 1"},
                {kUrban, 4, "urban 4"},
                {kFlatWithObjects, 0, "flat with objects"},
                {kFlat, 0, "flat"}};
  for (const auto& sc : scenes) {
    SimOptions o;
    o.seed = sc.seed;
    o.kind = sc.kind;
    const SimScan scan = Simulate(s, o);
    Frame f;
    RunReference(scan.cloud, p, t, f);
    ExpectSameBackProjectVariants(context(), p, f, &scan.cloud,
                                  std::string("simulated ") + sc.name);
  }
}

void RealScan(const vk::Context& context, const char* file) {
  const Cloud cloud = ReadKittiBin(test::DataFile(file));
  const SensorProfile s = LoadSensorProfile("hdl64e", test::SensorsDir());
  const Params p = ParamsForSensor(s);
  Frame f;
  RunReference(cloud, p, MakeTables(s, p), f);
  ExpectSameBackProjectVariants(context, p, f, &cloud, file);
}

TEST_F(BackProjectVk, Kitti07Frame964) {
  LPIR_REQUIRE_DATA("kitti/07/velodyne/000964.bin");
  RealScan(context(), "kitti/07/velodyne/000964.bin");
}

TEST_F(BackProjectVk, KittiUnknownFrame56) {
  LPIR_REQUIRE_DATA("kitti/unknown/velodyne/000056.bin");
  RealScan(context(), "kitti/unknown/velodyne/000056.bin");
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
  EXPECT_EQ(ExpectSameBackProject(context(), p, f, nullptr, "hand-made"), uint64_t(f.n));
  Params q = p;
  q.bp_range_gate = 0.0f;
  q.bp_height_gate = 0.0f;
  EXPECT_EQ(ExpectSameBackProject(context(), q, f, nullptr, "hand-made, zero gates"),
            uint64_t(f.n));
  const Params d = DefaultParams();
  q.bp_range_gate = d.bp_range_gate;
  q.bp_height_gate = d.bp_height_gate;
  EXPECT_EQ(ExpectSameBackProject(context(), q, f, nullptr, "hand-made, default gates"),
            uint64_t(f.n));
}

class TotalPrinter : public ::testing::Environment {
 public:
  void TearDown() override {
    std::printf("[back_project] total: %llu bytes compared, %llu mismatches\n",
                static_cast<unsigned long long>(g_total.compared),
                static_cast<unsigned long long>(g_total.mismatches));
  }
};
::testing::Environment* const kTotal = ::testing::AddGlobalTestEnvironment(new TotalPrinter);

}  // namespace
}  // namespace lpir
