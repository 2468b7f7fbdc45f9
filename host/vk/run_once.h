// Runs recorded GPU work once and waits for it, for one-shot work outside a frame (the tests'
// stage harness, benchmarks): the caller then owns no command buffer, fence or timestamp queries.
#pragma once
#include <functional>

#include "host/vk/command_buffer.h"
#include "host/vk/device.h"
#include "host/vk/result.h"

namespace lpir::vk {

// Records one command buffer with `record`, submits it and waits. With gpu_ns, the recorded work
// is also timed by two timestamps (*gpu_ns = -1 when the device has no timestamps).
Status RunOnce(const Device& device, const std::function<Status(CommandBuffer&)>& record,
               double* gpu_ns);

}  // namespace lpir::vk
