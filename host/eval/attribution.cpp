#include "host/eval/attribution.h"

namespace lpir {

const char* DeciderName(Decider d) {
  static const char* const kNames[kDeciderCount] = {"prepare:invalid",
                                                    "prepare:noise",
                                                    "back-project",
                                                    "component",
                                                    "veto",
                                                    "class+coarse",
                                                    "grow:class-ng",
                                                    "grow:coarse-ng",
                                                    "grow:hole",
                                                    "seed:both",
                                                    "seed:coarse",
                                                    "grow",
                                                    "lift"};
  return kNames[static_cast<int>(d)];
}

Decider Attribute(const Frame& f, uint32_t i, bool truth) {
  const uint8_t why = WhyOf(f.label_why[i]);
  if (why == kWhyInvalid) return Decider::kPrepareInvalid;
  if (why == kWhyNoise) return Decider::kPrepareNoise;
  const uint32_t pix = f.point_pixel[i];
  if ((f.pixel_label[pix] == kPixGround) != (f.label[i] != 0)) return Decider::kBackProject;
  const uint32_t cls = f.pixel_class[pix], fused = f.pixel_fused[pix];
  const uint32_t winner = f.pixel_point[pix];
  if (truth) {
    if (f.pixel_grown[pix] == kPixGround) return Decider::kComponent;
    if (fused == kPixVetoed) return Decider::kVeto;
    if (fused == kPixNonGround) return Decider::kClassAndCoarse;
    if (winner == kNone) return Decider::kGrowHole;
    return fused == kPixUnknown ? Decider::kGrowClassNg : Decider::kGrowCoarseNg;
  }
  if (fused == kPixVetoed) return Decider::kLift;
  if (fused == kPixGround) return cls == kPixGround ? Decider::kSeedBoth : Decider::kSeedCoarse;
  return Decider::kGrow;
}

}  // namespace lpir
