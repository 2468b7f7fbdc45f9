#include "host/eval/attribution.h"

#include "reference_cpu/stages.h"

namespace lpir {

const char* DeciderName(Decider d) {
  static const char* const kNames[kDeciderCount] = {
      "prepare:invalid", "prepare:noise", "back-project",   "component", "veto",
      "class+coarse",    "grow:class-ng", "grow:coarse-ng", "grow:hole", "seed:both",
      "seed:coarse",     "grow"};
  return kNames[static_cast<int>(d)];
}

std::vector<uint32_t> FusedWithoutVeto(const Params& p, const Frame& f) {
  Params q = p;
  q.occ_rows = 0;
  Frame g;
  g.pixel_class = f.pixel_class;
  g.pixel_point = f.pixel_point;
  g.coarse = f.coarse;
  g.pixel_filled = f.pixel_filled;
  g.f_range = f.f_range;
  g.f_height = f.f_height;
  Fuse(q, g);
  return g.pixel_fused;
}

Decider Attribute(const Frame& f, const std::vector<uint32_t>& without_veto, uint32_t i,
                  bool truth) {
  const uint8_t why = WhyOf(f.label_why[i]);
  if (why == kWhyInvalid) return Decider::kPrepareInvalid;
  if (why == kWhyNoise) return Decider::kPrepareNoise;
  const uint32_t pix = f.point_pixel[i];
  if ((f.pixel_label[pix] == kPixGround) != (f.label[i] != 0)) return Decider::kBackProject;
  const uint32_t cls = f.pixel_class[pix], fused = f.pixel_fused[pix];
  const uint32_t winner = f.pixel_point[pix];
  if (truth) {
    if (f.pixel_grown[pix] == kPixGround) return Decider::kComponent;
    if (fused == kPixNonGround)
      return without_veto[pix] != kPixNonGround ? Decider::kVeto : Decider::kClassAndCoarse;
    if (winner == kNone) return Decider::kGrowHole;
    return cls == kPixNonGround ? Decider::kGrowClassNg : Decider::kGrowCoarseNg;
  }
  if (fused == kPixGround) return cls == kPixGround ? Decider::kSeedBoth : Decider::kSeedCoarse;
  return Decider::kGrow;
}

}  // namespace lpir
