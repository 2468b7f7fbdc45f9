// The whole frame on Vulkan (host/gpu/frame_pipeline.h: one command buffer, upload, prepare,
// project, grid_reduce, coarse_segment, feature_maps, classify_pixels, fuse, grow and back_project,
// download) against the CPU reference (RunReference): every buffer of every stage byte for byte
// (tests/frame_compare.h), on random clouds from 0 points to the pipeline's maximum, simulated
// scenes of several sensors (with and without ring fields), and every real scan in
// ../shared/data; then several frames in flight, slots reused, and the errors a frame can meet.
#include <gtest/gtest-spi.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "apps/sim/scene.h"
#include "host/gpu/frame_pipeline.h"
#include "host/io/cloud_file.h"
#include "host/io/sensor_profile.h"
#include "reference_cpu/pipeline.h"
#include "tests/frame_compare.h"
#include "tests/stage_test_util.h"
#include "tests/test_util.h"
#include "tests/vk_test_util.h"

namespace lpir {
namespace {

struct SensorSetup {
  SensorProfile sensor;
  Params params;
  Tables tables;
};
SensorSetup MakeSetup(const SensorProfile& s) {
  SensorSetup setup{s, ParamsForSensor(s), {}};
  setup.tables = MakeTables(s, setup.params);
  return setup;
}
SensorSetup MakeSetup(const std::string& name) {
  return MakeSetup(LoadSensorProfile(name, test::SensorsDir()));
}

vk::FramePipeline MakePipeline(const vk::Context& context, const SensorSetup& s,
                               uint32_t max_points, uint32_t slots) {
  vk::Result<vk::FramePipeline> made =
      vk::FramePipeline::Create(context, s.params, s.tables, max_points, slots);
  EXPECT_TRUE(made.ok()) << made.error().message;
  if (!made.ok()) throw std::runtime_error(made.error().message);
  return std::move(made).value();
}

// Runs `cloud` through slot 0 with every buffer read back and compares the frame with
// RunReference's. Returns the bytes compared.
uint64_t ExpectSameWholeFrame(vk::FramePipeline& pipeline, const SensorSetup& s, const Cloud& cloud,
                              const std::string& what) {
  Frame cpu, gpu;
  RunReference(cloud, s.params, s.tables, cpu);
  const vk::Status submitted = pipeline.Submit(0, cloud);
  EXPECT_TRUE(submitted.ok()) << what << ": " << submitted.message();
  if (!submitted.ok()) return 0;
  FrameTimes times;
  const vk::Status collected = pipeline.Collect(0, gpu, /*all_buffers=*/true, &times);
  EXPECT_TRUE(collected.ok()) << what << ": " << collected.message();
  if (!collected.ok()) return 0;
  const uint64_t bytes = test::ExpectSameFrame(s.params, cpu, gpu, &cloud, what);
  size_t ground = 0;
  for (uint8_t l : cpu.label) ground += l;
  std::printf(
      "[frame_pipeline] %s: %zu points (%zu ground), %llu bytes compared; GPU %.2f ms "
      "(upload %.2f, download %.2f)\n",
      what.c_str(), cloud.size(), ground, static_cast<unsigned long long>(bytes), times.total_ms,
      times.upload_ms, times.download_ms);
  return bytes;
}

// Street-like points with every kind of trouble mixed in: invalid (NaN, Inf, origin, 1e30),
// reflection noise, second returns sharing a pixel, points above and below the beams.
Cloud RandomCloud(size_t n, float sensor_height, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  Cloud cloud;
  for (size_t i = 0; i < n; ++i) {
    const float az = unit(rng) * 6.2831853f, r = 2.0f + 60.0f * unit(rng) * unit(rng);
    float x = r * std::cos(az), y = r * std::sin(az), z = -sensor_height + 0.05f * unit(rng);
    float in = unit(rng);
    switch (rng() % 16) {
      case 0:
      case 1:
      case 2:
        z = -sensor_height + 3.0f * unit(rng);  // obstacles
        break;
      case 3:
        z += 0.1f * r * unit(rng);  // slopes
        break;
      case 4:
        switch (rng() % 5) {
          case 0:
            x = y = z = 0.0f;
            break;
          case 1:
            x = nan;
            break;
          case 2:
            z = -inf;
            break;
          case 3:
            y = 1e30f;
            break;
          default:
            in = nan;
        }
        break;
      case 5:
        z = -sensor_height - 1.0f, in = 0.0f;  // reflection noise
        break;
      case 6:
        if (i > 0) {  // a second return beside the previous point
          x = cloud.x(i - 1) * (1.0f + 0.002f * unit(rng));
          y = cloud.y(i - 1) * (1.0f + 0.002f * unit(rng));
          z = cloud.z(i - 1) + 0.3f * (unit(rng) - 0.5f);
        }
        break;
      case 7:
        z = (unit(rng) - 0.5f) * 2.0f * r;  // outside the beams' fan
        break;
      default:
        break;
    }
    cloud.Push(x, y, z, in * 100.0f);
  }
  return cloud;
}

class FramePipelineVk : public test::VkTest {};

// The small 16-beam sensor: sizes from empty to exactly the maximum.
TEST_F(FramePipelineVk, RandomCloudsUpToTheMaximum) {
  const SensorSetup s = MakeSetup(test::SmallSensor());
  constexpr uint32_t kMax = 40000;
  vk::FramePipeline pipeline = MakePipeline(context(), s, kMax, 1);
  uint64_t bytes = 0;
  uint32_t seed = 1;
  for (size_t n : {size_t(0), size_t(1), size_t(2), size_t(3), size_t(64), size_t(1000),
                   size_t(4097), size_t(kMax)})
    bytes += ExpectSameWholeFrame(pipeline, s, RandomCloud(n, 1.7f, seed++),
                                  "random cloud of " + std::to_string(n) + " points");
  EXPECT_GT(bytes, uint64_t(kMax) * 4 * 12);
}

// One ring field, as an Ouster or Velodyne PCD gives it, with a few rings out of range.
TEST_F(FramePipelineVk, RandomCloudWithRings) {
  const SensorSetup s = MakeSetup(test::SmallSensor());
  vk::FramePipeline pipeline = MakePipeline(context(), s, 20000, 1);
  Cloud cloud = RandomCloud(20000, 1.7f, 77);
  std::mt19937 rng(5);
  for (size_t i = 0; i < cloud.size(); ++i) cloud.ring.push_back(int32_t(rng() % 18) - 1);
  EXPECT_GT(ExpectSameWholeFrame(pipeline, s, cloud, "random cloud with rings"), 0u);
  // The same pipeline then takes a cloud without rings (has_ring is per frame).
  cloud.ring.clear();
  EXPECT_GT(ExpectSameWholeFrame(pipeline, s, cloud, "the same cloud without rings"), 0u);
}

TEST_F(FramePipelineVk, RandomHdl64eFrame) {
  const SensorSetup s = MakeSetup("hdl64e");
  vk::FramePipeline pipeline = MakePipeline(context(), s, 130000, 1);
  EXPECT_GT(ExpectSameWholeFrame(pipeline, s, RandomCloud(130000, 1.73f, 3), "random hdl64e"), 0u);
}

void SimulatedScenes(const vk::Context& context, const std::string& sensor) {
  const SensorSetup s = MakeSetup(sensor);
  vk::FramePipeline pipeline = MakePipeline(context, s, 300000, 1);
  const struct {
    SceneKind kind;
    uint32_t seed;
    bool rings;
    const char* name;
  } scenes[] = {{kUrban, 1, false, "urban 1"},
                {kUrban, 2, true, "urban 2 with rings"},
                {kFlatWithObjects, 0, false, "flat with objects"}};
  for (const auto& sc : scenes) {
    SimOptions o;
    o.seed = sc.seed;
    o.kind = sc.kind;
    o.emit_rings = sc.rings;
    const SimScan scan = Simulate(s.sensor, o);
    EXPECT_GT(ExpectSameWholeFrame(pipeline, s, scan.cloud, sensor + " simulated " + sc.name), 0u);
  }
}

TEST_F(FramePipelineVk, SimulatedHdl64e) { SimulatedScenes(context(), "hdl64e"); }
TEST_F(FramePipelineVk, SimulatedVlp16) { SimulatedScenes(context(), "vlp16"); }
TEST_F(FramePipelineVk, SimulatedOs1_128) { SimulatedScenes(context(), "os1-128"); }

// Every real scan in ../shared/data with the profile of its sensor.
struct RealScan {
  const char* file;
  const char* sensor;
};
const RealScan kRealScans[] = {
    {"kitti/07/velodyne/000964.bin", "hdl64e"},
    {"kitti/unknown/velodyne/000056.bin", "hdl64e"},
    {"kitti/00/velodyne/000000.bin", "hdl64e"},
    {"kitti/00/velodyne/000001.bin", "hdl64e"},
    {"kitti/00/velodyne/000002.bin", "hdl64e"},
    {"kitti/00/velodyne/000003.bin", "hdl64e"},
    {"kitti/00/velodyne/000004.bin", "hdl64e"},
    {"kitti/00/velodyne/000005.bin", "hdl64e"},
    {"nuscenes/n015-2018-07-24-11-22-45+0800__LIDAR_TOP__1532402927647951.pcd.bin", "hdl32e"},
    {"rellis3d/os1/000104.bin", "os1-64"},
    {"rellis3d/os1/frame000104-1581624663_170.ply", "os1-64"},
    {"rellis3d/vlp32c/000104.bin", "vlp32c"},
    {"hdl32e/source.ply", "hdl32e"},
    {"hdl32e/target.ply", "hdl32e"},
};

void PrintTo(const RealScan& scan, std::ostream* os) { *os << scan.file << " as " << scan.sensor; }

class RealScanVk : public test::VkTest, public ::testing::WithParamInterface<RealScan> {};

TEST_P(RealScanVk, EveryBufferEqual) {
  const RealScan scan = GetParam();
  LPIR_REQUIRE_DATA(scan.file);
  const SensorSetup s = MakeSetup(scan.sensor);
  const Cloud cloud = ReadCloud(test::DataFile(scan.file));
  vk::FramePipeline pipeline = MakePipeline(context(), s, uint32_t(cloud.size()), 1);
  EXPECT_GT(ExpectSameWholeFrame(pipeline, s, cloud,
                                 std::string(scan.file) + " (" + scan.sensor +
                                     (cloud.ring.empty() ? "" : ", rings") + ")"),
            0u);
}

std::string ScanName(const ::testing::TestParamInfo<RealScan>& info) {
  std::string name = std::to_string(info.index) + "_";
  const std::string file = info.param.file;
  for (char c : file.substr(0, 24)) name += std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
  return name;
}
INSTANTIATE_TEST_SUITE_P(Data, RealScanVk, ::testing::ValuesIn(kRealScans), ScanName);

// A simulated street of seed `seed` (with ring fields when `rings`), or with `random` a small
// random cloud (RandomCloud, 500 + seed % 7 * 100 points).
Cloud StreetOrRandom(const SensorSetup& s, uint32_t seed, bool random, bool rings) {
  if (random) return RandomCloud(500 + seed % 7 * 100, 1.7f, seed);
  SimOptions o;
  o.seed = seed;
  o.emit_rings = rings;
  return Simulate(s.sensor, o).cloud;
}

// Three slots, six frames of different sizes submitted ahead of their collection, slots reused:
// every frame's labels equal the reference's, and every buffer of any frame in flight (each
// slot owns its frame buffers) does.
TEST_F(FramePipelineVk, FramesInFlight) {
  const SensorSetup s = MakeSetup("vlp16");
  vk::FramePipeline pipeline = MakePipeline(context(), s, 60000, 3);
  std::vector<Cloud> clouds;
  for (uint32_t k = 0; k < 6; ++k) clouds.push_back(StreetOrRandom(s, 10 + k, k == 3, k % 2 == 1));
  auto check = [&](uint32_t k, bool all) {
    Frame cpu, gpu;
    RunReference(clouds[k], s.params, s.tables, cpu);
    const vk::Status status = pipeline.Collect(k % 3, gpu, all);
    ASSERT_TRUE(status.ok()) << "frame " << k << ": " << status.message();
    EXPECT_EQ(gpu.n, cpu.n) << "frame " << k;
    EXPECT_EQ(gpu.label, cpu.label) << "frame " << k << ": labels";
    EXPECT_EQ(gpu.why, cpu.why) << "frame " << k << ": why";
    EXPECT_EQ(gpu.label_why, cpu.label_why) << "frame " << k << ": label_why";
    if (all) test::ExpectSameFrame(s.params, cpu, gpu, &clouds[k], "frame " + std::to_string(k));
  };
  for (uint32_t k = 0; k < 3; ++k) ASSERT_TRUE(pipeline.Submit(k, clouds[k]).ok());
  check(0, true);  // frames 1 and 2 came after it, in other slots' buffers
  ASSERT_TRUE(pipeline.Submit(0, clouds[3]).ok());
  check(1, false);
  ASSERT_TRUE(pipeline.Submit(1, clouds[4]).ok());
  check(2, false);
  ASSERT_TRUE(pipeline.Submit(2, clouds[5]).ok());
  check(3, false);
  check(4, true);
  check(5, true);
}

// Batches: frames staged in consecutive slots, recorded in one command buffer interleaved pass by
// pass, each collected from its own slot with every buffer equal to the reference's; a batch costs
// one frame's barriers and B frames' dispatches; its slots take no new frame until all of its
// frames are collected.
TEST_F(FramePipelineVk, BatchesEqualTheReference) {
  const SensorSetup s = MakeSetup("vlp16");
  vk::FramePipeline pipeline = MakePipeline(context(), s, 60000, 4);
  std::vector<Cloud> clouds;
  for (uint32_t k = 0; k < 4; ++k) clouds.push_back(StreetOrRandom(s, 30 + k, k == 1, k == 2));
  ASSERT_TRUE(pipeline.Submit(0, clouds[0]).ok());
  const vk::RecordCounts one = pipeline.last_counts();
  Frame f;
  ASSERT_TRUE(pipeline.Collect(0, f).ok());
  for (uint32_t k = 0; k < 3; ++k) ASSERT_TRUE(pipeline.Stage(k, clouds[k]).ok());
  EXPECT_FALSE(pipeline.Stage(0, clouds[3]).ok()) << "slot 0 holds a staged cloud";
  ASSERT_TRUE(pipeline.SubmitStaged(0, 3).ok());
  const vk::RecordCounts batch = pipeline.last_counts();
  EXPECT_EQ(batch.barriers, one.barriers);
  EXPECT_EQ(batch.dispatches, 3 * one.dispatches);
  ASSERT_TRUE(pipeline.Submit(3, clouds[3]).ok()) << "slot 3 is not in the batch";
  auto collect = [&](uint32_t k) {
    Frame cpu, gpu;
    RunReference(clouds[k], s.params, s.tables, cpu);
    ASSERT_TRUE(pipeline.Collect(k, gpu, /*all_buffers=*/true).ok()) << "frame " << k;
    test::ExpectSameFrame(s.params, cpu, gpu, &clouds[k], "frame " + std::to_string(k));
  };
  collect(0);
  EXPECT_FALSE(pipeline.Stage(0, clouds[0]).ok()) << "slot 0's batch has frames 1, 2 to collect";
  collect(2);
  EXPECT_TRUE(pipeline.Stage(2, clouds[2]).ok()) << "slot 2 is free once its frame is collected";
  collect(1);
  collect(3);
  EXPECT_TRUE(pipeline.Stage(0, clouds[0]).ok()) << "the batch is collected";
  EXPECT_FALSE(pipeline.SubmitStaged(0, 2).ok()) << "slot 1 holds no cloud";
  EXPECT_TRUE(pipeline.SubmitStaged(2, 1).ok());
  EXPECT_TRUE(pipeline.SubmitStaged(0, 1).ok());
  ASSERT_TRUE(pipeline.Collect(0, f).ok());
  ASSERT_TRUE(pipeline.Collect(2, f).ok());
}

TEST_F(FramePipelineVk, ErrorsLeaveThePipelineUsable) {
  const SensorSetup s = MakeSetup(test::SmallSensor());
  vk::FramePipeline pipeline = MakePipeline(context(), s, 1000, 1);
  EXPECT_EQ(pipeline.max_points(), 1000u);
  EXPECT_GT(pipeline.device_bytes(), 0u);

  // The cloud itself is the caller's to check (Segmenter::Submit; segmenter_vk_test).
  Frame f;
  vk::Status status = pipeline.Collect(0, f);
  ASSERT_FALSE(status.ok());
  EXPECT_NE(status.message().find("holds no submitted frame"), std::string::npos);
  status = pipeline.Submit(1, RandomCloud(10, 1.7f, 2));
  ASSERT_FALSE(status.ok());
  EXPECT_NE(status.message().find("slot 1 is not free"), std::string::npos) << status.message();

  ASSERT_TRUE(pipeline.Submit(0, RandomCloud(1000, 1.7f, 3)).ok());
  status = pipeline.Submit(0, RandomCloud(5, 1.7f, 3));
  ASSERT_FALSE(status.ok());
  EXPECT_NE(status.message().find("slot 0 is not free"), std::string::npos) << status.message();
  ASSERT_TRUE(pipeline.Collect(0, f).ok());
  EXPECT_EQ(f.label.size(), 1000u);
  EXPECT_GT(ExpectSameWholeFrame(pipeline, s, RandomCloud(1000, 1.7f, 4), "after the errors"), 0u);
}

// A pipeline destroyed with frames in flight waits for them (no validation message, no crash).
TEST_F(FramePipelineVk, DestroyedWithFramesInFlight) {
  const SensorSetup s = MakeSetup(test::SmallSensor());
  vk::FramePipeline pipeline = MakePipeline(context(), s, 5000, 2);
  ASSERT_TRUE(pipeline.Submit(0, RandomCloud(5000, 1.7f, 1)).ok());
  ASSERT_TRUE(pipeline.Submit(1, RandomCloud(4000, 1.7f, 2)).ok());
  vk::FramePipeline other = MakePipeline(context(), s, 100, 1);
  ASSERT_TRUE(other.Submit(0, RandomCloud(100, 1.7f, 3)).ok());
  other = std::move(pipeline);  // waits for other's frame, then takes the two in flight
  EXPECT_EQ(other.max_points(), 5000u);
  Frame f;
  ASSERT_TRUE(other.Collect(1, f).ok());
  EXPECT_EQ(f.n, 4000u);
}

// What a mismatch prints: stage, buffer, first differing element, both values in decimal and
// hex, and where it is (a pixel's u and v, a point's coordinates).
TEST(FrameCompare, MismatchReportNamesStageBufferElementAndPlace) {
  const SensorSetup s = MakeSetup(test::SmallSensor());
  const Cloud cloud = RandomCloud(3000, 1.7f, 9);
  Frame cpu;
  RunReference(cloud, s.params, s.tables, cpu);
  Frame gpu = cpu;
  const uint32_t pixel = 5 * s.params.width + 17;
  gpu.f_height[pixel] = 1.5f;
  gpu.f_height[pixel + 3] = 2.5f;
  EXPECT_NONFATAL_FAILURE(
      test::ExpectSameFrame(s.params, cpu, gpu, &cloud, "corrupted"),
      "stage feature_maps, buffer f_height differs first at element 1297 (2 of 4096 differ)");
  EXPECT_NONFATAL_FAILURE(test::ExpectSameFrame(s.params, cpu, gpu, &cloud, "corrupted"),
                          "GPU 1.5 (0x3fc00000); pixel (u 17, v 5)");
  gpu = cpu;
  gpu.zt[42] = -0.0f;
  EXPECT_NONFATAL_FAILURE(test::ExpectSameFrame(s.params, cpu, gpu, &cloud, "corrupted"),
                          "GPU -0 (0x80000000); point 42 (x ");
  gpu = cpu;
  gpu.why[7] ^= 1;
  EXPECT_NONFATAL_FAILURE(test::ExpectSameFrame(s.params, cpu, gpu, &cloud, "corrupted"),
                          "stage back_project, buffer why differs first at element 7");
  gpu = cpu;
  gpu.label_why[9] ^= 2;
  EXPECT_NONFATAL_FAILURE(test::ExpectSameFrame(s.params, cpu, gpu, &cloud, "corrupted"),
                          "stage back_project, buffer label_why differs first at element 9");
}

TEST_F(FramePipelineVk, CreateRejectsBadArguments) {
  const SensorSetup s = MakeSetup(test::SmallSensor());
  EXPECT_FALSE(vk::FramePipeline::Create(context(), s.params, s.tables, 0, 1).ok());
  EXPECT_FALSE(vk::FramePipeline::Create(context(), s.params, s.tables, 10, 0).ok());
  Tables short_tables = s.tables;
  short_tables.column_dir.pop_back();
  const auto made = vk::FramePipeline::Create(context(), s.params, short_tables, 10, 1);
  ASSERT_FALSE(made.ok());
  EXPECT_NE(made.error().message.find("tables do not match"), std::string::npos);
}

// Every device limit Create checks, each error naming the limit, the value needed and the
// device's: fake limits (each one just too small) for storage buffers, Params and the heap;
// lavapipe's own maxStorageBufferRange and maxComputeWorkGroupCount[0] with a max_points over
// them.
TEST_F(FramePipelineVk, CreateChecksTheDeviceLimits) {
  const SensorSetup s = MakeSetup(test::SmallSensor());
  const vk::DeviceLimits real = vk::DeviceLimits::Of(device());
  ASSERT_GT(real.max_storage_buffer_range, 0u);
  ASSERT_GT(real.device_local_heap, 0u);
  auto error = [&](uint32_t max_points, const vk::DeviceLimits* limits) {
    const auto made =
        vk::FramePipeline::Create(context(), s.params, s.tables, max_points, 1, limits);
    return made.ok() ? std::string("(no error)") : made.error().message;
  };
  EXPECT_EQ(error(1000, &real), "(no error)");

  vk::DeviceLimits fake = real;
  fake.max_storage_buffer_range = 16000 - 1;  // the points buffer: 16 bytes a point
  EXPECT_EQ(error(1000, &fake),
            "frame pipeline: max_points 1000 needs a 16.0 kB (16000 bytes) points buffer; this "
            "device's maxStorageBufferRange is 15999");
  fake.max_storage_buffer_range = 16000;  // then the 16 x 256 pixels' pixel_key, 4 each
  EXPECT_EQ(error(1000, &fake),
            "frame pipeline: an image of 16 x 256 pixels needs a 16.4 kB (16384 bytes) "
            "pixel_key buffer; this device's maxStorageBufferRange is 16000");

  fake = real;
  fake.max_uniform_buffer_range = sizeof(Params) - 1;
  EXPECT_EQ(error(1000, &fake),
            "frame pipeline: the parameters need a " + std::to_string(sizeof(Params)) +
                "-byte uniform buffer; this device's maxUniformBufferRange is " +
                std::to_string(sizeof(Params) - 1));

  fake = real;
  fake.device_local_heap = 1 << 20;
  const std::string heap = error(100000, &fake);
  EXPECT_NE(heap.find("frame pipeline: max_points 100000 and an image of 16 x 256 pixels need "),
            std::string::npos)
      << heap;
  EXPECT_NE(heap.find(" of device memory"), std::string::npos) << heap;
  EXPECT_NE(heap.find("; this device's device-local memory heap holds 1048576 bytes"),
            std::string::npos)
      << heap;
  fake.device_local_heap = 1ull << 40;
  EXPECT_EQ(error(1000, &fake), "(no error)");

  // The device's own limits (lavapipe: 128 MiB storage buffers, 65535 workgroups of 64).
  const uint64_t over_range = real.max_storage_buffer_range / 16 + 1;
  if (over_range <= UINT32_MAX / 16) {
    const std::string e = error(uint32_t(over_range), nullptr);
    EXPECT_NE(e.find("frame pipeline: max_points " + std::to_string(over_range) + " needs a "),
              std::string::npos)
        << e;
    EXPECT_NE(e.find(" points buffer; this device's maxStorageBufferRange is " +
                     std::to_string(real.max_storage_buffer_range)),
              std::string::npos)
        << e;
  }
  const uint64_t groups = device().limits().maxComputeWorkGroupCount[0];
  const uint64_t over_groups = groups * 64 + 1;  // prepare: a point an invocation, 64 a group
  if (16 * over_groups <= real.max_storage_buffer_range && over_groups <= UINT32_MAX / 16 &&
      100 * over_groups < real.device_local_heap) {
    const std::string e = error(uint32_t(over_groups), nullptr);
    EXPECT_NE(e.find("frame pipeline: max_points " + std::to_string(over_groups) + ": "),
              std::string::npos)
        << e;
    EXPECT_NE(e.find("; this device's maxComputeWorkGroupCount[0] is " + std::to_string(groups)),
              std::string::npos)
        << e;
  } else {
    std::printf("[frame_pipeline] maxComputeWorkGroupCount[0] %llu: not reachable here\n",
                static_cast<unsigned long long>(groups));
  }
}

}  // namespace
}  // namespace lpir
