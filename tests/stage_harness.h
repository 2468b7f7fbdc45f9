// One-shot runs of any stage's kernel for the Vulkan equality tests (as ncnn's test_layer): the
// harness makes a frame's device buffers (host/gpu/frame_buffers.h, sized from the stage table as
// the frame pipeline sizes them), and the stage binds itself to them with its own
// Create(device, const FrameBuffers&). A test hands it a Frame holding what the stage reads;
// ExpectSameStage runs the reference stage and the kernel on it and compares the stage's buffers
// with frame_compare.h's comparer. The library's stages only bind and record (host/gpu/); this is
// their test bench.
#pragma once
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <optional>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "host/gpu/frame_buffers.h"
#include "host/gpu/stage_headers.h"
#include "host/vk/device.h"
#include "host/vk/result.h"
#include "host/vk/run_once.h"
#include "host/vk/transfer.h"
#include "reference_cpu/cloud.h"
#include "reference_cpu/frame.h"
#include "reference_cpu/params.h"
#include "reference_cpu/stages.h"
#include "tests/frame_compare.h"

namespace lpir::test {

// The most points, pixels and cells the harness's buffers hold.
struct FrameLimits {
  uint32_t points = 0, pixels = 0, cells = 0;
  // Exactly a frame of n points under p.
  static FrameLimits Of(uint32_t n, const Params& p) {
    return {n, p.width * p.beams, CellCount(p)};
  }
};

// A frame's device buffers and the tables', filled from a Frame and read back into one; stage
// agnostic (every buffer of the table).
class FrameBench {
 public:
  // Buffers for frames within `limits` (16 bytes at least each: an empty frame still binds), the
  // tables holding `tables` (16 bytes each when null).
  FrameBench(const vk::Device& device, const FrameLimits& limits, const Tables* tables);

  const vk::FrameBuffers& buffers() const { return buffers_; }
  const vk::Device& device() const { return device_; }
  // The first error of the set-up (Fill, Read and Bytes return theirs).
  const vk::Status& status() const { return status_; }

  // Uploads p (has_ring from the cloud, as RunReference sets it), the cloud's points and rings,
  // and every non-empty buffer of `in` that a stage before `stage` writes (an error names a buffer
  // not of the table's size); fills the frame's other LPIR_BUFFER buffers with 0xEE bytes, so that
  // a word the kernel should write and does not shows (scratch is the kernel's own). Returns the
  // frame's size.
  vk::Result<vk::FrameSize> Fill(const char* stage, const Params& p, const Cloud* cloud,
                                 const Frame& in);
  // Downloads `stage`'s device buffers of a frame of `size` into out's (n from size) and empties
  // its host buffers (the test unpacks those).
  vk::Status Read(const char* stage, const vk::FrameSize& size, Frame* out);
  // The first `count` bytes of the device buffer `name` of the table (word padding included).
  vk::Status Bytes(const char* name, size_t count, std::vector<uint8_t>* bytes);

 private:
  const vk::Device& device_;
  FrameLimits limits_;
  vk::TableBuffers tables_;
  vk::FrameBuffers buffers_;
  std::optional<vk::Transfer> transfer_;
  vk::Status status_;
};

// Calls a reference stage, on one thread, with the arguments its parameter list takes (one of the
// four lists of reference_cpu/stage_table.def, each with the threads last).
template <class Fn>
void CallReference(Fn fn, const Cloud& c, const Params& p, const Tables& t, Frame& f) {
  if constexpr (std::is_invocable_v<Fn, const Cloud&, const Params&, Frame&, Threads>)
    fn(c, p, f, Threads());
  else if constexpr (std::is_invocable_v<Fn, const Params&, Frame&, Threads>)
    fn(p, f, Threads());
  else if constexpr (std::is_invocable_v<Fn, const Params&, const Tables&, Frame&, Threads>)
    fn(p, t, f, Threads());
  else
    fn(c, p, t, f, Threads());
}

// The stage table's name and reference function of vk::<Type>Stage.
template <class Stage>
struct StageOf;
#define LPIR_STAGE(name, Type, parameters)                                              \
  template <>                                                                           \
  struct StageOf<vk::Type##Stage> {                                                     \
    static constexpr const char* kName = #name;                                         \
    static void Reference(const Cloud& c, const Params& p, const Tables& t, Frame& f) { \
      CallReference(&Type, c, p, t, f);                                                 \
    }                                                                                   \
  };
#define LPIR_BUFFER LPIR_IGNORE
#define LPIR_HOST_BUFFER LPIR_IGNORE
#define LPIR_SCRATCH LPIR_IGNORE
#include "reference_cpu/stage_table.def"

// Stage bound to a FrameBench's buffers once (its Create(device, const FrameBuffers&)), run on
// frame after frame.
template <class Stage>
class StageHarness {
 public:
  StageHarness(const vk::Device& device, const FrameLimits& limits, const Tables* tables)
      : bench_(device, limits, tables) {}

  // Fills the bench from `in` (FrameBench::Fill), records the stage once over the frame, submits,
  // waits, and gives *out a copy of `in` with the stage's buffers read back. `gpu_ns`, when given,
  // gets the GPU time in nanoseconds (-1 without timestamps).
  vk::Status Run(const Params& p, const Cloud* cloud, const Frame& in, Frame* out,
                 double* gpu_ns = nullptr) {
    LPIR_VK_RETURN_IF_ERROR(bench_.status());
    if (!stage_) {
      vk::Result<Stage> made = Stage::Create(bench_.device(), bench_.buffers());
      if (!made.ok()) return made.error();
      stage_.emplace(std::move(made).value());
    }
    LPIR_VK_ASSIGN_OR_RETURN(const vk::FrameSize size,
                             bench_.Fill(StageOf<Stage>::kName, p, cloud, in));
    LPIR_VK_RETURN_IF_ERROR(vk::RunOnce(
        bench_.device(), [&](vk::CommandBuffer& cmd) { return stage_->Record(cmd, size); },
        gpu_ns));
    *out = in;
    return bench_.Read(StageOf<Stage>::kName, size, out);
  }
  FrameBench& bench() { return bench_; }

 private:
  FrameBench bench_;
  std::optional<Stage> stage_;
};

// The bytes ExpectSameStage compares for one frame: the stage's device buffers, n points under p.
template <class Stage>
uint64_t StageBytes(uint32_t n, const Params& p) {
  uint64_t bytes = 0;
  Frame f;
  ForEachBuffer(
      [&](const BufferInfo& info, const auto& v) {
        if (info.on_device && std::string(info.stage) == StageOf<Stage>::kName)
          bytes += ItemsOf(info.per, n, p) * info.stride * sizeof(v[0]);
      },
      f);
  return bytes;
}

// Runs the reference stage on a copy of `in` and the kernel (through `h`) from `in`, and compares
// every device buffer the stage writes byte for byte, each whole (a mismatch names the buffer, the
// element, both values and its point, pixel or cell). Prints a line; returns the bytes compared
// (0 and a failure when the kernel could not run). `cloud`: the points (prepare, project and
// coarse_segment read them), `t`: the tables (project, grid_reduce, coarse_segment).
template <class Stage>
uint64_t ExpectSameStage(StageHarness<Stage>& h, const Params& p, const Tables* t,
                         const Cloud* cloud, const Frame& in, const std::string& what) {
  static const Tables kNoTables;
  static const Cloud kNoCloud;
  Frame cpu = in, gpu;
  Params q = p;
  if (cloud) q.has_ring = cloud->ring.empty() ? 0u : 1u;
  StageOf<Stage>::Reference(cloud ? *cloud : kNoCloud, q, t ? *t : kNoTables, cpu);
  double gpu_ns = 0;
  const vk::Status status = h.Run(p, cloud, in, &gpu, &gpu_ns);
  EXPECT_TRUE(status.ok()) << what << ": " << status.message();
  if (!status.ok()) return 0;
  const char* stage = StageOf<Stage>::kName;
  uint64_t bytes = 0;
  ForEachBuffer(
      [&](const BufferInfo& info, const auto& a, const auto& b) {
        if (info.on_device && std::string(info.stage) == stage)
          bytes += ExpectSameBuffer(stage, info.name, info.per, info.stride, a, b, p, cloud, what);
      },
      cpu, gpu);
  EXPECT_EQ(bytes, StageBytes<Stage>(gpu.n, p)) << what << ": bytes compared";
  std::printf("[%s] %s: %u points, %ux%u pixels: %llu bytes compared, GPU %.3f ms\n", stage,
              what.c_str(), cpu.n, p.beams, p.width, static_cast<unsigned long long>(bytes),
              gpu_ns / 1e6);
  return bytes;
}

// The same on a harness made for this frame alone.
template <class Stage>
uint64_t ExpectSameStage(const vk::Device& device, const Params& p, const Tables* t,
                         const Cloud* cloud, const Frame& in, const std::string& what) {
  StageHarness<Stage> h(device, FrameLimits::Of(cloud ? uint32_t(cloud->size()) : in.n, p), t);
  return ExpectSameStage(h, p, t, cloud, in, what);
}

}  // namespace lpir::test
