// Every buffer the pipeline writes, stage by stage, in the layout the shaders use
// (reference_cpu/stage_table.def lists them). Tests compare them byte for byte between the
// backends; the pictures read them.
#pragma once
#include <cstdint>
#include <vector>

#include "reference_cpu/params.h"

namespace lpir {

constexpr uint32_t kNone = 0xFFFFFFFFu;  // "no point" / "no pixel"

// Point flags (stage 1).
constexpr uint32_t kPointValid = 1u;  // finite, not at the origin, inside the range limits
constexpr uint32_t kPointNoise = 2u;  // reflection noise (III-B.1), valid but never ground

// Pixel classes (stages 6-8).
constexpr uint32_t kPixNonGround = 0u;
constexpr uint32_t kPixGround = 1u;
constexpr uint32_t kPixUnknown = 2u;
constexpr uint32_t kPixEmpty = 3u;
// pixel_fused and pixel_grown only: a pixel the occlusion veto (stage 7) took from ground or
// unknown; in pixel_label stage 8 makes it ground where it lifts the veto, else non-ground.
constexpr uint32_t kPixVetoed = 4u;
// pixel_class only: non-ground by eq. 12, but a smooth slope (f_slope < bank_slope, f_varz <
// bank_rough): a bank, which stage 7 leaves unknown where the coarse label is non-ground.
constexpr uint32_t kPixBank = 5u;
// pixel_fused only: unknown where the coarse segmentation saw no ground (its label of the pixel's
// point non-ground, or no point: a filled hole); stage 8 may climb to it up a bank's grade.
constexpr uint32_t kPixUnknownOff = 6u;

// Why a point got its final label (for tools and pictures).
constexpr uint8_t kWhyNonGround = 0, kWhyGround = 1, kWhyInvalid = 2, kWhyNoise = 3;

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
