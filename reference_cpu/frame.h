// Every buffer the pipeline writes, stage by stage, in the layout the shaders use
// (reference_cpu/stage_table.def lists them). Tests compare them byte for byte between the
// backends; the pictures read them.
#pragma once
#include <cstdint>
#include <vector>

#include "reference_cpu/params.h"
#include "shaders/common/frame_codes.h"  // kNone, kPoint*, kPix*, kWhy*

namespace lpir {

// A point's label and why in one byte (Frame::label_why): bit 0 the label, bits 1-2 the why.
constexpr uint8_t PackLabelWhy(uint8_t label, uint8_t why) { return uint8_t(label | why << 1); }
constexpr uint8_t LabelOf(uint8_t label_why) { return label_why & 1u; }
constexpr uint8_t WhyOf(uint8_t label_why) { return uint8_t(label_why >> 1); }

// What a buffer's items are: a frame's n points, its width * beams pixels (row-major), or its
// CellCount(p) grid cells.
enum class Per { kPoint, kPixel, kCell };

// Items of a `per` buffer in a frame of n points under p.
inline uint64_t ItemsOf(Per per, uint64_t n, const Params& p) {
  return per == Per::kPoint   ? n
         : per == Per::kPixel ? uint64_t(p.width) * p.beams
                              : uint64_t(CellCount(p));
}

// The stage table's no-op: a consumer's macro for the kinds of lines it does not use
// (reference_cpu/stage_table.def).
#define LPIR_IGNORE(...)

// Every buffer of every stage: a std::vector per LPIR_BUFFER and LPIR_HOST_BUFFER line of
// reference_cpu/stage_table.def, in its order, named, typed and sized (items x stride) as there.
struct Frame {
  uint32_t n = 0;  // points
#define LPIR_STAGE LPIR_IGNORE
#define LPIR_BUFFER(stage, name, type, per, stride) std::vector<type> name;
#define LPIR_HOST_BUFFER(stage, name, type, per, stride) std::vector<type> name;
#define LPIR_SCRATCH LPIR_IGNORE
#include "reference_cpu/stage_table.def"
};

// One buffer of Frame, as its table line gives it.
struct BufferInfo {
  const char* stage;  // the stage that writes it
  const char* name;   // its Frame member
  Per per;
  uint32_t stride;  // elements per item
  bool on_device;   // an LPIR_BUFFER line: a device buffer of the same layout too
};

// Calls fn(info, frames.name...) for every buffer of Frame in table order: the same member of
// each frame, so that one call compares, checks or reads a buffer whatever the stage.
template <typename Fn, typename... Frames>
void ForEachBuffer(Fn&& fn, Frames&... frames) {
#define LPIR_STAGE LPIR_IGNORE
#define LPIR_BUFFER(stage, name, type, per, stride) \
  fn(BufferInfo{#stage, #name, Per::per, stride, true}, frames.name...);
#define LPIR_HOST_BUFFER(stage, name, type, per, stride) \
  fn(BufferInfo{#stage, #name, Per::per, stride, false}, frames.name...);
#define LPIR_SCRATCH LPIR_IGNORE
#include "reference_cpu/stage_table.def"
}

}  // namespace lpir
