// One-shot runs of any stage's kernel for the Vulkan equality tests (as ncnn's test_layer): a
// test makes the stage's buffers here from host vectors (inputs uploaded at once, outputs filled
// after the run), binds them into the stage's <Stage>Buffers, and Run creates the stage, records
// it once, submits, waits and downloads the outputs. Buffers are device-local and made per run.
// The library's stages only bind and record (host/gpu/); this is their test bench.
#pragma once
#include <cstddef>
#include <cstdint>
#include <deque>
#include <optional>
#include <string>
#include <vector>

#include "host/vk/buffer.h"
#include "host/vk/command_buffer.h"
#include "host/vk/device.h"
#include "host/vk/result.h"
#include "host/vk/run_once.h"
#include "host/vk/transfer.h"
#include "reference_cpu/params.h"

namespace lpir::test {

class StageHarness {
 public:
  // `stage` names the stage in error messages ("fuse: pixel_class holds ...").
  StageHarness(const vk::Device& device, std::string stage);

  // A uniform buffer holding `p`.
  const vk::Buffer* Uniform(const Params& p) { return Input("params", &p, sizeof(Params)); }

  // A buffer holding `v` (16 bytes when empty: an empty cloud still binds); Run fails naming
  // `name` unless `v` holds `count` elements.
  template <class T>
  const vk::Buffer* In(const char* name, const std::vector<T>& v, size_t count) {
    if (v.size() != count && status_.ok())
      status_ = vk::UsageError(stage_, std::string(name) + " holds " + std::to_string(v.size()) +
                                           " elements, not " + std::to_string(count));
    return Input(name, v.data(), sizeof(T) * v.size());
  }

  // A buffer of `count` elements that Run downloads into *out (resized to `count` now).
  template <class T>
  const vk::Buffer* Out(std::vector<T>* out, size_t count) {
    out->resize(count);
    const vk::Buffer* buffer = Make(sizeof(T) * count);
    if (buffer && count) outputs_.push_back({buffer, out->data(), sizeof(T) * count});
    return buffer;
  }

  // A buffer of `bytes` that only the kernel reads and writes; never uploaded or downloaded.
  const vk::Buffer* Scratch(VkDeviceSize bytes) { return Make(bytes); }

  // Creates the Stage from `bindings` (the buffers above), records it once with
  // record(stage, cmd), submits, waits and downloads every Out. `gpu_ns`, when given, gets the
  // recorded work's GPU time in nanoseconds (-1 without timestamps). The first error of the
  // buffers above, else of the run.
  template <class Stage, class Bindings, class Record>
  vk::Status Run(const Bindings& bindings, const Record& record, double* gpu_ns = nullptr) {
    if (!status_.ok()) return status_;
    vk::Result<Stage> stage = Stage::Create(device_, bindings);
    if (!stage.ok()) return stage.error();
    LPIR_VK_RETURN_IF_ERROR(vk::RunOnce(
        device_, [&](vk::CommandBuffer& cmd) { return record(stage.value(), cmd); }, gpu_ns));
    return DownloadOutputs();
  }

 private:
  struct Output {
    const vk::Buffer* buffer;
    void* data;
    size_t bytes;
  };

  // A device-local buffer of `bytes`; nullptr after the first error (kept in status_).
  const vk::Buffer* Make(VkDeviceSize bytes);
  // Make, then uploads `bytes` of `data` (none when 0).
  const vk::Buffer* Input(const char* name, const void* data, size_t bytes);
  vk::Status DownloadOutputs();

  const vk::Device& device_;
  std::string stage_;
  std::optional<vk::Transfer> transfer_;
  std::deque<vk::Buffer> buffers_;  // a deque: the pointers handed out stay valid
  std::vector<Output> outputs_;
  vk::Status status_;
};

}  // namespace lpir::test
