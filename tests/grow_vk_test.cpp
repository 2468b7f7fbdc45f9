// Stage 8, grow, on Vulkan (shaders/grow.comp) against the CPU reference
// (reference_cpu/grow.cpp): pixel_grown, pixel_comp and pixel_label byte for byte. Inputs: over
// a thousand random label images and adversarial ones (serpentine corridors of unknown pixels,
// checkerboards, one huge unknown region, chains across the column wrap, images one row or one
// or two columns wide), the whole CPU pipeline (RunReference) on simulated HDL-64E streets and on
// the real KITTI scans when ../shared/data is present. The passes are fixed, so every image runs
// the same five dispatches; the components (union-find) carry the reference's lowest-pixel labels.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <cstring>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "apps/sim/scene.h"
#include "host/gpu/grow.h"
#include "host/io/kitti_bin.h"
#include "host/io/sensor_profile.h"
#include "host/vk/run_once.h"
#include "host/vk/transfer.h"
#include "reference_cpu/pipeline.h"
#include "reference_cpu/stages.h"
#include "tests/stage_harness.h"
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
  uint64_t lifted = 0, kept_vetoed = 0;  // vetoed pixels the reference lifted / left non-ground
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

// Compares lpir::Grow's outputs with `gpu`'s; prints a line when `verbose`.
void Compare(const Params& p, const Frame& in, const Frame& gpu, const std::string& what,
             double gpu_ns, bool verbose) {
  Frame cpu = in;
  Grow(p, cpu);
  const size_t pixels = size_t(p.width) * p.beams;
  for (size_t i = 0; i < pixels; ++i)
    if (in.pixel_fused[i] == kPixVetoed) {
      g_total.lifted += cpu.pixel_label[i] == kPixGround;
      g_total.kept_vetoed += cpu.pixel_label[i] == kPixNonGround;
    }
  size_t bad = CompareBuffer("pixel_grown", cpu.pixel_grown, gpu.pixel_grown, p, what);
  bad += CompareBuffer("pixel_comp", cpu.pixel_comp, gpu.pixel_comp, p, what);
  bad += CompareBuffer("pixel_label", cpu.pixel_label, gpu.pixel_label, p, what);
  if (!verbose && bad == 0) return;
  uint32_t hist[4] = {0, 0, 0, 0}, grown = 0;
  for (size_t i = 0; i < pixels; ++i) {
    if (in.pixel_fused[i] < 4) ++hist[in.pixel_fused[i]];
    grown += (in.pixel_fused[i] == kPixUnknown || in.pixel_fused[i] == kPixUnknownOff) &&
             cpu.pixel_grown[i] == kPixGround;
  }
  std::printf(
      "[grow] %s: %ux%u pixels (fused non-ground %u, ground %u, unknown %u, empty %u; %u grown): "
      "%zu values compared, %zu differ, GPU %.3f ms\n",
      what.c_str(), p.beams, p.width, hist[0], hist[1], hist[2], hist[3], grown, 3 * pixels, bad,
      gpu_ns / 1e6);
}

// Stage 8 on the GPU, as lpir::Grow(p, f): reads f.pixel_fused, f.f_height and f.f_range, fills
// f.pixel_grown, f.pixel_comp and f.pixel_label.
vk::Status GrowOnGpu(const vk::Device& device, const Params& p, Frame& f, double* gpu_ns) {
  const size_t pixels = size_t(p.width) * p.beams;
  test::StageHarness h(device, "grow");
  vk::GrowBuffers b;
  b.params = h.Uniform(p);
  b.pixel_fused = h.In("pixel_fused", f.pixel_fused, pixels);
  b.f_height = h.In("f_height", f.f_height, pixels);
  b.f_range = h.In("f_range", f.f_range, pixels);
  b.pixel_grown = h.Out(&f.pixel_grown, pixels);
  b.pixel_comp = h.Out(&f.pixel_comp, pixels);
  b.pixel_label = h.Out(&f.pixel_label, pixels);
  b.grow_reach = h.Scratch(vk::GrowStage::ReachBytes(pixels));
  b.grow_sizes = h.Scratch(vk::GrowStage::SizesBytes(pixels));
  return h.Run<vk::GrowStage>(
      b,
      [&](const vk::GrowStage& s, vk::CommandBuffer& cmd) {
        return s.Record(cmd, p.width, p.beams);
      },
      gpu_ns);
}

// Runs lpir::Grow and GrowOnGpu (buffers and pipelines made for this image) on `in`'s
// pixel_fused and feature maps; compares the outputs.
void ExpectSameGrow(const vk::Context& context, const Params& p, const Frame& in,
                    const std::string& what) {
  Frame gpu = in;
  const size_t pixels = size_t(p.width) * p.beams;
  gpu.pixel_grown.assign(pixels, 0xDEADBEEFu);
  gpu.pixel_comp.assign(pixels, 0xDEADBEEFu);
  gpu.pixel_label.assign(pixels, 0xDEADBEEFu);
  double gpu_ns = 0;
  const vk::Status status = GrowOnGpu(context.device(), p, gpu, &gpu_ns);
  EXPECT_TRUE(status.ok()) << what << ": " << status.message();
  if (status.ok()) Compare(p, in, gpu, what, gpu_ns, true);
}

// One GrowStage bound to buffers for up to kMaxPixels pixels, run on image after image: the many
// small images share its pipelines.
class GrowRunner {
 public:
  static constexpr uint32_t kMaxPixels = 1u << 16;

  explicit GrowRunner(const vk::Device& device) : device_(device) {}

  // Makes the buffers and the stage (a fatal failure when the device cannot).
  void Build() {
    const vk::Device& device = device_;
    const vk::MemoryKind kind = vk::MemoryKind::kDeviceLocal;
    auto make = [&](vk::Buffer& b, VkDeviceSize bytes) {
      auto made = vk::Buffer::Create(device, bytes, kind);
      ASSERT_TRUE(made.ok()) << made.status().message();
      b = std::move(made).value();
    };
    make(params_, sizeof(Params));
    for (vk::Buffer* b : {&fused_, &height_, &range_, &grown_, &comp_, &label_})
      make(*b, 4 * VkDeviceSize(kMaxPixels));
    make(reach_, vk::GrowStage::ReachBytes(kMaxPixels));
    make(sizes_, vk::GrowStage::SizesBytes(kMaxPixels));
    auto transfer = vk::Transfer::Create(device);
    ASSERT_TRUE(transfer.ok()) << transfer.status().message();
    transfer_.emplace(std::move(transfer).value());
    const vk::GrowBuffers b{&params_, &fused_, &height_, &range_, &grown_,
                            &comp_,   &label_, &reach_,  &sizes_};
    auto stage = vk::GrowStage::Create(device, b);
    ASSERT_TRUE(stage.ok()) << stage.status().message();
    stage_.emplace(std::move(stage).value());
  }

  // Runs the stage on `in` (at most kMaxPixels pixels) and compares with the reference.
  void ExpectSame(const Params& p, const Frame& in, const std::string& what, bool verbose = false) {
    ASSERT_TRUE(stage_ && transfer_);
    const uint32_t pixels = p.width * p.beams;
    ASSERT_LE(pixels, kMaxPixels) << what;
    const VkDeviceSize bytes = 4 * VkDeviceSize(pixels);
    // Yesterday's values stay in the buffers past this image and in its outputs until written:
    // the stage must overwrite every output word it owns.
    Frame gpu = in;
    ASSERT_TRUE(transfer_->Upload(params_, &p, sizeof(Params)).ok());
    if (pixels) {
      ASSERT_TRUE(transfer_->Upload(fused_, in.pixel_fused.data(), bytes).ok());
      ASSERT_TRUE(transfer_->Upload(height_, in.f_height.data(), bytes).ok());
      ASSERT_TRUE(transfer_->Upload(range_, in.f_range.data(), bytes).ok());
    }
    double gpu_ns = 0;
    const vk::Status run = vk::RunOnce(
        device_, [&](vk::CommandBuffer& cmd) { return stage_->Record(cmd, p.width, p.beams); },
        verbose ? &gpu_ns : nullptr);
    ASSERT_TRUE(run.ok()) << what << ": " << run.message();
    gpu.pixel_grown.resize(pixels);
    gpu.pixel_comp.resize(pixels);
    gpu.pixel_label.resize(pixels);
    if (pixels) {
      ASSERT_TRUE(transfer_->Download(grown_, gpu.pixel_grown.data(), bytes).ok());
      ASSERT_TRUE(transfer_->Download(comp_, gpu.pixel_comp.data(), bytes).ok());
      ASSERT_TRUE(transfer_->Download(label_, gpu.pixel_label.data(), bytes).ok());
    }
    Compare(p, in, gpu, what, gpu_ns, verbose);
    ++images_;
  }
  uint32_t images() const { return images_; }

 private:
  const vk::Device& device_;
  vk::Buffer params_, fused_, height_, range_, grown_, comp_, label_, reach_, sizes_;
  std::optional<vk::Transfer> transfer_;
  std::optional<vk::GrowStage> stage_;
  uint32_t images_ = 0;
};

// A random label image as in tests/grow_test.cpp (heights near a step's allowance, rare seeds),
// here also with larger sizes and min_component > 0.
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
  }
};

// The rule that keeps a small component of seeds, drawn: off (share above 1), at its default, or
// at shares whose product with a size lands on a whole number of seeds (0.5, 1) or next to one
// (0.8, 0.75).
void SeedShare(std::mt19937& rng, Params& p) {
  const float shares[] = {2.0f, 0.8f, 0.5f, 1.0f, 0.75f};
  p.comp_seed_share = shares[rng() % 5];
  p.comp_seed_min = rng() % 8;
}

Image RandomImage(uint32_t seed, float grow_grade, uint32_t max_width, uint32_t max_beams) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<uint32_t> width_pick(1, max_width), beams_pick(1, max_beams);
  Image im(width_pick(rng), beams_pick(rng));
  im.p.min_component = rng() % 16;
  im.p.grow_grade = grow_grade;
  SeedShare(rng, im.p);
  // ground, non-ground, unknown, empty, vetoed, 7, unknown off the coarse ground
  std::discrete_distribution<int> cls({3, 2, 8, 1, 2, 0.2, 4});
  std::uniform_real_distribution<float> uni(0.0f, 1.0f);
  const uint32_t classes[7] = {kPixGround, kPixNonGround, kPixUnknown, kPixEmpty, kPixVetoed,
                               7u,         kPixUnknownOff};
  const float typical = im.p.grow_dz + grow_grade * (1.0f + 20.0f * im.p.column_arc);
  for (uint32_t v = 0; v < im.p.beams; ++v)
    for (uint32_t u = 0; u < im.p.width; ++u) {
      const uint32_t pix = v * im.p.width + u;
      im.f.pixel_fused[pix] = classes[cls(rng)];
      im.f.f_height[pix] = -1.7f + 2.0f * typical * uni(rng);
      im.f.f_range[pix] = 30.0f - 1.5f * float(v) + 2.0f * uni(rng);
    }
  for (uint32_t& c : im.f.pixel_fused)
    if (c == kPixGround && uni(rng) < 0.7f) c = kPixUnknown;
  return im;
}

class GrowVk : public test::VkTest {};

// A random image with its own class mix: mostly unknown (long growing chains), mostly ground, or
// mostly non-ground (small scattered components).
Image MixedImage(std::mt19937& rng, uint32_t max_width, uint32_t max_beams) {
  std::uniform_int_distribution<uint32_t> width_pick(1, max_width), beams_pick(1, max_beams);
  Image im(width_pick(rng), beams_pick(rng));
  std::uniform_real_distribution<float> uni(0.0f, 1.0f);
  im.p.min_component = rng() % 40;
  im.p.grow_grade = uni(rng) < 0.5f ? 0.0f : 0.05f;
  SeedShare(rng, im.p);
  const double weights[7] = {1.0 + 10 * uni(rng), 1.0 + 10 * uni(rng), 1.0 + 20 * uni(rng),
                             5 * uni(rng),        5 * uni(rng),        0.3 * uni(rng),
                             10 * uni(rng)};
  std::discrete_distribution<int> cls(weights, weights + 7);
  const uint32_t classes[7] = {kPixGround, kPixNonGround, kPixUnknown, kPixEmpty, kPixVetoed,
                               7u,         kPixUnknownOff};
  const float allowed = im.p.grow_dz + im.p.grow_grade * (1.0f + 20.0f * im.p.column_arc);
  const float step_share = 0.5f + 1.5f * uni(rng);  // heights spread over this many allowances
  for (uint32_t pix = 0; pix < im.p.width * im.p.beams; ++pix) {
    const uint32_t v = pix / im.p.width;
    im.f.pixel_fused[pix] = classes[cls(rng)];
    im.f.f_height[pix] = -1.7f + step_share * allowed * uni(rng);
    im.f.f_range[pix] = 30.0f - 0.4f * float(v) + 2.0f * uni(rng);
  }
  return im;
}

TEST_F(GrowVk, ThousandRandomImages) {
  GrowRunner runner(context().device());
  runner.Build();
  std::mt19937 rng(20261202);
  const Counts before = g_total;
  for (uint32_t k = 0; k < 1000; ++k) {
    const Image im = k < 30 ? RandomImage(k, k % 2 ? 0.05f : 0.0f, 48, 16)
                            : MixedImage(rng, k % 10 == 0 ? 700 : 96, k % 10 == 0 ? 70 : 24);
    runner.ExpectSame(im.p, im.f, "random image " + std::to_string(k));
    if (HasFailure()) break;
  }
  EXPECT_EQ(runner.images(), 1000u);
  EXPECT_GT(g_total.lifted, before.lifted) << "no image exercised the veto's lift";
  EXPECT_GT(g_total.kept_vetoed, before.kept_vetoed) << "no image kept a vetoed pixel non-ground";
}

// The adversarial images: each one run with its seed at the first and at the last pixel of its
// unknown region (a component's lowest pixel is then its seed or far from it).
struct Adversary {
  std::string name;
  Image im;
};

Image Blank(uint32_t width, uint32_t beams, uint32_t fill) {
  Image im(width, beams);
  for (uint32_t& c : im.f.pixel_fused) c = fill;
  return im;
}

// A serpentine corridor of unknown pixels, `wide` pixels across, through non-ground pixels: rows
// of corridor joined at alternate ends. `vertical` turns it by 90 degrees.
Image Serpentine(uint32_t width, uint32_t beams, uint32_t wide, bool vertical) {
  Image im = Blank(width, beams, kPixNonGround);
  const uint32_t period = 2 * wide;
  const uint32_t lanes = vertical ? width : beams, length = vertical ? beams : width;
  for (uint32_t a = 0; a < lanes; ++a)
    for (uint32_t b = 0; b < length; ++b) {
      const uint32_t lane = a / period, in = a % period;
      const bool corridor = in < wide || (in >= wide && (lane % 2 ? b < wide : b + wide >= length));
      if (!corridor) continue;
      const uint32_t v = vertical ? b : a, u = vertical ? a : b;
      im.f.pixel_fused[v * width + u] = kPixUnknown;
    }
  return im;
}

std::vector<Adversary> Adversaries() {
  std::vector<Adversary> out;
  out.push_back({"serpentine 1 wide", Serpentine(512, 64, 1, false)});
  out.push_back({"serpentine 2 wide", Serpentine(500, 61, 2, false)});
  out.push_back({"serpentine vertical", Serpentine(257, 128, 1, true)});
  out.push_back({"huge unknown region", Blank(1024, 64, kPixUnknown)});
  {
    Image im = Blank(1000, 64, kPixUnknown);  // no seed at all: nothing grows
    out.push_back({"huge unknown region, no seed", im});
  }
  for (uint32_t fill : {kPixGround, kPixNonGround}) {  // checkerboards: diagonal-only contact
    Image im = Blank(333, 40, kPixUnknown);
    for (uint32_t pix = 0; pix < im.f.pixel_fused.size(); ++pix)
      if (((pix / 333) + (pix % 333)) % 2) im.f.pixel_fused[pix] = fill;
    out.push_back({fill == kPixGround ? "checkerboard ground" : "checkerboard non-ground", im});
  }
  {
    Image im = Blank(64, 32, kPixNonGround);  // a spiral of unknown pixels
    uint32_t top = 0, left = 0, bottom = 31, right = 63;
    while (top <= bottom && left <= right) {
      for (uint32_t u = left; u <= right; ++u) im.f.pixel_fused[top * 64 + u] = kPixUnknown;
      for (uint32_t v = top; v <= bottom; ++v) im.f.pixel_fused[v * 64 + right] = kPixUnknown;
      if (bottom < top + 2 || right < left + 2) break;
      top += 2, left += 2, bottom -= 2, right -= 2;
      if (left >= 2) im.f.pixel_fused[(top - 1) * 64 + left - 2] = kPixUnknown;
    }
    out.push_back({"spiral", im});
  }
  {
    Image im = Blank(300, 8, kPixNonGround);  // a chain that crosses the column wrap each row
    for (uint32_t v = 0; v < 8; ++v) {
      im.f.pixel_fused[v * 300 + 299] = kPixUnknown;
      im.f.pixel_fused[v * 300 + 0] = kPixUnknown;
      if (v + 1 < 8) im.f.pixel_fused[(v + 1) * 300 + 1] = kPixUnknown;  // diagonal step down
    }
    out.push_back({"chain across the wrap", im});
  }
  out.push_back({"one row", Blank(2048, 1, kPixUnknown)});
  out.push_back({"one column", Blank(1, 1000, kPixUnknown)});
  out.push_back({"two columns", Blank(2, 700, kPixUnknown)});
  {
    Image im = Blank(2048, 32, kPixUnknown);  // a huge region cut by walls no step may cross
    for (uint32_t pix = 0; pix < im.f.pixel_fused.size(); ++pix)
      if (pix % 2048 % 97 == 0) im.f.f_height[pix] = 5.0f;
    out.push_back({"huge region behind walls", im});
  }
  {
    // Columns off the coarse ground climbed only by the bank's step: each row up lies 0.5 m
    // farther and 0.15 m higher; neighbouring columns 1 m apart in height, so no other step
    // joins them (a chain of 200 union-find links up one column).
    Image im = Blank(64, 200, kPixUnknownOff);
    for (uint32_t v = 0; v < 200; ++v)
      for (uint32_t u = 0; u < 64; ++u) {
        im.f.f_range[v * 64 + u] = 5.0f + 0.5f * float(199 - v);
        im.f.f_height[v * 64 + u] = -1.7f + 0.15f * float(199 - v) + float(u % 2);
      }
    out.push_back({"banks climbed up their columns", im});
  }
  return out;
}

TEST_F(GrowVk, AdversarialImages) {
  GrowRunner runner(context().device());
  runner.Build();
  for (Adversary& a : Adversaries()) {
    Image& im = a.im;
    im.p.min_component = 5;
    std::vector<uint32_t> unknown;
    for (uint32_t pix = 0; pix < im.f.pixel_fused.size(); ++pix)
      if (im.f.pixel_fused[pix] == kPixUnknown || im.f.pixel_fused[pix] == kPixUnknownOff)
        unknown.push_back(pix);
    ASSERT_FALSE(unknown.empty()) << a.name;
    const bool seeded = a.name.find("no seed") == std::string::npos;
    for (int end = 0; end < (seeded ? 2 : 1); ++end) {
      Frame f = im.f;
      if (seeded) f.pixel_fused[end ? unknown.back() : unknown.front()] = kPixGround;
      runner.ExpectSame(im.p, f, a.name + (end ? ", seed last" : ", seed first"), true);
      Frame cpu = f;
      Grow(im.p, cpu);
      size_t grown = 0;
      for (uint32_t pix : unknown) grown += cpu.pixel_grown[pix] == kPixGround;
      if (!seeded) {
        EXPECT_EQ(grown, 0u) << a.name << ": nothing grows without a seed";
      } else if (a.name.rfind("serpentine", 0) == 0) {
        EXPECT_EQ(grown, unknown.size()) << a.name << ": the whole corridor grows";
      } else if (a.name.rfind("banks", 0) == 0) {
        EXPECT_EQ(grown, 200u) << a.name << ": the seed's column, and only it, grows";
      }
    }
  }
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
    std::printf(
        "[grow] total: %llu values compared, %llu mismatches; vetoed pixels %llu lifted, "
        "%llu kept\n",
        static_cast<unsigned long long>(g_total.compared),
        static_cast<unsigned long long>(g_total.mismatches),
        static_cast<unsigned long long>(g_total.lifted),
        static_cast<unsigned long long>(g_total.kept_vetoed));
  }
};
::testing::Environment* const kTotal = ::testing::AddGlobalTestEnvironment(new TotalPrinter);

}  // namespace
}  // namespace lpir
