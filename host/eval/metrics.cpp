// Ground-segmentation scores under the DG, PP, PW, GG and rellis protocols (see metrics.h).
#include "host/eval/metrics.h"

#include <stdexcept>

namespace lpir {
namespace {

constexpr uint32_t kUnlabeled = 0, kOutlier = 1, kVegetation = 70;

double Ratio(uint64_t num, uint64_t den) { return den == 0 ? 0.0 : double(num) / double(den); }

}  // namespace

bool IsGroundClass(uint32_t label) {
  switch (label & 0xFFFFu) {
    case 40:  // road
    case 44:  // parking
    case 48:  // sidewalk
    case 49:  // other-ground
    case 60:  // lane-marking
    case 72:  // terrain
      return true;
    default:
      return false;
  }
}

const char* ProtocolName(Protocol protocol) {
  switch (protocol) {
    case Protocol::kDG:
      return "dg";
    case Protocol::kPP:
      return "pp";
    case Protocol::kPW:
      return "pw";
    case Protocol::kGG:
      return "gg";
    case Protocol::kRellis:
      return "rellis";
  }
  return "?";
}

Protocol ParseProtocol(const std::string& name, Ontology ontology) {
  std::string known;
  for (Protocol p : ProtocolsOf(ontology)) {
    if (name == ProtocolName(p)) return p;
    known += std::string(known.empty() ? "" : ", ") + ProtocolName(p);
  }
  for (Protocol p : {Protocol::kDG, Protocol::kPP, Protocol::kPW, Protocol::kGG, Protocol::kRellis})
    if (name == ProtocolName(p))
      throw std::invalid_argument("protocol '" + name + "' scores " + OntologyName(OntologyOf(p)) +
                                  " labels, not " + OntologyName(ontology) + " ones (known for " +
                                  OntologyName(ontology) + ": " + known + ")");
  throw std::invalid_argument("unknown protocol '" + name + "' (known: " + known + ")");
}

std::vector<Protocol> AllProtocols() {
  return {Protocol::kDG, Protocol::kPP, Protocol::kPW, Protocol::kGG};
}

std::vector<Protocol> ProtocolsOf(Ontology ontology) {
  if (ontology == Ontology::kRellis3d) return {Protocol::kRellis};
  return AllProtocols();
}

Ontology OntologyOf(Protocol protocol) {
  return protocol == Protocol::kRellis ? Ontology::kRellis3d : Ontology::kSemanticKitti;
}

bool AveragesPerFrame(Protocol protocol) {
  return protocol == Protocol::kPP || protocol == Protocol::kPW;
}

Counts& Counts::operator+=(const Counts& o) {
  tp += o.tp;
  fp += o.fp;
  fn += o.fn;
  tn += o.tn;
  ignored += o.ignored;
  return *this;
}

void Counts::Add(Outcome outcome) {
  switch (outcome) {
    case Outcome::kTP:
      ++tp;
      break;
    case Outcome::kFP:
      ++fp;
      break;
    case Outcome::kFN:
      ++fn;
      break;
    case Outcome::kTN:
      ++tn;
      break;
    case Outcome::kIgnored:
      ++ignored;
      break;
  }
}

bool operator==(const Counts& a, const Counts& b) {
  return a.tp == b.tp && a.fp == b.fp && a.fn == b.fn && a.tn == b.tn && a.ignored == b.ignored;
}

Outcome ScorePoint(Protocol protocol, uint32_t label, bool predicted, float z) {
  const uint32_t cls = ClassOf(label);
  const bool unlabeled = cls == kUnlabeled || cls == kOutlier;
  bool truth = IsGroundClass(cls);
  switch (protocol) {
    case Protocol::kDG:
      break;
    case Protocol::kPP:
    case Protocol::kGG:
      if (unlabeled || cls == kVegetation) return Outcome::kIgnored;
      break;
    case Protocol::kPW:
      if (cls == kVegetation && z < kPwLowVegetationZ) truth = true;
      if (predicted && unlabeled) return Outcome::kIgnored;
      break;
    case Protocol::kRellis:
      if (cls == kRellisVoid) return Outcome::kIgnored;
      truth = IsRellisGroundClass(cls);
      break;
  }
  if (predicted) return truth ? Outcome::kTP : Outcome::kFP;
  return truth ? Outcome::kFN : Outcome::kTN;
}

void CheckFrame(Protocol protocol, const Labels& pred, const std::vector<uint32_t>& gt,
                const std::vector<float>* z) {
  if (pred.size() != gt.size())
    throw std::invalid_argument("prediction has " + std::to_string(pred.size()) +
                                " points but the ground truth " + std::to_string(gt.size()));
  if (protocol == Protocol::kPW) {
    if (!z) throw std::invalid_argument("protocol pw needs each point's z");
    if (z->size() != gt.size())
      throw std::invalid_argument("protocol pw: " + std::to_string(z->size()) + " z values for " +
                                  std::to_string(gt.size()) + " points");
  }
}

Counts CountFrame(Protocol protocol, const Labels& pred, const std::vector<uint32_t>& gt,
                  const std::vector<float>* z) {
  CheckFrame(protocol, pred, gt, z);
  Counts c;
  for (size_t i = 0; i < gt.size(); ++i)
    c.Add(ScorePoint(protocol, gt[i], pred[i] != 0, z ? (*z)[i] : 0.0f));
  return c;
}

Scores ScoreCounts(const Counts& c) {
  Scores s;
  s.precision = Ratio(c.tp, c.tp + c.fp);
  s.recall = Ratio(c.tp, c.tp + c.fn);
  const double sum = s.precision + s.recall;
  s.f1 = sum == 0 ? 0.0 : 2 * s.precision * s.recall / sum;
  s.iou = Ratio(c.tp, c.tp + c.fp + c.fn);
  return s;
}

Scores SequenceScores::Add(const Counts& frame) {
  summed_ += frame;
  ++frames_;
  const Scores s = ScoreCounts(frame);
  score_sum_.precision += s.precision;
  score_sum_.recall += s.recall;
  score_sum_.f1 += s.f1;
  score_sum_.iou += s.iou;
  return s;
}

Scores SequenceScores::Total() const {
  if (!AveragesPerFrame(protocol_)) return ScoreCounts(summed_);
  Scores mean;
  if (frames_ == 0) return mean;
  const double n = double(frames_);
  mean.precision = score_sum_.precision / n;
  mean.recall = score_sum_.recall / n;
  mean.f1 = score_sum_.f1 / n;
  mean.iou = score_sum_.iou / n;
  return mean;
}

}  // namespace lpir
