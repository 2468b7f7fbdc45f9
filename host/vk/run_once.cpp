#include "host/vk/run_once.h"

#include "host/vk/fence.h"
#include "host/vk/timestamp_queries.h"

namespace lpir::vk {

Status RunOnce(const Device& device, const std::function<Status(CommandBuffer&)>& record,
               double* gpu_ns) {
  LPIR_VK_ASSIGN_OR_RETURN(CommandBuffer cmd, CommandBuffer::Create(device));
  LPIR_VK_ASSIGN_OR_RETURN(Fence fence, Fence::Create(device));
  const bool timed = gpu_ns && device.timestamp_valid_bits() != 0;
  Result<TimestampQueries> queries =
      timed ? TimestampQueries::Create(device, 2) : Result<TimestampQueries>(Error{});
  if (timed && !queries.ok()) return queries.error();

  LPIR_VK_RETURN_IF_ERROR(cmd.Begin());
  if (timed) {
    cmd.ResetQueries(queries.value());
    cmd.WriteTimestamp(queries.value(), 0);
  }
  LPIR_VK_RETURN_IF_ERROR(record(cmd));
  if (timed) cmd.WriteTimestamp(queries.value(), 1);
  LPIR_VK_RETURN_IF_ERROR(cmd.End());
  LPIR_VK_RETURN_IF_ERROR(cmd.SubmitAndWait(fence));
  if (gpu_ns) {
    *gpu_ns = -1.0;
    if (timed) {
      double ns[2];
      LPIR_VK_RETURN_IF_ERROR(queries->Read(ns));
      *gpu_ns = ns[1] - ns[0];
    }
  }
  return Status();
}

}  // namespace lpir::vk
