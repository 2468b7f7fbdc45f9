// The per-device shape (host/vk/shape.h): the default follows the device type, LPIR_VK_SHAPE
// forces it for every stage created after it is set, an invalid value is an error that names the
// variable and the value, and the shape sets the workgroups that the chunked passes record (so a
// shape that is reported but not applied fails here; that both shapes give the reference's bytes
// is the stage equality tests' job, which ctest runs once per shape).
// Registered once (its name starts with vk_): it sets the variable itself.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "host/gpu/coarse_segment.h"
#include "host/gpu/feature_maps.h"
#include "host/gpu/grid_reduce.h"
#include "host/gpu/project.h"
#include "host/vk/buffer.h"
#include "host/vk/command_buffer.h"
#include "host/vk/shape.h"
#include "reference_cpu/params.h"
#include "tests/vk_test_util.h"

namespace lpir {
namespace {

// Sets LPIR_VK_SHAPE for the test's scope (nullptr: unset) and puts the caller's value back.
class ScopedShapeEnv {
 public:
  explicit ScopedShapeEnv(const char* value) {
    if (const char* old = std::getenv(vk::kShapeEnv)) saved_ = old;
    Set(value);
  }
  ~ScopedShapeEnv() { Set(saved_ ? saved_->c_str() : nullptr); }
  void Set(const char* value) {
    if (value)
      setenv(vk::kShapeEnv, value, 1);
    else
      unsetenv(vk::kShapeEnv);
  }

 private:
  std::optional<std::string> saved_;
};

// Workgroups of `invocations` at the stages' local size.
uint64_t Groups(uint64_t invocations, uint64_t local) { return (invocations + local - 1) / local; }

// What one stage recorded.
struct Recorded {
  vk::Shape shape = vk::Shape::kGpu;
  uint32_t dispatches = 0;
  uint64_t workgroups = 0;
};

class ShapeTest : public test::VkTest {
 protected:
  // Points every binding of a stage's buffer struct (nothing but `const Buffer*` members) at a
  // buffer of its own (the stages' fills and dispatches then touch distinct buffers, as in a
  // frame), big enough for any fixed-size block the shaders declare (recording reads none).
  template <class Buffers>
  void BindAll(Buffers& buffers) {
    static_assert(sizeof(Buffers) % sizeof(const vk::Buffer*) == 0);
    const vk::Buffer** slots = reinterpret_cast<const vk::Buffer**>(&buffers);
    for (size_t k = 0; k < sizeof(Buffers) / sizeof(const vk::Buffer*); ++k) {
      vk::Result<vk::Buffer> made =
          vk::Buffer::Create(device(), 1 << 16, vk::MemoryKind::kDeviceLocal);
      ASSERT_TRUE(made.ok()) << made.message();
      buffers_.push_back(std::make_unique<vk::Buffer>(std::move(made).value()));
      slots[k] = buffers_.back().get();
    }
  }

  // Creates `Stage` over BindAll's buffers under the current
  // LPIR_VK_SHAPE and records it into a fresh command buffer with `record`.
  template <class Stage, class Buffers, class RecordFn>
  std::optional<Recorded> Record(RecordFn record) {
    Buffers buffers;
    BindAll(buffers);
    vk::Result<Stage> stage = Stage::Create(device(), buffers);
    EXPECT_TRUE(stage.ok()) << stage.message();
    vk::Result<vk::CommandBuffer> cmd = vk::CommandBuffer::Create(device());
    EXPECT_TRUE(cmd.ok()) << cmd.message();
    if (!stage.ok() || !cmd.ok()) return std::nullopt;
    EXPECT_TRUE(cmd->Begin().ok());
    const vk::Status recorded = record(stage.value(), cmd.value());
    EXPECT_TRUE(recorded.ok()) << recorded.message();
    EXPECT_TRUE(cmd->End().ok());
    return Recorded{stage->shape(), cmd->counts().dispatches, cmd->counts().workgroups};
  }

 private:
  std::vector<std::unique_ptr<vk::Buffer>> buffers_;
};

TEST_F(ShapeTest, DefaultFollowsTheDeviceType) {
  ScopedShapeEnv env(nullptr);
  vk::Result<vk::Shape> shape = vk::ShapeFor(device());
  ASSERT_TRUE(shape.ok()) << shape.message();
  const bool cpu = device().properties().deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU;
  EXPECT_EQ(shape.value(), cpu ? vk::Shape::kCpu : vk::Shape::kGpu) << device().name();
  env.Set("");  // empty: as unset
  ASSERT_TRUE(vk::ShapeFor(device()).ok());
  EXPECT_EQ(vk::ShapeFor(device()).value(), shape.value());
}

TEST_F(ShapeTest, EnvironmentForcesItAtEveryCall) {
  ScopedShapeEnv env("gpu");
  ASSERT_TRUE(vk::ShapeFor(device()).ok());
  EXPECT_EQ(vk::ShapeFor(device()).value(), vk::Shape::kGpu);
  EXPECT_STREQ(vk::ShapeName(vk::Shape::kGpu), "gpu");
  env.Set("cpu");
  ASSERT_TRUE(vk::ShapeFor(device()).ok());
  EXPECT_EQ(vk::ShapeFor(device()).value(), vk::Shape::kCpu);
  EXPECT_STREQ(vk::ShapeName(vk::Shape::kCpu), "cpu");
}

TEST_F(ShapeTest, InvalidValueIsAnErrorNamingVariableAndValue) {
  ScopedShapeEnv env("fastest");
  vk::Result<vk::Shape> shape = vk::ShapeFor(device());
  ASSERT_FALSE(shape.ok());
  EXPECT_NE(shape.message().find("LPIR_VK_SHAPE"), std::string::npos) << shape.message();
  EXPECT_NE(shape.message().find("fastest"), std::string::npos) << shape.message();
  // A stage created under it fails with the same message.
  vk::GridReduceBuffers buffers;
  BindAll(buffers);
  vk::Result<vk::GridReduceStage> stage = vk::GridReduceStage::Create(device(), buffers);
  ASSERT_FALSE(stage.ok());
  EXPECT_EQ(stage.message(), shape.message());
}

// A KITTI frame (124k points, the 64 x 2048 image, the default 2880 cells): every chunked pass
// takes one point or pixel per invocation in the GPU shape and the stage's kCpuItems in the CPU
// shape; the counts are printed for docs/decisions/shapes.md.
TEST_F(ShapeTest, WorkgroupsFollowTheShape) {
  const Params p = DefaultParams();
  const uint32_t n = 124000, cells = CellCount(p), width = p.width, beams = p.beams;
  ASSERT_EQ(width % 4, 0u);                             // feature_maps measures quads
  const uint64_t local = vk::ProjectStage::kLocalSize;  // every stage's (Vulkan allows 128)
  static_assert(vk::GridReduceStage::kLocalSize == vk::ProjectStage::kLocalSize &&
                vk::CoarseSegmentStage::kLocalSize == vk::ProjectStage::kLocalSize &&
                vk::FeatureMapsStage::kLocalSize == vk::ProjectStage::kLocalSize);
  for (const vk::Shape shape : {vk::Shape::kGpu, vk::Shape::kCpu}) {
    SCOPED_TRACE(vk::ShapeName(shape));
    ScopedShapeEnv env(vk::ShapeName(shape));
    const bool cpu = shape == vk::Shape::kCpu;
    auto items = [&](uint64_t cpu_items) { return cpu ? cpu_items : 1; };

    const std::optional<Recorded> project = Record<vk::ProjectStage, vk::ProjectBuffers>(
        [&](const vk::ProjectStage& s, vk::CommandBuffer& cmd) { return s.Record(cmd, n); });
    const std::optional<Recorded> grid = Record<vk::GridReduceStage, vk::GridReduceBuffers>(
        [&](const vk::GridReduceStage& s, vk::CommandBuffer& cmd) {
          return s.Record(cmd, n, cells);
        });
    const std::optional<Recorded> coarse = Record<vk::CoarseSegmentStage, vk::CoarseSegmentBuffers>(
        [&](const vk::CoarseSegmentStage& s, vk::CommandBuffer& cmd) {
          return s.Record(cmd, n, cells);
        });
    const std::optional<Recorded> features = Record<vk::FeatureMapsStage, vk::FeatureMapsBuffers>(
        [&](const vk::FeatureMapsStage& s, vk::CommandBuffer& cmd) {
          return s.Record(cmd, width, beams);
        });
    ASSERT_TRUE(project && grid && coarse && features);
    for (const Recorded* r : {&*project, &*grid, &*coarse, &*features}) EXPECT_EQ(r->shape, shape);

    // project: pass 0 over chunks, pass 1 indirect (not counted), pass 2 one per point.
    const uint64_t project_0 = Groups(
        (n + items(vk::ProjectStage::kCpuItems) - 1) / items(vk::ProjectStage::kCpuItems), local);
    EXPECT_EQ(project->dispatches, 3u);
    EXPECT_EQ(project->workgroups, project_0 + Groups(n, local));
    // grid_reduce: the cell clear, then the points.
    const uint64_t grid_1 = Groups(
        (n + items(vk::GridReduceStage::kCpuItems) - 1) / items(vk::GridReduceStage::kCpuItems),
        local);
    EXPECT_EQ(grid->dispatches, 2u);
    EXPECT_EQ(grid->workgroups, Groups(cells, local) + grid_1);
    // coarse_segment: passes 0, 2, 4 over cells, 1, 3, 5 over chunks of points.
    const uint64_t coarse_odd = Groups((n + items(vk::CoarseSegmentStage::kCpuItems) - 1) /
                                           items(vk::CoarseSegmentStage::kCpuItems),
                                       local);
    EXPECT_EQ(coarse->dispatches, 6u);
    EXPECT_EQ(coarse->workgroups, 3 * Groups(cells, local) + 3 * coarse_odd);
    // feature_maps: quads (pass 1), then runs of items(kCpuItems) pixels of a row (pass 2).
    const uint64_t features_2 = Groups((width + items(vk::FeatureMapsStage::kCpuItems) - 1) /
                                           items(vk::FeatureMapsStage::kCpuItems) * beams,
                                       local);
    EXPECT_EQ(features->dispatches, 2u);
    EXPECT_EQ(features->workgroups, Groups(uint64_t(width) * beams / 4, local) + features_2);

    std::printf(
        "[shape %s] workgroups, n = %u, %u cells, %u x %u: project pass 0 %llu, pass 2 %llu; "
        "grid_reduce pass 0 %llu, pass 1 %llu; coarse_segment passes 0/2/4 %llu each, 1/3/5 %llu "
        "each; feature_maps pass 1 %llu, pass 2 %llu; the four stages %llu\n",
        vk::ShapeName(shape), n, cells, beams, width, (unsigned long long)project_0,
        (unsigned long long)Groups(n, local), (unsigned long long)Groups(cells, local),
        (unsigned long long)grid_1, (unsigned long long)Groups(cells, local),
        (unsigned long long)coarse_odd,
        (unsigned long long)Groups(uint64_t(width) * beams / 4, local),
        (unsigned long long)features_2,
        (unsigned long long)(project->workgroups + grid->workgroups + coarse->workgroups +
                             features->workgroups));
  }
}

}  // namespace
}  // namespace lpir
