// Shape choice: the environment variable, else the device type.
#include "host/vk/shape.h"

#include <cstdlib>
#include <string>

namespace lpir::vk {

Result<Shape> ShapeFor(const Device& device) {
  const char* forced = std::getenv(kShapeEnv);
  if (forced && *forced) {
    const std::string value = forced;
    if (value == ShapeName(Shape::kGpu)) return Shape::kGpu;
    if (value == ShapeName(Shape::kCpu)) return Shape::kCpu;
    return UsageError(kShapeEnv, "\"" + value + "\" is no shape (gpu or cpu)");
  }
  return device.properties().deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU ? Shape::kCpu : Shape::kGpu;
}

const char* ShapeName(Shape shape) { return shape == Shape::kCpu ? "cpu" : "gpu"; }

}  // namespace lpir::vk
