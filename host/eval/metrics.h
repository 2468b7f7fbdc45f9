// Ground-segmentation scores against SemanticKITTI labels under the four evaluation protocols in
// use (docs/accuracy.md, The four protocols): DG, PP, PW, GG; and against RELLIS-3D labels under
// one. Precision, recall and F1 as in the paper's eq. 13, plus the ground IoU.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "host/eval/ontology.h"
#include "reference_cpu/cloud.h"

namespace lpir {

// How a protocol treats each point (class = label & 0xFFFF; ground classes 40 road, 44 parking,
// 48 sidewalk, 49 other-ground, 60 lane-marking, 72 terrain):
//   kDG  DipG-Seg's evaluator (what LPIR-GSeg compares against): every point is scored; vegetation
//        (70), unlabeled (0) and outlier (1) count as non-ground. Counts summed over a sequence.
//   kPP  Patchwork++ paper: points of class 70, 0 and 1 are not scored at all. Per-frame scores,
//        then their mean over the frames.
//   kPW  Patchwork paper: ground also includes vegetation (70) lower than z = -1.2975 m (three
//        quarters of KITTI's 1.73 m sensor height below the sensor; needs each point's z).
//        Predicted-ground points of class 0 or 1 are not false positives: they leave precision's
//        denominator (counted as `ignored`); not-predicted 0/1 points are true negatives. Per-frame
//        scores, then their mean.
//   kGG  GroundGrid's evaluator: points of class 70, 0 and 1 are not scored. Counts summed.
// and, on RELLIS-3D labels (Ontology::kRellis3d; ground: IsRellisGroundClass):
//   kRellis  void (0) is not scored; every other class is ground or non-ground. Counts summed.
//        The SemanticKITTI protocols differ only in how they treat classes 70, 0 and 1 and a
//        KITTI sensor height, none of which RELLIS-3D has, so they are not defined on it.
enum class Protocol { kDG, kPP, kPW, kGG, kRellis };

// The vegetation height threshold of kPW, metres in the sensor frame.
constexpr float kPwLowVegetationZ = -1.2975f;

// True for the six ground classes (on label & 0xFFFF; the instance bits are ignored).
bool IsGroundClass(uint32_t label);

// "dg", "pp", "pw", "gg", "rellis".
const char* ProtocolName(Protocol protocol);
// Inverse of ProtocolName over the protocols of `ontology` (case-sensitive);
// std::invalid_argument naming the valid ones, or saying which ontology a known name belongs to.
Protocol ParseProtocol(const std::string& name, Ontology ontology = Ontology::kSemanticKitti);
// DG, PP, PW, GG in that order: the SemanticKITTI protocols.
std::vector<Protocol> AllProtocols();
// The protocols defined on `ontology`: AllProtocols() for SemanticKITTI, {kRellis} for RELLIS-3D.
std::vector<Protocol> ProtocolsOf(Ontology ontology);
// The ontology whose labels `protocol` reads.
Ontology OntologyOf(Protocol protocol);
// True for the protocols that average per-frame scores (PP, PW); false: counts summed (DG, GG,
// rellis).
bool AveragesPerFrame(Protocol protocol);

// What a protocol makes of one point.
enum class Outcome { kTP, kFP, kFN, kTN, kIgnored };

struct Counts {
  uint64_t tp = 0;       // predicted ground, truly ground
  uint64_t fp = 0;       // predicted ground, truly non-ground
  uint64_t fn = 0;       // predicted non-ground, truly ground
  uint64_t tn = 0;       // predicted non-ground, truly non-ground
  uint64_t ignored = 0;  // points the protocol does not score
  Counts& operator+=(const Counts& o);
  void Add(Outcome outcome);  // one more point of that outcome
};
bool operator==(const Counts& a, const Counts& b);

// One point under `protocol`: its stored label (class = label & 0xFFFF), whether it was predicted
// ground, and its z in metres (read by kPW only).
Outcome ScorePoint(Protocol protocol, uint32_t label, bool predicted, float z);

// The checks CountFrame makes: std::invalid_argument when the sizes differ or kPW has no z.
void CheckFrame(Protocol protocol, const Labels& pred, const std::vector<uint32_t>& gt,
                const std::vector<float>* z);

// One frame. `pred`: 1 ground, 0 non-ground (any non-zero value is ground); `gt`: the labels of
// the protocol's ontology; `z`: each point's z in metres (required by kPW, ignored by the others;
// may be null for them). std::invalid_argument as CheckFrame.
Counts CountFrame(Protocol protocol, const Labels& pred, const std::vector<uint32_t>& gt,
                  const std::vector<float>* z);

// Fractions in [0, 1]. precision = TP / (TP + FP), recall = TP / (TP + FN),
// F1 = 2 P R / (P + R) (eq. 13), iou = TP / (TP + FP + FN). A ratio whose denominator is 0 is
// defined as 0 (a frame without ground that predicts none scores 0, not 1), so every score is
// always a finite number.
struct Scores {
  double precision = 0;
  double recall = 0;
  double f1 = 0;
  double iou = 0;
};
Scores ScoreCounts(const Counts& counts);

// Accumulates the frames of one sequence under one protocol. Total(): for DG and GG the scores of
// the summed counts; for PP and PW the mean over frames of each per-frame score (F1 and IoU are
// averaged too, not recomputed from the mean precision and recall). No frames: all 0.
class SequenceScores {
 public:
  explicit SequenceScores(Protocol protocol) : protocol_(protocol) {}
  // Adds one frame's counts and returns that frame's scores.
  Scores Add(const Counts& frame);
  Scores Total() const;
  const Counts& summed() const { return summed_; }
  size_t frames() const { return frames_; }
  Protocol protocol() const { return protocol_; }

 private:
  Protocol protocol_;
  Counts summed_;
  Scores score_sum_;
  size_t frames_ = 0;
};

}  // namespace lpir
