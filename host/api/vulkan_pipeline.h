// VulkanPipeline: the Vulkan twin of CpuPipeline, a vk::FramePipeline on a device of its own
// (vk::Context), its errors thrown as std::runtime_error("Vulkan: <message>").
#pragma once
#include <cstdint>
#include <memory>
#include <string>

#include "host/api/frame_backend.h"
#include "host/vk/context.h"
#include "host/vk/result.h"
#include "reference_cpu/params.h"

namespace lpir {

namespace vk {
class FramePipeline;
}  // namespace vk

class VulkanPipeline final : public FrameBackend {
 public:
  // The device `context_options` asks for and a FramePipeline of `slots` slots on it for clouds
  // of up to `max_points` points, taking batches of up to `batch` frames. The Error says why
  // not: no device (no_device), only CPU drivers where a GPU was asked for (cpu_driver_only), a
  // device limit, a failed call.
  static vk::Result<std::unique_ptr<VulkanPipeline>> Create(
      const vk::ContextOptions& context_options, const Params& params, const Tables& tables,
      uint32_t max_points, uint32_t slots, uint32_t batch);
  ~VulkanPipeline() override;
  VulkanPipeline(const VulkanPipeline&) = delete;
  VulkanPipeline& operator=(const VulkanPipeline&) = delete;

  void Stage(uint32_t slot, const Cloud& cloud, const Mount& mount, bool borrowed) override;
  void SubmitStaged(uint32_t first, uint32_t count) override;
  void Collect(uint32_t slot, Frame& out, bool all_buffers, FrameTimes* times) override;

  uint32_t batch() const override { return batch_; }
  uint64_t device_bytes() const override;
  bool on_cpu_driver() const override;
  std::string device_name() const;

 private:
  explicit VulkanPipeline(uint32_t batch);

  uint32_t batch_;
  std::unique_ptr<vk::Context> context_;         // at a stable address: the pipeline points to it
  std::unique_ptr<vk::FramePipeline> pipeline_;  // uses *context_: destroyed first, waiting for
                                                 // its frames
};

}  // namespace lpir
