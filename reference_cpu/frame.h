// Every buffer the pipeline writes, stage by stage, in the layout the shaders use. Tests compare
// these byte for byte between backends; the pictures read them.
#pragma once
#include <cstdint>
#include <vector>

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

// Why a point got its final label (for tools and pictures).
constexpr uint8_t kWhyNonGround = 0, kWhyGround = 1, kWhyInvalid = 2, kWhyNoise = 3;

// A point's label and why in one byte (Frame::label_why): bit 0 the label, bits 1-2 the why.
constexpr uint8_t PackLabelWhy(uint8_t label, uint8_t why) { return uint8_t(label | why << 1); }
constexpr uint8_t LabelOf(uint8_t label_why) { return label_why & 1u; }
constexpr uint8_t WhyOf(uint8_t label_why) { return uint8_t(label_why >> 1); }

struct Frame {
  uint32_t n = 0;  // points

  // 1 prepare: per point.
  std::vector<uint32_t> flags;  // kPoint* bits
  std::vector<float> zt;        // corrected height, eq. 3
  std::vector<float> r2;        // squared planar range x^2 + y^2
  std::vector<float> inten;     // intensity * intensity_scale

  // 2 project: per point and per pixel (row-major, width columns).
  std::vector<uint32_t> point_pixel;  // v * width + u, or kNone when invalid
  std::vector<uint32_t> pixel_key;    // ordered key of the nearest r2 on the pixel, kNone empty
  std::vector<uint32_t> pixel_point;  // winning point (nearest, then lowest index), kNone empty

  // 3 grid reduce: per point and per cell.
  std::vector<uint32_t> point_cell;  // cell index, kNone for invalid and noise points
  std::vector<uint32_t> cell_zmin;   // ordered key of min z_t, kNone when empty
  std::vector<uint32_t> cell_zmax;   // ordered key of max z_t, 0 when empty
  std::vector<uint32_t> cell_count;

  // 4 coarse segment: per cell and per point.
  std::vector<uint32_t> cell_seed_mode;  // 0 no seeds, 1 lowest points, 2 whole cell (eq. 5)
  std::vector<int32_t> cell_plane;       // per cell 8 ints: n (Q14 unit normal x,y,z), mean (mm
                                         // x,y,z), threshold (mm * 2^14; -1: no ground), seeds
  std::vector<uint32_t> coarse;          // per point 1 ground, 0 non-ground

  // 5 feature maps: per pixel (empty pixels hold 0).
  std::vector<uint32_t> pixel_filled;  // 1 measured, 2 hole filled by morphology, 0 empty
  std::vector<float> f_range, f_inten, f_height, f_slope, f_edge_l, f_edge_r, f_varz, f_vari;

  // 6 classify, 7 fuse, 8 grow: per pixel class kPix*.
  std::vector<uint32_t> pixel_class;
  std::vector<uint32_t> pixel_fused;
  std::vector<uint32_t> pixel_grown;  // after growing, before the connectivity constraint
  std::vector<uint32_t> pixel_comp;   // component label (lowest pixel index) of ground pixels
  std::vector<uint32_t> pixel_label;  // final, kPixGround or kPixNonGround (kPixEmpty when empty)

  // 9 back-project: per point.
  std::vector<uint8_t> label;      // 1 ground, 0 non-ground
  std::vector<uint8_t> why;        // kWhy*
  std::vector<uint8_t> label_why;  // PackLabelWhy(label, why): the bytes the GPU writes, and all
                                   // that a frame downloads (four points a word)
};

}  // namespace lpir
