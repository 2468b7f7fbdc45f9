// Buffer-access patterns on the Vulkan device (lavapipe unless LPIR_VK_DEVICE names another):
// shaders/access_bench.comp's four ways of writing b = a + 1 over 2^20 uints, timed by GPU
// timestamps, median of 20 dispatches, reported as nanoseconds per element. They explain the
// shapes of the stage shaders (docs/speed.md): on Mesa 22.3's lavapipe each buffer access of an
// invocation is a loop over the SIMD lanes, so a uvec4 access for four elements is much cheaper
// than four scalar ones, and code under an `if` costs even when no lane takes it.
// Each benchmark checks b before it times anything.
#include <benchmark/benchmark.h>

#include <cstdint>
#include <cstdlib>
#include <memory>
#include <numeric>
#include <string>
#include <vector>

#include "host/vk/buffer.h"
#include "host/vk/context.h"
#include "host/vk/kernel.h"
#include "host/vk/run_once.h"
#include "host/vk/transfer.h"

namespace lpir::vk {
namespace {
#include "shaders/access_bench.spv.h"  // kAccessBenchSpv

constexpr uint32_t kElements = 1u << 20;
constexpr uint32_t kLocalSize = 64, kChunk = 64;  // shaders/access_bench.comp's kChunk

struct Fixture {
  Context context;
  Buffer a, b;
  Kernel kernel;
};

// The device, the buffers (a = 0, 7, 14, ...) and the four passes; nullptr (and why) on failure.
std::unique_ptr<Fixture> MakeFixture(std::string* why) {
  ContextOptions options = ContextOptions::FromEnvironment();
  Result<Context> context = Context::Create(options);
  if (!context.ok()) {
    *why = context.error().message;
    return nullptr;
  }
  const Device& device = context.value().device();
  const VkDeviceSize bytes = 4 * VkDeviceSize(kElements);
  Result<Buffer> a = Buffer::Create(device, bytes, MemoryKind::kDeviceLocal);
  Result<Buffer> b = Buffer::Create(device, bytes, MemoryKind::kDeviceLocal);
  Result<Transfer> transfer = Transfer::Create(device);
  if (!a.ok() || !b.ok() || !transfer.ok()) {
    *why = "buffers";
    return nullptr;
  }
  std::vector<uint32_t> values(kElements);
  for (uint32_t i = 0; i < kElements; ++i) values[i] = 7 * i;
  if (!transfer.value().Upload(a.value(), values.data(), bytes).ok()) {
    *why = "upload";
    return nullptr;
  }
  PipelineDesc desc;
  desc.name = "access_bench";
  desc.code = SpirvOf(kAccessBenchSpv);
  desc.bindings = {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER};
  desc.push_constant_bytes = sizeof(uint32_t);
  desc.local_size_x = kLocalSize;
  desc.passes = 4;
  Result<Kernel> kernel = Kernel::Create(device, desc, {&a.value(), &b.value()});
  if (!kernel.ok()) {
    *why = kernel.error().message;
    return nullptr;
  }
  return std::unique_ptr<Fixture>(new Fixture{std::move(context.value()), std::move(a.value()),
                                              std::move(b.value()), std::move(kernel.value())});
}

void BM_Access(benchmark::State& state, uint32_t pass) {
  std::string why;
  std::unique_ptr<Fixture> f = MakeFixture(&why);
  if (!f) {
    state.SkipWithError(("no Vulkan device: " + why).c_str());
    return;
  }
  const Device& device = f->context.device();
  const uint32_t n = kElements;
  const uint32_t invocations = pass == 1 ? n / 4 : pass == 2 ? n / kChunk : n;
  auto run = [&](double* ns) {
    return RunOnce(
        device, [&](CommandBuffer& cmd) { return f->kernel.Record(cmd, invocations, &n, pass); },
        ns);
  };
  double ns = 0;
  if (!run(&ns).ok()) {
    state.SkipWithError("dispatch failed");
    return;
  }
  std::vector<uint32_t> out(n);
  Result<Transfer> transfer = Transfer::Create(device);
  if (!transfer.ok() || !transfer.value().Download(f->b, out.data(), 4 * VkDeviceSize(n)).ok()) {
    state.SkipWithError("download failed");
    return;
  }
  for (uint32_t i = 0; i < n; ++i)
    if (out[i] != 7 * i + 1) {
      state.SkipWithError(("b[" + std::to_string(i) + "] != a[i] + 1").c_str());
      return;
    }
  for (auto _ : state) {
    if (!run(&ns).ok()) {
      state.SkipWithError("dispatch failed");
      return;
    }
    state.SetIterationTime(ns * 1e-9);
  }
  state.counters["ns_per_element"] = benchmark::Counter(ns / n);
  state.SetLabel(device.name());
}

}  // namespace
}  // namespace lpir::vk

int main(int argc, char** argv) {
  const char* names[] = {"one_per_invocation", "uvec4_per_invocation", "loop_of_64",
                         "untaken_branch"};
  for (uint32_t pass = 0; pass < 4; ++pass)
    benchmark::RegisterBenchmark((std::string("BM_Access/") + names[pass]).c_str(),
                                 lpir::vk::BM_Access, pass)
        ->Unit(benchmark::kMillisecond)
        ->Iterations(1)
        ->Repetitions(20)
        ->ReportAggregatesOnly(true)
        ->UseManualTime();
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
