// Stage 8, grow, on Vulkan (shaders/grow.comp) against the CPU reference
// (reference_cpu/grow.cpp): pixel_grown, pixel_comp and pixel_label byte for byte. Inputs: random
// label images (as tests/grow_test.cpp makes them), the whole CPU pipeline (RunReference) on the
// simulated HDL-64E streets and on the real KITTI scans when ../shared/data is present; the sweeps
// the growing loop needed are printed, and a too small budget must be reported as non-convergence.
// The components (union-find on the GPU) must carry the reference's lowest-pixel labels.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "apps/sim/scene.h"
#include "host/io/kitti_bin.h"
#include "host/io/sensor_profile.h"
#include "host/stages/grow.h"
#include "reference_cpu/pipeline.h"
#include "reference_cpu/stages.h"
#include "tests/test_util.h"
#include "tests/vk_test_util.h"

namespace lpir {
namespace {

std::string ValueText(uint32_t u) {
  char text[48];
  std::snprintf(text, sizeof(text), "%u (0x%08x)", u, u);
  return text;
}

struct Counts {
  uint64_t compared = 0, mismatches = 0;
  uint32_t max_grow_sweeps = 0;
};
Counts g_total;

// Compares one output buffer; returns the mismatches.
size_t CompareBuffer(const char* name, const std::vector<uint32_t>& cpu,
                     const std::vector<uint32_t>& gpu, const Params& p, const std::string& what) {
  EXPECT_EQ(gpu.size(), cpu.size()) << what << ": " << name;
  if (gpu.size() != cpu.size()) return cpu.size();
  const size_t n = cpu.size();
  size_t first = n, count = 0;
  for (size_t i = 0; i < n; ++i)
    if (std::memcmp(&cpu[i], &gpu[i], 4) != 0) {
      if (first == n) first = i;
      ++count;
    }
  g_total.compared += n;
  g_total.mismatches += count;
  EXPECT_EQ(count, 0u) << "grow (" << what << "): buffer " << name << " differs at element "
                       << first << " (row " << (first < n ? first / p.width : 0) << ", column "
                       << (first < n ? first % p.width : 0) << "; " << count << " of " << n
                       << " differ): CPU " << (first < n ? ValueText(cpu[first]) : "") << ", GPU "
                       << (first < n ? ValueText(gpu[first]) : "");
  return count;
}

// Runs lpir::Grow and vk::RunGrow on `in`'s pixel_fused and feature maps; compares the outputs.
void ExpectSameGrow(const vk::Context& context, const Params& p, const Frame& in,
                    const std::string& what) {
  Frame cpu = in, gpu = in;
  Grow(p, cpu);
  const size_t pixels = size_t(p.width) * p.beams;
  gpu.pixel_grown.assign(pixels, 0xDEADBEEFu);
  gpu.pixel_comp.assign(pixels, 0xDEADBEEFu);
  gpu.pixel_label.assign(pixels, 0xDEADBEEFu);
  vk::GrowReport report;
  double gpu_ns = 0;
  const vk::Status status = vk::RunGrow(context, p, gpu, &report, &gpu_ns);
  EXPECT_TRUE(status.ok()) << what << ": " << status.message();
  if (!status.ok()) return;
  size_t bad = CompareBuffer("pixel_grown", cpu.pixel_grown, gpu.pixel_grown, p, what);
  bad += CompareBuffer("pixel_comp", cpu.pixel_comp, gpu.pixel_comp, p, what);
  bad += CompareBuffer("pixel_label", cpu.pixel_label, gpu.pixel_label, p, what);
  uint32_t hist[4] = {0, 0, 0, 0}, grown = 0;
  for (size_t i = 0; i < pixels; ++i) {
    if (in.pixel_fused[i] < 4) ++hist[in.pixel_fused[i]];
    grown += in.pixel_fused[i] == kPixUnknown && cpu.pixel_grown[i] == kPixGround;
  }
  g_total.max_grow_sweeps = std::max(g_total.max_grow_sweeps, report.grow_sweeps);
  std::printf(
      "[grow] %s: %ux%u pixels (fused non-ground %u, ground %u, unknown %u, empty %u; %u grown): "
      "%u grow sweeps (budget %u); %zu values compared, %zu differ, GPU %.3f ms\n",
      what.c_str(), p.beams, p.width, hist[0], hist[1], hist[2], hist[3], grown,
      report.grow_sweeps, p.grow_max_iters, 3 * pixels, bad, gpu_ns / 1e6);
}

// A random label image as in tests/grow_test.cpp (heights near a step's allowance, intensity
// jumps, rare seeds), here also with larger sizes and min_component > 0.
struct Image {
  Params p = DefaultParams();
  Frame f;
  Image(uint32_t width, uint32_t beams) {
    p.width = width;
    p.beams = beams;
    p.column_arc = float(2.0 * 3.14159265358979323846 / double(width));
    const size_t pixels = size_t(width) * beams;
    f.pixel_fused.assign(pixels, kPixEmpty);
    f.f_range.assign(pixels, 10.0f);
    f.f_height.assign(pixels, -1.7f);
    f.f_inten.assign(pixels, 0.3f);
  }
};

Image RandomImage(uint32_t seed, float grow_grade, uint32_t max_width, uint32_t max_beams) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<uint32_t> width_pick(1, max_width), beams_pick(1, max_beams);
  Image im(width_pick(rng), beams_pick(rng));
  im.p.min_component = rng() % 16;
  im.p.grow_grade = grow_grade;
  std::discrete_distribution<int> cls({3, 2, 12, 1, 0.2});  // ground, non-ground, unknown, empty, 7
  std::uniform_real_distribution<float> uni(0.0f, 1.0f);
  const uint32_t classes[5] = {kPixGround, kPixNonGround, kPixUnknown, kPixEmpty, 7u};
  const float di = im.p.grow_di;
  const float typical = im.p.grow_dz + grow_grade * (1.0f + 20.0f * im.p.column_arc);
  for (uint32_t v = 0; v < im.p.beams; ++v)
    for (uint32_t u = 0; u < im.p.width; ++u) {
      const uint32_t pix = v * im.p.width + u;
      im.f.pixel_fused[pix] = classes[cls(rng)];
      im.f.f_height[pix] = -1.7f + 2.0f * typical * uni(rng);
      im.f.f_inten[pix] = 0.2f + (uni(rng) < 0.15f ? 1.5f * di : 0.0f) + 0.1f * di * uni(rng);
      im.f.f_range[pix] = 30.0f - 1.5f * float(v) + 2.0f * uni(rng);
    }
  for (uint32_t& c : im.f.pixel_fused)
    if (c == kPixGround && uni(rng) < 0.7f) c = kPixUnknown;
  return im;
}

class GrowVk : public test::VkTest {};

TEST_F(GrowVk, RandomImagesSmall) {
  // 2 x 15 images (each run builds the stage's nine pipelines: under the sanitizers ~1 s each).
  for (float grade : {DefaultParams().grow_grade, 0.05f})
    for (uint32_t seed = 0; seed < 15; ++seed) {
      const Image im = RandomImage(seed, grade, 48, 16);
      ExpectSameGrow(context(), im.p, im.f,
                     "random image " + std::to_string(seed) + " grade " + std::to_string(grade));
    }
}

TEST_F(GrowVk, RandomImagesLarge) {
  // Sizes up to 700 x 70, most of them not multiples of 4 (init and finish take four pixels at a
  // time, the pixels left over one by one).
  for (uint32_t seed = 100; seed < 112; ++seed) {
    const Image im = RandomImage(seed, seed % 2 ? 0.05f : 0.0f, 700, 70);
    ExpectSameGrow(context(), im.p, im.f, "random image " + std::to_string(seed));
  }
}

TEST_F(GrowVk, LongSnakeGrowsToItsEnd) {
  // A one-pixel-wide serpentine of unknown pixels through a 64 x 512 image, one seed at its
  // start: 16,415 pixels in one chain, which one-pixel-per-sweep growing could not reach within
  // the budget; growth spreads on from every pixel it reaches, so a few sweeps do.
  Image im(512, 64);
  im.p.min_component = 10;
  for (uint32_t v = 0; v < 64; v += 2)
    for (uint32_t u = 0; u < 512; ++u) im.f.pixel_fused[v * 512 + u] = kPixUnknown;
  for (uint32_t v = 1; v < 64; v += 2) {
    const uint32_t u = (v / 2) % 2 ? 0 : 511;
    im.f.pixel_fused[v * 512 + u] = kPixUnknown;
  }
  im.f.pixel_fused[0] = kPixGround;
  ExpectSameGrow(context(), im.p, im.f, "serpentine");  // with the default budget
}

TEST_F(GrowVk, ABudgetTooSmallIsReported) {
  // One sweep grows the pixel next to the seed and leaves an unknown pixel that can never grow
  // (no ground neighbour): proving the fixed point takes a second sweep, so a budget of one sweep
  // must be reported as non-convergence, in any schedule.
  Image im(16, 4);
  im.f.pixel_fused[0] = kPixGround;
  im.f.pixel_fused[1] = kPixUnknown;
  im.f.pixel_fused[3 * 16 + 8] = kPixUnknown;
  im.p.grow_max_iters = 2;
  ExpectSameGrow(context(), im.p, im.f, "two pixels, budget 2");
  im.p.grow_max_iters = 1;
  Frame gpu = im.f;
  vk::GrowReport report;
  const vk::Status status = vk::RunGrow(context(), im.p, gpu, &report);
  EXPECT_FALSE(status.ok()) << "one sweep cannot prove the fixed point";
  EXPECT_EQ(report.grow_sweeps, 0u);
  EXPECT_FALSE(report.converged());
}

TEST_F(GrowVk, SimulatedScenesHdl64) {
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
    ExpectSameGrow(context(), p, f, std::string("simulated ") + sc.name);
    Params q = p;
    q.grow_grade = 0.05f;
    q.min_component = 64;
    ExpectSameGrow(context(), q, f, std::string("simulated ") + sc.name + ", grade 0.05, min 64");
  }
}

void RealScan(const vk::Context& context, const char* file) {
  const Cloud cloud = ReadKittiBin(test::DataFile(file));
  const SensorProfile s = LoadSensorProfile("hdl64e", test::SensorsDir());
  const Params p = ParamsForSensor(s);
  Frame f;
  RunReference(cloud, p, MakeTables(s, p), f);
  {
    Frame again = f;
    Grow(p, again);
    EXPECT_EQ(again.pixel_label, f.pixel_label) << file << ": RunReference's pixel_label";
  }
  ExpectSameGrow(context, p, f, file);
  Params q = p;
  q.grow_grade = 0.05f;
  q.min_component = 64;
  ExpectSameGrow(context, q, f, std::string(file) + ", grade 0.05, min 64");
}

TEST_F(GrowVk, Kitti07Frame964) {
  LPIR_REQUIRE_DATA("kitti/07/velodyne/000964.bin");
  RealScan(context(), "kitti/07/velodyne/000964.bin");
}

TEST_F(GrowVk, KittiUnknownFrame56) {
  LPIR_REQUIRE_DATA("kitti/unknown/velodyne/000056.bin");
  RealScan(context(), "kitti/unknown/velodyne/000056.bin");
}

class TotalPrinter : public ::testing::Environment {
 public:
  void TearDown() override {
    std::printf("[grow] total: %llu values compared, %llu mismatches; most grow sweeps %u\n",
                static_cast<unsigned long long>(g_total.compared),
                static_cast<unsigned long long>(g_total.mismatches), g_total.max_grow_sweeps);
  }
};
::testing::Environment* const kTotal = ::testing::AddGlobalTestEnvironment(new TotalPrinter);

}  // namespace
}  // namespace lpir
