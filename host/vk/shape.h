// Shape: how much work one invocation of a chunked pass takes on a device (docs/spec.md,
// Performance shape). kGpu runs one point or pixel per invocation: neighbouring lanes on
// neighbouring elements (coalesced), no serial loop, a workgroup per 64 elements to fill the
// device. kCpu runs a chunk of consecutive points or pixels per invocation, runs of one cell merged
// in registers before the atomics: a CPU driver such as lavapipe pays for every invocation and
// every buffer access (a loop over its SIMD lanes), so fewer, longer invocations are faster there
// (docs/decisions/shapes.md). Both shapes produce the same bytes.
// Kernel::Create asks ShapeFor once per kernel and specializes the shaders' kItems (constant 2).
#pragma once
#include "host/vk/device.h"
#include "host/vk/result.h"

namespace lpir::vk {

enum class Shape { kGpu, kCpu };

// The environment variable that forces a shape: "gpu" or "cpu" (unset or empty: by device).
inline constexpr const char* kShapeEnv = "LPIR_VK_SHAPE";

// The shape a kernel created now on `device` takes: LPIR_VK_SHAPE when set (read at every call),
// else kCpu on a VK_PHYSICAL_DEVICE_TYPE_CPU device and kGpu on every other. An error naming the
// variable and its value when that is neither "gpu" nor "cpu".
Result<Shape> ShapeFor(const Device& device);

// "gpu" or "cpu", the names LPIR_VK_SHAPE takes.
const char* ShapeName(Shape shape);

}  // namespace lpir::vk
