// Evaluation protocols DG, PP, PW, GG and rellis on small hand-counted frames: exact counts per
// protocol, the eq. 13 scores, summed versus per-frame-mean aggregation, 0/0 and error cases; the
// class tables of both ontologies; the per-class and per-range-band tallies.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "host/eval/by_class.h"
#include "host/eval/by_range.h"
#include "host/eval/metrics.h"
#include "host/eval/ontology.h"

namespace lpir {
namespace {

Counts Make(uint64_t tp, uint64_t fp, uint64_t fn, uint64_t tn, uint64_t ignored) {
  Counts c;
  c.tp = tp;
  c.fp = fp;
  c.fn = fn;
  c.tn = tn;
  c.ignored = ignored;
  return c;
}

// Fourteen points covering every case; the comment gives DG / PP=GG / PW.
struct Frame {
  Labels pred;
  std::vector<uint32_t> gt;
  std::vector<float> z;
};

Frame Mixed() {
  Frame f;
  auto add = [&](uint32_t label, uint8_t pred, float z) {
    f.gt.push_back(label);
    f.pred.push_back(pred);
    f.z.push_back(z);
  };
  add(40, 1, -1.7f);               //  0 road, ground:          TP / TP / TP
  add(40, 0, -1.7f);               //  1 road, missed:          FN / FN / FN
  add(72, 1, -1.6f);               //  2 terrain:               TP / TP / TP
  add(48, 0, -1.8f);               //  3 sidewalk, missed:      FN / FN / FN
  add(10, 1, -1.0f);               //  4 car as ground:         FP / FP / FP
  add(10, 0, -0.5f);               //  5 car:                   TN / TN / TN
  add(70, 1, -1.5f);               //  6 low vegetation, pred:  FP / ig / TP
  add(70, 0, -1.5f);               //  7 low vegetation:        TN / ig / FN
  add(70, 1, -0.5f);               //  8 high vegetation, pred: FP / ig / FP
  add(0, 1, -1.7f);                //  9 unlabeled, pred:       FP / ig / ig
  add(1, 0, -3.0f);                // 10 outlier:               TN / ig / TN
  add(50, 0, 2.0f);                // 11 building:              TN / TN / TN
  add(40 | (5u << 16), 1, -1.7f);  // 12 road with an instance: TP / TP / TP
  add(70, 1, -1.2975f);            // 13 vegetation exactly at the threshold (not below):
                                   //                           FP / ig / FP
  return f;
}

TEST(EvalMetrics, GroundClasses) {
  for (uint32_t c : {40u, 44u, 48u, 49u, 60u, 72u}) {
    EXPECT_TRUE(IsGroundClass(c)) << c;
    EXPECT_TRUE(IsGroundClass(c | (123u << 16))) << c;  // instance bits ignored
  }
  for (uint32_t c : {0u, 1u, 10u, 50u, 51u, 70u, 71u, 80u, 252u, 41u})
    EXPECT_FALSE(IsGroundClass(c)) << c;
}

TEST(EvalMetrics, CountsPerProtocol) {
  Frame f = Mixed();
  EXPECT_EQ(CountFrame(Protocol::kDG, f.pred, f.gt, nullptr), Make(3, 5, 2, 4, 0));
  EXPECT_EQ(CountFrame(Protocol::kPP, f.pred, f.gt, nullptr), Make(3, 1, 2, 2, 6));
  EXPECT_EQ(CountFrame(Protocol::kGG, f.pred, f.gt, nullptr), Make(3, 1, 2, 2, 6));
  EXPECT_EQ(CountFrame(Protocol::kPW, f.pred, f.gt, &f.z), Make(4, 3, 3, 3, 1));
  // z is ignored by the protocols that do not need it.
  EXPECT_EQ(CountFrame(Protocol::kDG, f.pred, f.gt, &f.z), Make(3, 5, 2, 4, 0));
}

TEST(EvalMetrics, PwUnlabeledOnlyLeavesPrecisionWhenPredictedGround) {
  // Predicted-ground 0/1 points are not false positives; not-predicted ones are true negatives.
  Labels pred = {1, 1, 0, 0, 1};
  std::vector<uint32_t> gt = {0, 1, 0, 1, 40};
  std::vector<float> z(5, -1.7f);
  EXPECT_EQ(CountFrame(Protocol::kPW, pred, gt, &z), Make(1, 0, 0, 2, 2));
  Scores s = ScoreCounts(CountFrame(Protocol::kPW, pred, gt, &z));
  EXPECT_EQ(s.precision, 1.0);
  // Under DG the same points are false positives.
  EXPECT_EQ(CountFrame(Protocol::kDG, pred, gt, nullptr), Make(1, 2, 0, 2, 0));
}

TEST(EvalMetrics, ScoresFollowEquation13) {
  Frame f = Mixed();
  Scores dg = ScoreCounts(CountFrame(Protocol::kDG, f.pred, f.gt, nullptr));
  EXPECT_DOUBLE_EQ(dg.precision, 3.0 / 8);
  EXPECT_DOUBLE_EQ(dg.recall, 3.0 / 5);
  EXPECT_DOUBLE_EQ(dg.f1, 6.0 / 13);  // 2 * (3/8) * (3/5) / (3/8 + 3/5)
  EXPECT_DOUBLE_EQ(dg.iou, 3.0 / 10);
  Scores pp = ScoreCounts(CountFrame(Protocol::kPP, f.pred, f.gt, nullptr));
  EXPECT_DOUBLE_EQ(pp.precision, 3.0 / 4);
  EXPECT_DOUBLE_EQ(pp.recall, 3.0 / 5);
  EXPECT_DOUBLE_EQ(pp.f1, 2.0 / 3);
  EXPECT_DOUBLE_EQ(pp.iou, 3.0 / 6);
  Scores pw = ScoreCounts(CountFrame(Protocol::kPW, f.pred, f.gt, &f.z));
  EXPECT_DOUBLE_EQ(pw.precision, 4.0 / 7);
  EXPECT_DOUBLE_EQ(pw.recall, 4.0 / 7);
  EXPECT_DOUBLE_EQ(pw.f1, 4.0 / 7);
  EXPECT_DOUBLE_EQ(pw.iou, 4.0 / 10);
}

TEST(EvalMetrics, ZeroOverZeroIsZero) {
  Scores none = ScoreCounts(Counts{});
  EXPECT_EQ(none.precision, 0.0);
  EXPECT_EQ(none.recall, 0.0);
  EXPECT_EQ(none.f1, 0.0);
  EXPECT_EQ(none.iou, 0.0);
  // No ground anywhere and none predicted: still 0, not 1.
  Labels pred = {0, 0};
  std::vector<uint32_t> gt = {10, 50};
  Counts c = CountFrame(Protocol::kDG, pred, gt, nullptr);
  EXPECT_EQ(c, Make(0, 0, 0, 2, 0));
  EXPECT_EQ(ScoreCounts(c).f1, 0.0);
  // Ground predicted, none there: precision 0, recall 0/0 = 0.
  Scores fp_only = ScoreCounts(Make(0, 4, 0, 0, 0));
  EXPECT_EQ(fp_only.precision, 0.0);
  EXPECT_EQ(fp_only.recall, 0.0);
  EXPECT_EQ(fp_only.iou, 0.0);
}

TEST(EvalMetrics, SummedVersusPerFrameMean) {
  Frame a = Mixed();
  // Frame b: two road points found, one car called ground, one car right: TP 2, FP 1, TN 1.
  Frame b;
  b.pred = {1, 1, 0, 1};
  b.gt = {40, 40, 10, 10};
  b.z = {-1.7f, -1.7f, -1.0f, -1.0f};
  for (Protocol p : AllProtocols()) {
    SCOPED_TRACE(ProtocolName(p));
    SequenceScores seq(p);
    Counts ca = CountFrame(p, a.pred, a.gt, &a.z);
    Counts cb = CountFrame(p, b.pred, b.gt, &b.z);
    Scores sa = seq.Add(ca);
    Scores sb = seq.Add(cb);
    EXPECT_EQ(seq.frames(), 2u);
    Counts sum = ca;
    sum += cb;
    EXPECT_EQ(seq.summed(), sum);
    Scores t = seq.Total();
    if (AveragesPerFrame(p)) {
      EXPECT_DOUBLE_EQ(t.precision, (sa.precision + sb.precision) / 2);
      EXPECT_DOUBLE_EQ(t.recall, (sa.recall + sb.recall) / 2);
      EXPECT_DOUBLE_EQ(t.f1, (sa.f1 + sb.f1) / 2);
      EXPECT_DOUBLE_EQ(t.iou, (sa.iou + sb.iou) / 2);
    } else {
      Scores s = ScoreCounts(sum);
      EXPECT_DOUBLE_EQ(t.precision, s.precision);
      EXPECT_DOUBLE_EQ(t.f1, s.f1);
    }
  }
  // The numbers, by hand. DG sums: TP 5, FP 6, FN 2.
  SequenceScores dg(Protocol::kDG);
  dg.Add(CountFrame(Protocol::kDG, a.pred, a.gt, nullptr));
  dg.Add(CountFrame(Protocol::kDG, b.pred, b.gt, nullptr));
  EXPECT_DOUBLE_EQ(dg.Total().precision, 5.0 / 11);
  EXPECT_DOUBLE_EQ(dg.Total().recall, 5.0 / 7);
  EXPECT_DOUBLE_EQ(dg.Total().iou, 5.0 / 13);
  // PP means: precision (3/4 + 2/3) / 2, recall (3/5 + 1) / 2, F1 (2/3 + 4/5) / 2.
  SequenceScores pp(Protocol::kPP);
  pp.Add(CountFrame(Protocol::kPP, a.pred, a.gt, nullptr));
  pp.Add(CountFrame(Protocol::kPP, b.pred, b.gt, nullptr));
  EXPECT_DOUBLE_EQ(pp.Total().precision, (3.0 / 4 + 2.0 / 3) / 2);
  EXPECT_DOUBLE_EQ(pp.Total().recall, (3.0 / 5 + 1.0) / 2);
  EXPECT_DOUBLE_EQ(pp.Total().f1, (2.0 / 3 + 4.0 / 5) / 2);
  EXPECT_DOUBLE_EQ(pp.Total().iou, (3.0 / 6 + 2.0 / 3) / 2);
  // GG sums: TP 5, FP 2, FN 2.
  SequenceScores gg(Protocol::kGG);
  gg.Add(CountFrame(Protocol::kGG, a.pred, a.gt, nullptr));
  gg.Add(CountFrame(Protocol::kGG, b.pred, b.gt, nullptr));
  EXPECT_DOUBLE_EQ(gg.Total().precision, 5.0 / 7);
  EXPECT_DOUBLE_EQ(gg.Total().recall, 5.0 / 7);
  // No frames: zeros.
  EXPECT_EQ(SequenceScores(Protocol::kPW).Total().f1, 0.0);
}

TEST(EvalMetrics, ProtocolNames) {
  for (Protocol p : AllProtocols()) EXPECT_EQ(ParseProtocol(ProtocolName(p)), p);
  EXPECT_STREQ(ProtocolName(Protocol::kDG), "dg");
  EXPECT_STREQ(ProtocolName(Protocol::kPW), "pw");
  try {
    ParseProtocol("kitti");
    FAIL() << "accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("unknown protocol 'kitti' (known: dg, pp, pw, gg)"),
              std::string::npos);
  }
  EXPECT_TRUE(AveragesPerFrame(Protocol::kPP));
  EXPECT_TRUE(AveragesPerFrame(Protocol::kPW));
  EXPECT_FALSE(AveragesPerFrame(Protocol::kDG));
  EXPECT_FALSE(AveragesPerFrame(Protocol::kGG));
}

TEST(EvalMetrics, Errors) {
  Labels pred = {1, 0};
  std::vector<uint32_t> gt = {40};
  EXPECT_THROW(CountFrame(Protocol::kDG, pred, gt, nullptr), std::invalid_argument);
  gt.push_back(40);
  EXPECT_THROW(CountFrame(Protocol::kPW, pred, gt, nullptr), std::invalid_argument);
  std::vector<float> z = {-1.7f};
  EXPECT_THROW(CountFrame(Protocol::kPW, pred, gt, &z), std::invalid_argument);
}

// The message of the std::invalid_argument `f` throws; "" when it throws none.
template <typename F>
std::string ErrorOf(F f) {
  try {
    f();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

TEST(EvalOntology, ClassNames) {
  EXPECT_STREQ(ClassName(Ontology::kSemanticKitti, 0), "unlabeled");
  EXPECT_STREQ(ClassName(Ontology::kSemanticKitti, 1), "outlier");
  EXPECT_STREQ(ClassName(Ontology::kSemanticKitti, 40), "road");
  EXPECT_STREQ(ClassName(Ontology::kSemanticKitti, 44), "parking");
  EXPECT_STREQ(ClassName(Ontology::kSemanticKitti, 49), "other-ground");
  EXPECT_STREQ(ClassName(Ontology::kSemanticKitti, 60), "lane-marking");
  EXPECT_STREQ(ClassName(Ontology::kSemanticKitti, 72), "terrain");
  EXPECT_STREQ(ClassName(Ontology::kSemanticKitti, 259), "moving-other-vehicle");
  EXPECT_STREQ(ClassName(Ontology::kSemanticKitti, 2), "unknown");
  EXPECT_STREQ(ClassName(Ontology::kRellis3d, 0), "void");
  EXPECT_STREQ(ClassName(Ontology::kRellis3d, 3), "grass");
  EXPECT_STREQ(ClassName(Ontology::kRellis3d, 23), "concrete");
  EXPECT_STREQ(ClassName(Ontology::kRellis3d, 34), "rubble");
  EXPECT_STREQ(ClassName(Ontology::kRellis3d, 40), "unknown");  // road is SemanticKITTI's
  // Every id RELLIS-3D defines (and only those) has a name.
  const std::vector<uint32_t> rellis = {0,  1,  3,  4,  5,  6,  7,  8,  9,  10,
                                        12, 15, 17, 18, 19, 23, 27, 31, 33, 34};
  for (uint32_t c = 0; c <= 40; ++c) {
    const bool defined = std::find(rellis.begin(), rellis.end(), c) != rellis.end();
    EXPECT_EQ(std::string(ClassName(Ontology::kRellis3d, c)) != "unknown", defined) << c;
  }
}

TEST(EvalOntology, Names) {
  for (Ontology o : {Ontology::kSemanticKitti, Ontology::kRellis3d})
    EXPECT_EQ(ParseOntology(OntologyName(o)), o);
  EXPECT_EQ(ErrorOf([] { ParseOntology("kitti"); }),
            "unknown ontology 'kitti' (known: semantickitti, rellis3d)");
  EXPECT_EQ(ClassOf(40u | (7u << 16)), 40u);
}

TEST(EvalOntology, RellisGroundClasses) {
  for (uint32_t c = 0; c < 40; ++c) {
    const bool ground = c == 1 || c == 3 || c == 6 || c == 10 || c == 23 || c == 31 || c == 33;
    EXPECT_EQ(IsRellisGroundClass(c), ground) << c;
  }
}

TEST(EvalMetrics, RellisSkipsVoid) {
  // void (pred 1, pred 0), grass TP, dirt FN, tree FP, bush TN, concrete TP, person TN, mud TP,
  // asphalt FN.
  Labels pred = {1, 0, 1, 0, 1, 0, 1, 0, 1, 0};
  std::vector<uint32_t> gt = {0, 0, 3, 1, 4, 19, 23, 17, 33, 10};
  EXPECT_EQ(CountFrame(Protocol::kRellis, pred, gt, nullptr), Make(3, 1, 2, 2, 2));
  EXPECT_EQ(ScorePoint(Protocol::kRellis, 0, true, 0), Outcome::kIgnored);
  EXPECT_EQ(ScorePoint(Protocol::kRellis, 6, true, 0), Outcome::kTP);    // water
  EXPECT_EQ(ScorePoint(Protocol::kRellis, 31, false, 0), Outcome::kFN);  // puddle
  EXPECT_EQ(ScorePoint(Protocol::kRellis, 40, true, 0), Outcome::kFP);   // not RELLIS ground
  EXPECT_EQ(ScorePoint(Protocol::kDG, 3, true, 0), Outcome::kFP);        // not KITTI ground
  EXPECT_FALSE(AveragesPerFrame(Protocol::kRellis));
}

TEST(EvalMetrics, ProtocolsPerOntology) {
  EXPECT_EQ(ProtocolsOf(Ontology::kSemanticKitti), AllProtocols());
  EXPECT_EQ(ProtocolsOf(Ontology::kRellis3d), std::vector<Protocol>{Protocol::kRellis});
  EXPECT_EQ(ParseProtocol("rellis", Ontology::kRellis3d), Protocol::kRellis);
  EXPECT_EQ(OntologyOf(Protocol::kRellis), Ontology::kRellis3d);
  for (Protocol p : AllProtocols()) EXPECT_EQ(OntologyOf(p), Ontology::kSemanticKitti);
  EXPECT_EQ(ErrorOf([] { ParseProtocol("pw", Ontology::kRellis3d); }),
            "protocol 'pw' scores semantickitti labels, not rellis3d ones (known for rellis3d: "
            "rellis)");
  EXPECT_EQ(ErrorOf([] { ParseProtocol("rellis"); }),
            "protocol 'rellis' scores rellis3d labels, not semantickitti ones (known for "
            "semantickitti: dg, pp, pw, gg)");
  EXPECT_EQ(ErrorOf([] { ParseProtocol("x", Ontology::kRellis3d); }),
            "unknown protocol 'x' (known: rellis)");
}

TEST(EvalByClass, MixedFrameByHand) {
  Frame f = Mixed();
  ClassBreakdown b({Protocol::kDG, Protocol::kPP, Protocol::kPW});
  b.Add(f.pred, f.gt, &f.z);
  b.Add(f.pred, f.gt, &f.z);  // twice: everything doubles
  const auto& c = b.classes();
  ASSERT_EQ(c.size(), 8u);  // 0 1 10 40 48 50 70 72 (the road with an instance is 40)
  const ClassTally& road = c.at(40);
  EXPECT_EQ(road.points, 6u);
  EXPECT_EQ(road.predicted_ground, 4u);
  EXPECT_EQ(road.counts[0], Make(4, 0, 2, 0, 0));
  const ClassTally& veg = c.at(70);  // points 6, 7, 8, 13
  EXPECT_EQ(veg.points, 8u);
  EXPECT_EQ(veg.predicted_ground, 6u);
  EXPECT_EQ(veg.counts[0], Make(0, 6, 0, 2, 0));      // DG: all non-ground
  EXPECT_EQ(veg.counts[1], Make(0, 0, 0, 0, 8));      // PP: not scored
  EXPECT_EQ(veg.counts[2], Make(2, 4, 2, 0, 0));      // PW: 6, 7 low; 8, 13 not below -1.2975
  EXPECT_EQ(c.at(0).counts[2], Make(0, 0, 0, 0, 2));  // PW: predicted unlabeled left out
  EXPECT_EQ(c.at(10).counts[1], Make(0, 2, 0, 2, 0));
  EXPECT_EQ(c.at(48).predicted_ground, 0u);
}

TEST(EvalByClass, SumsToTheFrameCounts) {
  Frame f = Mixed();
  ClassBreakdown b(AllProtocols());
  b.Add(f.pred, f.gt, &f.z);
  for (size_t k = 0; k < AllProtocols().size(); ++k) {
    const Protocol p = AllProtocols()[k];
    SCOPED_TRACE(ProtocolName(p));
    Counts sum;
    uint64_t points = 0;
    for (const auto& entry : b.classes()) {
      sum += entry.second.counts[k];
      points += entry.second.points;
    }
    EXPECT_EQ(sum, CountFrame(p, f.pred, f.gt, &f.z));
    EXPECT_EQ(points, f.gt.size());
  }
}

TEST(EvalByRange, Bands) {
  EXPECT_EQ(kRangeBands, 7u);
  const char* names[] = {"0-5", "5-10", "10-20", "20-30", "30-40", "40-60", "60+"};
  for (size_t b = 0; b < kRangeBands; ++b) EXPECT_EQ(RangeBandName(b), names[b]);
  EXPECT_EQ(RangeBand(0.0f), 0u);
  EXPECT_EQ(RangeBand(4.999f), 0u);
  EXPECT_EQ(RangeBand(5.0f), 1u);  // an edge opens the band above it
  EXPECT_EQ(RangeBand(19.99f), 2u);
  EXPECT_EQ(RangeBand(20.0f), 3u);
  EXPECT_EQ(RangeBand(39.9f), 4u);
  EXPECT_EQ(RangeBand(40.0f), 5u);
  EXPECT_EQ(RangeBand(59.99f), 5u);
  EXPECT_EQ(RangeBand(60.0f), 6u);
  EXPECT_EQ(RangeBand(1e30f), 6u);
  EXPECT_EQ(RangeBand(std::numeric_limits<float>::infinity()), 6u);
  EXPECT_EQ(RangeBand(std::nanf("")), 6u);
}

TEST(EvalByRange, CountsPerBandByHand) {
  Cloud cloud;
  Labels pred;
  std::vector<uint32_t> gt;
  auto add = [&](float x, float y, float z, uint32_t label, uint8_t p) {
    cloud.Push(x, y, z, 0);
    gt.push_back(label);
    pred.push_back(p);
  };
  add(1, 0, -1.7f, 40, 1);      // 0-5    TP
  add(3, 4, -1.7f, 40, 0);      // 5-10   FN (3-4-5: exactly 5 m)
  add(0, 9.99f, -1.0f, 10, 1);  // 5-10   FP
  add(10, 0, -1.7f, 40, 1);     // 10-20  TP
  add(0, -25, -1.7f, 48, 0);    // 20-30  FN
  add(-30, 0, 1.0f, 50, 1);     // 30-40  FP
  add(45, 0, -1.7f, 72, 1);     // 40-60  TP
  add(59.9f, 0, -1.7f, 70, 1);  // 40-60  DG FP, GG ignored, PW TP (low vegetation)
  add(60, 0, -1.7f, 40, 0);     // 60+    FN
  add(100, 0, -1.7f, 0, 0);     // 60+    DG TN, GG ignored
  RangeBreakdown b({Protocol::kDG, Protocol::kGG, Protocol::kPW});
  b.Add(cloud, pred, gt);
  const auto& t = b.bands();
  const std::vector<uint64_t> points = {1, 2, 1, 1, 1, 2, 2};
  for (size_t i = 0; i < kRangeBands; ++i) EXPECT_EQ(t[i].points, points[i]) << i;
  EXPECT_EQ(t[0].counts[0], Make(1, 0, 0, 0, 0));
  EXPECT_EQ(t[1].counts[0], Make(0, 1, 1, 0, 0));
  EXPECT_EQ(t[2].counts[0], Make(1, 0, 0, 0, 0));
  EXPECT_EQ(t[3].counts[0], Make(0, 0, 1, 0, 0));
  EXPECT_EQ(t[4].counts[0], Make(0, 1, 0, 0, 0));
  EXPECT_EQ(t[5].counts[0], Make(1, 1, 0, 0, 0));
  EXPECT_EQ(t[5].counts[1], Make(1, 0, 0, 0, 1));
  EXPECT_EQ(t[5].counts[2], Make(2, 0, 0, 0, 0));
  EXPECT_EQ(t[6].counts[0], Make(0, 0, 1, 1, 0));
  EXPECT_EQ(t[6].counts[1], Make(0, 0, 1, 0, 1));
  // Summed over the bands: the frame's counts (PW's z taken from the cloud).
  std::vector<float> z;
  for (size_t i = 0; i < cloud.size(); ++i) z.push_back(cloud.z(i));
  for (size_t k = 0; k < b.protocols().size(); ++k) {
    Counts sum;
    for (const RangeTally& band : t) sum += band.counts[k];
    EXPECT_EQ(sum, CountFrame(b.protocols()[k], pred, gt, &z)) << ProtocolName(b.protocols()[k]);
  }
}

TEST(EvalBreakdown, Errors) {
  Labels pred = {1, 0};
  std::vector<uint32_t> gt = {40, 40};
  ClassBreakdown by_class({Protocol::kPW});
  EXPECT_NE(ErrorOf([&] { by_class.Add(pred, gt, nullptr); }).find("needs each point's z"),
            std::string::npos);
  Cloud cloud;
  cloud.Push(1, 0, 0, 0);
  RangeBreakdown by_range({Protocol::kDG});
  EXPECT_EQ(ErrorOf([&] { by_range.Add(cloud, pred, gt); }),
            "scan has 1 points but the ground truth 2");
  EXPECT_TRUE(by_class.classes().empty());  // nothing half-added
  EXPECT_EQ(by_range.bands()[0].points, 0u);
}

}  // namespace
}  // namespace lpir
