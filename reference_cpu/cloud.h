// A LiDAR scan as the pipeline sees it: plain buffers in the layout the shaders use.
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

namespace lpir {

// One point = 4 floats (x, y, z in metres in the sensor frame, raw intensity as the file had it),
// the std430 vec4 layout. `ring` is either empty (no ring field in the file) or one entry per
// point: the laser index as the file numbers it (the sensor profile says whether 0 is the top).
struct Cloud {
  std::vector<float> xyzi;
  std::vector<int32_t> ring;

  size_t size() const { return xyzi.size() / 4; }
  float x(size_t i) const { return xyzi[4 * i + 0]; }
  float y(size_t i) const { return xyzi[4 * i + 1]; }
  float z(size_t i) const { return xyzi[4 * i + 2]; }
  float intensity(size_t i) const { return xyzi[4 * i + 3]; }
  void Push(float x, float y, float z, float i) {
    xyzi.push_back(x);
    xyzi.push_back(y);
    xyzi.push_back(z);
    xyzi.push_back(i);
  }
};

// Per-point ground truth or prediction: 1 ground, 0 non-ground.
using Labels = std::vector<uint8_t>;

}  // namespace lpir
