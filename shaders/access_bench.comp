// Not a stage: the buffer-access patterns that decide a shader's speed on a CPU driver, for
// bench/access_bench.cpp. Each pass (specialization constant kPass) writes b = a + 1 over n
// uints (push constant, a power of 2) in its own way:
//   0 one element per invocation;
//   1 four per invocation, through uvec4 views of the same buffers (n a multiple of 4);
//   2 one invocation per kChunk consecutive elements, in a loop;
//   3 as 0, plus a branch that no invocation takes at run time, holding 16 more loads and
//     stores: what it costs shows whether the device skips code that no lane runs.
#version 450

layout(local_size_x_id = 0) in;

layout(std430, set = 0, binding = 0) readonly buffer A { uint a[]; };
layout(std430, set = 0, binding = 1) buffer B { uint b[]; };
layout(std430, set = 0, binding = 0) readonly buffer A4 { uvec4 a4[]; };
layout(std430, set = 0, binding = 1) writeonly buffer B4 { uvec4 b4[]; };

layout(constant_id = 1) const uint kPass = 0u;

layout(push_constant) uniform Push { uint n; } pc;

const uint kChunk = 64u;

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (kPass == 1u) {
    if (i < pc.n / 4u) b4[i] = a4[i] + 1u;
  } else if (kPass == 2u) {
    uint end = min(i * kChunk + kChunk, pc.n);
    for (uint k = i * kChunk; k < end; ++k) b[k] = a[k] + 1u;
  } else {
    if (i >= pc.n) return;
    uint v = a[i];
    if (kPass == 3u && v == 0xFFFFFFFFu) {  // the input holds no such value
      uint mask = pc.n - 1u;
      for (uint k = 1u; k <= 16u; ++k) b[(i + k * 4099u) & mask] = a[(i + k * 8191u) & mask];
    }
    b[i] = v + 1u;
  }
}
