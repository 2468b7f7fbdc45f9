// The counted cost of a frame (FramePipeline::last_counts, counted as CommandBuffer records): in
// each shape (LPIR_VK_SHAPE=gpu and cpu, read when the pipeline is made), frames of different
// point counts record the same numbers of dispatches, indirect dispatches and barriers
// (docs/spec.md, Performance shape: a dispatch count that does not depend on the data), every count
// positive; the bytes moved grow with the points (the cloud up, at least a byte of label per point
// down); each frame's labels equal the reference's.
#include <gtest/gtest.h>

#include <cstdlib>
#include <string>
#include <vector>

#include "apps/sim/scene.h"
#include "host/gpu/frame_pipeline.h"
#include "host/io/sensor_profile.h"
#include "reference_cpu/pipeline.h"
#include "tests/test_util.h"
#include "tests/vk_test_util.h"

namespace lpir {
namespace {

// The first `n` points of `cloud`.
Cloud Prefix(const Cloud& cloud, size_t n) {
  Cloud part;
  part.xyzi.assign(cloud.xyzi.begin(), cloud.xyzi.begin() + 4 * n);
  return part;
}

// Sets LPIR_VK_SHAPE for the scope, then puts it back as it was.
class ShapeScope {
 public:
  explicit ShapeScope(const char* shape) {
    const char* before = std::getenv("LPIR_VK_SHAPE");
    had_ = before != nullptr;
    if (had_) saved_ = before;
    ::setenv("LPIR_VK_SHAPE", shape, 1);
  }
  ~ShapeScope() {
    if (had_)
      ::setenv("LPIR_VK_SHAPE", saved_.c_str(), 1);
    else
      ::unsetenv("LPIR_VK_SHAPE");
  }

 private:
  bool had_ = false;
  std::string saved_;
};

class FramePipelineCountsVk : public test::VkTest,
                              public ::testing::WithParamInterface<const char*> {};

TEST_P(FramePipelineCountsVk, FixedDispatchesAndBarriersBytesGrowWithPoints) {
  const SensorProfile sensor = LoadSensorProfile("vlp16", test::SensorsDir());
  const Params params = ParamsForSensor(sensor);
  const Tables tables = MakeTables(sensor, params);
  SimOptions o;
  o.seed = 4;
  const Cloud street = Simulate(sensor, o).cloud;
  ASSERT_GT(street.size(), 5000u);
  const std::vector<size_t> sizes = {street.size(), 1000, street.size() / 3};

  vk::Result<vk::FramePipeline> made = [&] {
    ShapeScope shape(GetParam());
    return vk::FramePipeline::Create(context(), params, tables, uint32_t(street.size()), 1);
  }();
  ASSERT_TRUE(made.ok()) << made.error().message;
  vk::FramePipeline pipeline = std::move(made).value();

  std::vector<vk::RecordCounts> counts;
  for (size_t n : sizes) {
    const Cloud cloud = Prefix(street, n);
    ASSERT_TRUE(pipeline.Submit(0, cloud).ok());
    counts.push_back(pipeline.last_counts());
    Frame gpu, cpu;
    ASSERT_TRUE(pipeline.Collect(0, gpu).ok());
    RunReference(cloud, params, tables, cpu);
    EXPECT_EQ(gpu.label, cpu.label) << n << " points";
    const vk::RecordCounts& c = counts.back();
    std::printf(
        "[counts] shape %s, %zu points: %u dispatches (%u indirect), %u barriers, %llu "
        "workgroups of direct dispatches, %llu bytes up, %llu bytes down\n",
        GetParam(), n, c.dispatches, c.indirect_dispatches, c.barriers,
        static_cast<unsigned long long>(c.workgroups),
        static_cast<unsigned long long>(c.upload_bytes),
        static_cast<unsigned long long>(c.download_bytes));
    EXPECT_GT(c.dispatches, c.indirect_dispatches) << n;
    EXPECT_GT(c.barriers, 0u) << n;
    EXPECT_GT(c.workgroups, 0u) << n;
    EXPECT_GE(c.upload_bytes, 16 * uint64_t(n)) << n;  // the points, 16 bytes each
    EXPECT_GE(c.download_bytes, uint64_t(n)) << n;     // a label per point
  }
  for (size_t k = 1; k < counts.size(); ++k) {
    EXPECT_EQ(counts[k].dispatches, counts[0].dispatches) << sizes[k] << " points";
    EXPECT_EQ(counts[k].indirect_dispatches, counts[0].indirect_dispatches) << sizes[k];
    EXPECT_EQ(counts[k].barriers, counts[0].barriers) << sizes[k] << " points";
  }
  // The largest frame moves the most bytes and launches no fewer workgroups; Begin reset the
  // counts between frames (a sum would grow from frame to frame).
  EXPECT_GT(counts[0].upload_bytes, counts[2].upload_bytes);
  EXPECT_GT(counts[2].upload_bytes, counts[1].upload_bytes);
  EXPECT_GT(counts[0].download_bytes, counts[1].download_bytes);
  EXPECT_GE(counts[0].workgroups, counts[2].workgroups);
  EXPECT_GE(counts[2].workgroups, counts[1].workgroups);
}

INSTANTIATE_TEST_SUITE_P(Shapes, FramePipelineCountsVk, ::testing::Values("gpu", "cpu"),
                         [](const ::testing::TestParamInfo<const char*>& info) {
                           return std::string(info.param);
                         });

}  // namespace
}  // namespace lpir
