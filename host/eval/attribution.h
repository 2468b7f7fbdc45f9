// Which stage decided a wrongly labelled point: for every missed ground point (FN) and every false
// ground point (FP), the first rule below that holds, read from the Frame the CPU reference
// fills (every stage's buffers).
#pragma once
#include <cstdint>

#include "reference_cpu/frame.h"

namespace lpir {

enum class Decider {
  kPrepareInvalid,  // the point is invalid (prepare)
  kPrepareNoise,    // the point is reflection noise (prepare)
  kBackProject,     // its label differs from its pixel's final label (back_project gates)
  kComponent,       // FN: the pixel was grown ground, its component was too small (grow)
  kVeto,            // FN: the occlusion veto made the pixel non-ground (fuse), not lifted
  kClassAndCoarse,  // FN: pixel class and coarse label both non-ground (coarse_segment and
                    // classify_pixels)
  kGrowClassNg,     // FN: unknown (class non-ground, coarse ground) and not grown into
  kGrowCoarseNg,    // FN: unknown (class ground or unknown, coarse non-ground), not grown into
  kGrowHole,        // FN: a hole-filled pixel (no point, no coarse opinion), not grown into
  kSeedBoth,        // FP: a seed whose class and coarse label both said ground
  kSeedCoarse,      // FP: a seed of unknown class that the coarse label made ground
  kGrow,            // FP: an unknown pixel reached by growing
  kLift,            // FP: a vetoed pixel that the ground around it lifted (grow)
};
constexpr int kDeciderCount = 13;

// "prepare:invalid", "prepare:noise", "back-project", "component", "veto", "class+coarse",
// "grow:class-ng", "grow:coarse-ng", "grow:hole", "seed:both", "seed:coarse", "grow", "lift".
const char* DeciderName(Decider d);

// The decider of point i of `f`, whose final label is wrong: `truth` true for a missed ground
// point (FN), false for a false ground point (FP).
Decider Attribute(const Frame& f, uint32_t i, bool truth);

}  // namespace lpir
