// Stage 7, fuse, on Vulkan (shaders/fuse.comp) against the CPU reference
// (reference_cpu/fuse.cpp): pixel_fused byte for byte. Inputs from the whole CPU pipeline
// (RunReference) on random clouds, the simulated HDL-64E scenes and the real scans when
// ../shared/data is present, each also under other veto parameters; and hand-made images that
// put occluders exactly on the veto's thresholds (range == reach, height == top, one ulp either
// side) and pixels above exactly on the step spare's (range == far, height == bound), in the top
// rows and with occ_rows beyond the image.
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
#include "host/gpu/fuse.h"
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

// The inputs of pixel `pix` and of the occ_rows pixels above it, for a mismatch report.
std::string PixelText(const Params& p, const Frame& f, uint32_t pix) {
  const uint32_t v = pix / p.width, u = pix % p.width;
  std::string s = "pixel " + std::to_string(pix) + " (row " + std::to_string(v) + ", column " +
                  std::to_string(u) + "): class " + std::to_string(f.pixel_class[pix]) +
                  ", point " + ValueText(f.pixel_point[pix]);
  if (f.pixel_point[pix] != kNone && f.pixel_point[pix] < f.coarse.size())
    s += ", coarse " + std::to_string(f.coarse[f.pixel_point[pix]]);
  s += ", filled " + std::to_string(f.pixel_filled[pix]) + ", range " + FloatText(f.f_range[pix]) +
       ", height " + FloatText(f.f_height[pix]);
  for (uint32_t k = 1; k <= p.occ_rows && k <= v; ++k) {
    const uint32_t a = pix - k * p.width;
    s += "; above " + std::to_string(k) + ": filled " + std::to_string(f.pixel_filled[a]) +
         ", range " + FloatText(f.f_range[a]) + ", height " + FloatText(f.f_height[a]);
  }
  return s;
}

struct Counts {
  uint64_t compared = 0, mismatches = 0;
};
Counts g_total;

// Stage 7 on the GPU, as lpir::Fuse(p, f): reads f.pixel_class, f.pixel_point, f.coarse,
// f.pixel_filled, f.f_range and f.f_height, fills f.pixel_fused.
vk::Status FuseOnGpu(const vk::Device& device, const Params& p, Frame& f, double* gpu_ns) {
  const size_t pixels = size_t(p.width) * p.beams;
  // Without points the reference reads 0 in place of coarse[0].
  const std::vector<uint32_t> no_points(4, 0);
  const std::vector<uint32_t>& coarse = f.coarse.empty() ? no_points : f.coarse;
  test::StageHarness h(device, "fuse");
  vk::FuseBuffers b;
  b.params = h.Uniform(p);
  b.pixel_class = h.In("pixel_class", f.pixel_class, pixels);
  b.pixel_point = h.In("pixel_point", f.pixel_point, pixels);
  b.coarse = h.In("coarse", coarse, coarse.size());
  b.pixel_filled = h.In("pixel_filled", f.pixel_filled, pixels);
  b.f_range = h.In("f_range", f.f_range, pixels);
  b.f_height = h.In("f_height", f.f_height, pixels);
  b.pixel_fused = h.Out(&f.pixel_fused, pixels);
  return h.Run<vk::FuseStage>(
      b,
      [&](const vk::FuseStage& s, vk::CommandBuffer& cmd) {
        return s.Record(cmd, p.width, p.beams);
      },
      gpu_ns);
}

// Runs lpir::Fuse and FuseOnGpu on the same inputs (`in`'s stage 1-6 buffers and coarse) and
// compares pixel_fused byte for byte. Returns the number of values compared.
uint64_t ExpectSameFuse(const vk::Context& context, const Params& p, const Frame& in,
                        const std::string& what) {
  Frame cpu = in, gpu = in;
  cpu.pixel_fused.clear();
  gpu.pixel_fused.assign(in.pixel_class.size(), 0xDEADBEEFu);  // must be overwritten
  Fuse(p, cpu);
  double gpu_ns = 0;
  const vk::Status status = FuseOnGpu(context.device(), p, gpu, &gpu_ns);
  EXPECT_TRUE(status.ok()) << what << ": " << status.message();
  if (!status.ok()) return 0;
  EXPECT_EQ(gpu.pixel_fused.size(), cpu.pixel_fused.size()) << what;
  if (gpu.pixel_fused.size() != cpu.pixel_fused.size()) return 0;
  const size_t n = cpu.pixel_fused.size();
  size_t first = n, count = 0;
  uint32_t hist[4] = {0, 0, 0, 0};
  for (size_t i = 0; i < n; ++i) {
    if (cpu.pixel_fused[i] < 4) ++hist[cpu.pixel_fused[i]];
    if (std::memcmp(&cpu.pixel_fused[i], &gpu.pixel_fused[i], 4) != 0) {
      if (first == n) first = i;
      ++count;
    }
  }
  g_total.compared += n;
  g_total.mismatches += count;
  EXPECT_EQ(count, 0u) << "fuse (" << what << "): buffer pixel_fused differs at element " << first
                       << " (" << count << " of " << n << " differ): CPU "
                       << (first < n ? ValueText(cpu.pixel_fused[first]) : "") << ", GPU "
                       << (first < n ? ValueText(gpu.pixel_fused[first]) : "") << "; "
                       << (first < n ? PixelText(p, in, uint32_t(first)) : "");
  std::printf(
      "[fuse] %s: %ux%u pixels (non-ground %u, ground %u, unknown %u, empty %u), occ_rows %u: "
      "%zu values compared, %zu differ, GPU %.3f ms\n",
      what.c_str(), p.beams, p.width, hist[0], hist[1], hist[2], hist[3], p.occ_rows, n, count,
      gpu_ns / 1e6);
  return n;
}

// The pipeline's own stage 7 output must be what lpir::Fuse gives (the test re-runs it), and the
// GPU must match it under the frame's parameters and under other veto settings.
void ExpectSameFuseVariants(const vk::Context& context, const Params& p, const Frame& f,
                            const std::string& what) {
  {
    Frame again = f;
    Fuse(p, again);
    EXPECT_EQ(again.pixel_fused, f.pixel_fused) << what << ": RunReference's pixel_fused";
  }
  EXPECT_EQ(ExpectSameFuse(context, p, f, what), size_t(p.width) * p.beams);
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
    q.occ_rows = var.rows;
    q.occ_margin = var.margin;
    q.occ_rise = var.rise;
    q.occ_grade = var.grade;
    q.occ_front = var.front;
    q.occ_pass = var.pass;
    q.occ_step_rows = var.step_rows;
    q.occ_step = var.step;
    q.occ_step_grade = var.step_grade;
    q.occ_step_reach = var.step_reach;
    char text[240];
    std::snprintf(text, sizeof(text),
                  "%s, occ_rows %u margin %g rise %g grade %g front %g pass %g, step rows %u "
                  "step %g grade %g reach %g",
                  what.c_str(), var.rows, double(var.margin), double(var.rise), double(var.grade),
                  double(var.front), double(var.pass), var.step_rows, double(var.step),
                  double(var.step_grade), double(var.step_reach));
    EXPECT_EQ(ExpectSameFuse(context, q, f, text), size_t(p.width) * p.beams);
  }
}

// A random street-like cloud: ground points around -sensor_height with noise, boxes of object
// points, points sharing pixels, and a few invalid points.
Cloud RandomCloud(size_t n, float sensor_height, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  Cloud cloud;
  for (size_t i = 0; i < n; ++i) {
    const float az = unit(rng) * 6.2831853f, r = 3.0f + 50.0f * unit(rng) * unit(rng);
    float x = r * std::cos(az), y = r * std::sin(az), z = -sensor_height + 0.05f * unit(rng);
    switch (rng() % 10) {
      case 0:
      case 1:
      case 2:  // an object: a wall / car / pole standing on the ground
        z = -sensor_height + 3.0f * unit(rng);
        break;
      case 3:  // a slope
        z += 0.1f * r * unit(rng);
        break;
      case 4:
        if (rng() % 8 == 0) x = 0.0f, y = 0.0f, z = 0.0f;  // invalid
        break;
      default:
        break;
    }
    cloud.Push(x, y, z, unit(rng) * 0.9f);
  }
  return cloud;
}

class FuseVk : public test::VkTest {};

TEST_F(FuseVk, RandomCloudsSmallSensor) {
  const SensorProfile s = test::SmallSensor();
  const Params p = ParamsForSensor(s);
  const Tables t = MakeTables(s, p);
  for (uint32_t seed : {1u, 2u, 3u}) {
    const Cloud cloud = RandomCloud(500 + 3000 * seed, s.sensor_height, seed);
    Frame f;
    RunReference(cloud, p, t, f);
    ExpectSameFuseVariants(context(), p, f, "small sensor, random cloud " + std::to_string(seed));
  }
}

TEST_F(FuseVk, RandomCloudsHdl64) {
  const SensorProfile s = LoadSensorProfile("hdl64e", test::SensorsDir());
  const Params p = ParamsForSensor(s);
  const Tables t = MakeTables(s, p);
  for (uint32_t seed : {7u, 8u}) {
    const Cloud cloud = RandomCloud(120000, s.sensor_height, seed);
    Frame f;
    RunReference(cloud, p, t, f);
    ExpectSameFuseVariants(context(), p, f, "hdl64e, random cloud " + std::to_string(seed));
  }
}

TEST_F(FuseVk, EmptyCloud) {
  const SensorProfile s = test::SmallSensor();
  const Params p = ParamsForSensor(s);
  Frame f;
  RunReference(Cloud(), p, MakeTables(s, p), f);
  EXPECT_EQ(ExpectSameFuse(context(), p, f, "empty cloud"), size_t(p.width) * p.beams);
}

TEST_F(FuseVk, SimulatedScenesHdl64) {
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
    ExpectSameFuseVariants(context(), p, f, std::string("simulated ") + sc.name);
  }
}

void RealScan(const vk::Context& context, const char* file) {
  const Cloud cloud = ReadKittiBin(test::DataFile(file));
  const SensorProfile s = LoadSensorProfile("hdl64e", test::SensorsDir());
  const Params p = ParamsForSensor(s);
  Frame f;
  RunReference(cloud, p, MakeTables(s, p), f);
  ExpectSameFuseVariants(context, p, f, file);
}

TEST_F(FuseVk, Kitti07Frame964) {
  LPIR_REQUIRE_DATA("kitti/07/velodyne/000964.bin");
  RealScan(context(), "kitti/07/velodyne/000964.bin");
}

TEST_F(FuseVk, KittiUnknownFrame56) {
  LPIR_REQUIRE_DATA("kitti/unknown/velodyne/000056.bin");
  RealScan(context(), "kitti/unknown/velodyne/000056.bin");
}

// --- hand-made images ---

// An image of beams x width pixels, every pixel empty; Measure() gives a pixel a point.
struct Image {
  Params p = DefaultParams();
  Frame f;
  Image(uint32_t width, uint32_t beams) {
    p.width = width;
    p.beams = beams;
    const size_t pixels = size_t(width) * beams;
    f.pixel_class.assign(pixels, kPixEmpty);
    f.pixel_point.assign(pixels, kNone);
    f.pixel_filled.assign(pixels, 0u);
    f.f_range.assign(pixels, 0.0f);
    f.f_height.assign(pixels, 0.0f);
  }
  uint32_t Pix(uint32_t v, uint32_t u) const { return v * p.width + u; }
  void Measure(uint32_t v, uint32_t u, uint32_t cls, bool coarse_ground, float range,
               float height) {
    const uint32_t pix = Pix(v, u);
    f.pixel_class[pix] = cls;
    f.pixel_point[pix] = f.n++;
    f.coarse.push_back(coarse_ground ? 1u : 0u);
    f.pixel_filled[pix] = 1u;
    f.f_range[pix] = range;
    f.f_height[pix] = height;
  }
  void Fill(uint32_t v, uint32_t u, uint32_t cls, float range, float height) {
    const uint32_t pix = Pix(v, u);
    f.pixel_class[pix] = cls;
    f.pixel_filled[pix] = 2u;
    f.f_range[pix] = range;
    f.f_height[pix] = height;
  }
};

// The reference's bounds of a pixel of class `cls`, each operation rounded (tests build with
// -ffp-contract=off).
float Reach(const Params& p, float r, uint32_t cls) {
  const float rr = r * r;
  const float grade = p.occ_grade * rr;
  const float near = r + p.occ_margin;
  const float any = near + grade;
  return cls == kPixGround ? std::min(any, r + p.occ_front) : any;
}
float Top(const Params& p, float z) { return z + p.occ_rise; }

// Runs the reference on `im` and checks each (column, vetoed) pair of `expect` on row v: vetoed is
// non-ground, else ground. Returns how many were vetoed and how many spared; `what` names the case.
std::pair<size_t, size_t> ExpectVerdicts(const Image& im, uint32_t v,
                                         const std::vector<std::pair<uint32_t, bool>>& expect,
                                         const std::string& what) {
  Frame cpu = im.f;
  Fuse(im.p, cpu);
  size_t vetoes = 0, spared = 0;
  for (const auto& [col, veto] : expect) {
    EXPECT_EQ(cpu.pixel_fused[im.Pix(v, col)], veto ? kPixVetoed : kPixGround)
        << "reference, " << what << ", column " << col;
    vetoes += veto, spared += !veto;
  }
  return {vetoes, spared};
}

TEST_F(FuseVk, VetoAtItsExactThresholds) {
  // Every column: a seed at row v (coarse ground, class ground or unknown: their reaches differ),
  // one occluder candidate k rows above; the candidate's range and height sit on the thresholds or
  // one ulp either side.
  for (uint32_t cls : {kPixGround, kPixUnknown})
    for (uint32_t occ_rows : {1u, 2u, 3u}) {
      const uint32_t beams = 8, v = 5;
      Image im(64, beams);
      im.p.occ_rows = occ_rows;
      const float ranges[] = {2.5f, 10.0f, 15.0f, 37.3f, 80.0f};
      uint32_t u = 0;
      std::vector<std::pair<uint32_t, bool>> expect;
      for (float r : ranges) {
        const float z = -1.7f + 0.01f * float(u);
        const float reach = Reach(im.p, r, cls), top = Top(im.p, z);
        const float below_reach = std::nextafter(reach, 0.0f);
        const float above_top = std::nextafter(top, 1e9f);
        const struct {
          float range, height;
          bool veto;
        } cands[] = {{below_reach, above_top, true},
                     {reach, above_top, false},  // range == reach: not nearer
                     {below_reach, top, false},  // height == top: not higher
                     {std::nextafter(reach, 1e9f), above_top, false},
                     {below_reach, std::nextafter(top, -1e9f), false},
                     {reach, top, false}};
        for (const auto& c : cands) {
          for (uint32_t k = 1; k <= occ_rows + 1 && u < im.p.width; ++k) {
            im.Measure(v, u, cls, true, r, z);
            if (k % 2)
              im.Measure(v - k, u, kPixNonGround, false, c.range, c.height);
            else
              im.Fill(v - k, u, kPixUnknown, c.range, c.height);  // hole-filled occluders count too
            expect.push_back({u, c.veto && k <= occ_rows});
            ++u;
          }
        }
        // The same values on an empty pixel above (filled 0) never veto.
        if (u < im.p.width) {
          im.Measure(v, u, cls, true, r, z);
          const uint32_t a = im.Pix(v - 1, u);
          im.f.f_range[a] = below_reach;
          im.f.f_height[a] = above_top;
          expect.push_back({u, false});
          ++u;
        }
      }
      ASSERT_LE(u, im.p.width);
      const auto [vetoes, spared] = ExpectVerdicts(
          im, v, expect, "class " + std::to_string(cls) + ", occ_rows " + std::to_string(occ_rows));
      EXPECT_GT(vetoes, 0u);
      EXPECT_GT(spared, 0u);
      EXPECT_EQ(
          ExpectSameFuse(context(), im.p, im.f, "thresholds, occ_rows " + std::to_string(occ_rows)),
          size_t(im.p.width) * beams);
    }
}

// The step spare's bound as the reference computes it for a pixel above at range ra (each
// operation rounded; tests build with -ffp-contract=off).
float StepBound(const Params& p, float r, float z, float ra) {
  const float base = exact::Ftz0(z + p.occ_step);
  const float d = exact::Ftz0(ra - r);
  const float beyond = d > 0.0f ? d : 0.0f;
  return exact::Ftz0(base + exact::Ftz0(p.occ_step_grade * beyond));
}
float StepFar(const Params& p, float r) { return exact::Ftz0(r + p.occ_step_reach); }

TEST_F(FuseVk, StepSpareAtItsExactThresholds) {
  // Every column: a seed at row v under an occluder one row up (nearer, higher than the veto's
  // top, not above the step's base), a landing two rows up (class ground, farther) and a candidate
  // three rows up whose range and height sit on the step's bounds or one ulp beside them.
  for (uint32_t cls : {kPixGround, kPixUnknown})
    for (uint32_t step_rows : {2u, 3u, 10u}) {
      const uint32_t beams = 8, v = 6;
      Image im(64, beams);
      im.p.occ_step_rows = step_rows;
      im.p.occ_pass = 1000.0f;  // the occluder is nearer: no pixel here is passed under
      const float ranges[] = {5.0f, 10.0f, 37.3f};
      uint32_t u = 0;
      std::vector<std::pair<uint32_t, bool>> expect;  // column, vetoed
      for (float r : ranges) {
        const float z = -1.7f + 0.01f * float(u);
        const float far = StepFar(im.p, r);
        const float ra = r + 1.5f, bound = StepBound(im.p, r, z, ra);
        const float far_in = std::nextafter(far, 0.0f);
        const struct {
          float landing_range, range, height;
          bool veto;
        } cands[] = {
            {r + 1.0f, ra, bound, false},                                // at the bound: not steep
            {r + 1.0f, ra, std::nextafter(bound, 1e9f), true},           // steep
            {r + 1.0f, far, z + 2.0f, false},                            // at far: not looked at
            {r + 1.0f, far_in, z + 2.0f, true},                          // inside far: steep
            {r, ra, z, true},                                            // landing at d == 0: none
            {far, ra, z, true},                                          // landing at far: none
            {std::nextafter(r, 1e9f), ra, z, false},                     // landing one ulp beyond
            {far_in, r - 1.0f, StepBound(im.p, r, z, r - 1.0f), false},  // nearer, at base
        };
        for (const auto& c : cands) {
          im.Measure(v, u, cls, true, r, z);
          im.Measure(v - 1, u, kPixNonGround, false, r - 0.5f, z + 0.1f);
          im.Measure(v - 2, u, kPixGround, true, c.landing_range, z);
          im.Measure(v - 3, u, kPixNonGround, false, c.range, c.height);
          // A candidate beyond occ_step_rows is not looked at: a steep one then spares.
          const bool looked_at = step_rows >= 3;
          const bool landing = c.landing_range > r && c.landing_range < far;
          expect.push_back({u, looked_at ? c.veto : !landing});
          ++u;
        }
      }
      ASSERT_LE(u, im.p.width);
      const auto [vetoes, spared] = ExpectVerdicts(
          im, v, expect,
          "class " + std::to_string(cls) + ", step rows " + std::to_string(step_rows));
      EXPECT_GT(vetoes, 0u);
      EXPECT_GT(spared, 0u);
      EXPECT_EQ(ExpectSameFuse(context(), im.p, im.f,
                               "step thresholds, step rows " + std::to_string(step_rows)),
                size_t(im.p.width) * beams);
    }
}

// The ray's clearance at the occluder's range as the reference computes it, Ftz0(z * Ftz0(ra - r)),
// and the farthest range ra < r at which it still reaches Ftz0(occ_pass * r) (one ulp farther, it
// no longer does, or ra is the pixel's own range).
float Clearance(float r, float z, float ra) { return exact::Ftz0(z * exact::Ftz0(ra - r)); }
float PassedAt(const Params& p, float r, float z) {
  const float pass = exact::Ftz0(p.occ_pass * r);
  float ra = std::min(r + pass / z, std::nextafter(r, 0.0f));
  while (!(Clearance(r, z, ra) >= pass)) ra = std::nextafter(ra, -1e9f);
  for (float up = std::nextafter(ra, 1e9f); up < r && Clearance(r, z, up) >= pass;
       up = std::nextafter(ra, 1e9f))
    ra = up;
  return ra;
}

TEST_F(FuseVk, PassedUnderAtItsExactThresholds) {
  // Every column: a seed at row v under one occluder a row up (higher than the veto's top) whose
  // range gives the ray a clearance at occ_pass or one ulp short of it; only a pixel of class
  // ground is spared, and only by an occluder nearer than itself.
  for (float occ_pass : {0.15f, 0.0f})
    for (uint32_t cls : {kPixGround, kPixUnknown}) {
      const uint32_t beams = 4, v = 3;
      Image im(64, beams);
      im.p.occ_pass = occ_pass;
      uint32_t u = 0;
      std::vector<std::pair<uint32_t, bool>> expect;  // column, vetoed
      for (float r : {5.0f, 10.0f, 15.0f, 37.3f}) {
        const float z = -1.7f + 0.01f * float(u);
        const float at = PassedAt(im.p, r, z);
        const struct {
          float range;
          bool passed;
        } cands[] = {{at, true},
                     {std::nextafter(at, 1e9f), false},
                     {r, false},  // d == 0: not nearer
                     {std::nextafter(r, 0.0f), occ_pass == 0.0f},
                     {0.5f * at, true}};
        for (const auto& c : cands) {
          im.Measure(v, u, cls, true, r, z);
          im.Measure(v - 1, u, kPixNonGround, false, c.range, z + 1.0f);
          expect.push_back({u, !(c.passed && cls == kPixGround)});
          ++u;
        }
      }
      ASSERT_LE(u, im.p.width);
      const auto [vetoes, spared] = ExpectVerdicts(
          im, v, expect, "class " + std::to_string(cls) + ", occ_pass " + std::to_string(occ_pass));
      EXPECT_GT(vetoes, 0u);
      EXPECT_EQ(spared > 0, cls == kPixGround);
      EXPECT_EQ(ExpectSameFuse(context(), im.p, im.f,
                               "passed under, occ_pass " + std::to_string(occ_pass)),
                size_t(im.p.width) * beams);
    }
}

TEST_F(FuseVk, TopRowsAndReachBeyondTheImage) {
  // Ground pixels on every row of a 5-row image under occluders on every row above: rows 0 ..
  // occ_rows - 1 see fewer rows than occ_rows (row 0 none); occ_rows beyond the image.
  for (uint32_t occ_rows : {0u, 1u, 2u, 4u, 5u, 9u, 0xFFFFFFFFu}) {
    Image im(16, 5);
    im.p.occ_rows = occ_rows;
    for (uint32_t u = 0; u < 16; ++u)
      for (uint32_t v = 0; v < 5; ++v) {
        // Column u: the occluder row (higher, nearer) is row u % 5; every other pixel is ground.
        if (v == u % 5)
          im.Measure(v, u, kPixNonGround, false, 5.0f, 1.0f);
        else
          im.Measure(v, u, (u & 8) ? kPixUnknown : kPixGround, true, 20.0f, -1.7f);
      }
    EXPECT_EQ(
        ExpectSameFuse(context(), im.p, im.f, "top rows, occ_rows " + std::to_string(occ_rows)),
        16u * 5u);
  }
}

TEST_F(FuseVk, RandomImagesEveryClassAndOpinion) {
  // Classes 0-3, points with either coarse bit, hole-filled and empty pixels, ranges and heights
  // from a few values so that equality with reach and top happens, and unusual class values.
  std::mt19937 rng(42);
  for (uint32_t trial = 0; trial < 12; ++trial) {
    const uint32_t width = 1 + rng() % 700, beams = 1 + rng() % 70;
    Image im(width, beams);
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
    EXPECT_EQ(ExpectSameFuse(context(), im.p, im.f, "random image " + std::to_string(trial)),
              size_t(width) * beams);
  }
}

class TotalPrinter : public ::testing::Environment {
 public:
  void TearDown() override {
    std::printf("[fuse] total: %llu values compared, %llu mismatches\n",
                static_cast<unsigned long long>(g_total.compared),
                static_cast<unsigned long long>(g_total.mismatches));
  }
};
::testing::Environment* const kTotal = ::testing::AddGlobalTestEnvironment(new TotalPrinter);

}  // namespace
}  // namespace lpir
