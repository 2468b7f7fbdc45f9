// CpuPipeline: the CPU reference (RunReference) behind the slots of vk::FramePipeline. Stage
// copies the cloud into its slot, as the Vulkan twin copies it into the slot's staging buffer;
// the frame runs when it is collected, on the calling thread, straight into the caller's Frame:
// one set of frame buffers however many slots, reused from frame to frame.
#pragma once
#include <cstdint>
#include <vector>

#include "host/api/frame_backend.h"
#include "reference_cpu/params.h"

namespace lpir {

class CpuPipeline final : public FrameBackend {
 public:
  CpuPipeline(const Params& params, const Tables& tables, uint32_t slots);

  void Stage(uint32_t slot, const Cloud& cloud, const Mount& mount) override;
  void SubmitStaged(uint32_t first, uint32_t count) override;
  void Collect(uint32_t slot, Frame& out, bool all_buffers, FrameTimes* times) override;

  uint32_t batch() const override { return 1; }  // frames run one by one
  uint64_t device_bytes() const override { return 0; }
  bool on_cpu_driver() const override { return false; }

 private:
  Params params_;
  Tables tables_;
  std::vector<Cloud> clouds_;  // per slot: the cloud staged
  std::vector<Mount> mounts_;  // and its mount
};

}  // namespace lpir
