#include "host/api/cpu_pipeline.h"

namespace lpir {

CpuPipeline::CpuPipeline(const Params& params, const Tables& tables, uint32_t slots)
    : params_(params), tables_(tables), clouds_(slots), mounts_(slots) {}

void CpuPipeline::Stage(uint32_t slot, const Cloud& cloud, const Mount& mount) {
  clouds_[slot] = cloud;  // into the slot's vectors: no allocation once they have grown
  mounts_[slot] = mount;
}

void CpuPipeline::SubmitStaged(uint32_t, uint32_t) {}  // nothing to start: Collect runs the frame

void CpuPipeline::Collect(uint32_t slot, Frame& out, bool, FrameTimes* times) {
  RunReference(clouds_[slot], WithMount(params_, mounts_[slot]), tables_, out, times);
}

}  // namespace lpir
