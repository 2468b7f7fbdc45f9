// Attribution of wrong points to the stage that decided them (host/eval/attribution.h): each rule
// on a hand-made one-pixel frame, then a simulated street where every wrong point gets a decider
// of its kind (FN or FP) and every pixel the veto decided is one fuse without the veto would have
// left ground or unknown.
#include "host/eval/attribution.h"

#include <gtest/gtest.h>

#include <set>
#include <string>

#include "apps/sim/scene.h"
#include "host/io/sensor_profile.h"
#include "reference_cpu/pipeline.h"
#include "reference_cpu/stages.h"

namespace lpir {
namespace {

// One point on one pixel; the fields each rule reads.
struct OnePixel {
  uint8_t why = kWhyNonGround, label = 0;
  uint32_t cls = kPixUnknown, fused = kPixUnknown, grown = kPixUnknown, final_label = kPixNonGround;
  bool has_point = true, coarse = false;

  Frame Make() const {
    Frame f;
    f.n = 1;
    f.label = {label};
    f.label_why = {PackLabelWhy(label, why)};
    f.point_pixel = {0};
    f.pixel_point = {has_point ? 0u : kNone};
    f.coarse = {coarse ? 1u : 0u};
    f.pixel_class = {cls};
    f.pixel_fused = {fused};
    f.pixel_grown = {grown};
    f.pixel_label = {final_label};
    return f;
  }
};

Decider Of(const OnePixel& o, bool truth) { return Attribute(o.Make(), 0, truth); }

TEST(Attribution, EachRuleOnOnePixel) {
  OnePixel invalid;
  invalid.why = kWhyInvalid;
  EXPECT_EQ(Of(invalid, true), Decider::kPrepareInvalid);
  OnePixel noise;
  noise.why = kWhyNoise;
  EXPECT_EQ(Of(noise, true), Decider::kPrepareNoise);

  OnePixel lost;  // ground pixel, the point gated out
  lost.final_label = kPixGround;
  lost.grown = kPixGround;
  EXPECT_EQ(Of(lost, true), Decider::kBackProject);

  OnePixel small;  // grown, then dropped with its component
  small.grown = kPixGround;
  EXPECT_EQ(Of(small, true), Decider::kComponent);

  OnePixel vetoed;
  vetoed.cls = kPixGround;
  vetoed.coarse = true;
  vetoed.fused = vetoed.grown = kPixVetoed;
  EXPECT_EQ(Of(vetoed, true), Decider::kVeto);
  OnePixel both_ng = vetoed;  // class and coarse label said non-ground: nothing to veto
  both_ng.cls = kPixNonGround;
  both_ng.coarse = false;
  both_ng.fused = both_ng.grown = kPixNonGround;
  EXPECT_EQ(Of(both_ng, true), Decider::kClassAndCoarse);

  OnePixel unknown;  // unknown after fuse, never reached
  unknown.cls = kPixNonGround;
  unknown.coarse = true;
  EXPECT_EQ(Of(unknown, true), Decider::kGrowClassNg);
  unknown.cls = kPixBank;  // a bank on the coarse ground: the class objected
  EXPECT_EQ(Of(unknown, true), Decider::kGrowClassNg);
  unknown.cls = kPixGround;
  unknown.coarse = false;
  unknown.fused = unknown.grown = kPixUnknownOff;
  EXPECT_EQ(Of(unknown, true), Decider::kGrowCoarseNg);
  unknown.cls = kPixBank;  // a bank off the coarse ground, not climbed to
  EXPECT_EQ(Of(unknown, true), Decider::kGrowCoarseNg);
  unknown.has_point = false;
  EXPECT_EQ(Of(unknown, true), Decider::kGrowHole);

  OnePixel seed;  // false ground
  seed.label = 1;
  seed.why = kWhyGround;
  seed.fused = seed.grown = seed.final_label = kPixGround;
  seed.cls = kPixGround;
  EXPECT_EQ(Of(seed, false), Decider::kSeedBoth);
  seed.cls = kPixUnknown;
  EXPECT_EQ(Of(seed, false), Decider::kSeedCoarse);
  seed.fused = kPixUnknown;
  EXPECT_EQ(Of(seed, false), Decider::kGrow);
  OnePixel lifted = seed;  // vetoed, then lifted by the ground around it
  lifted.fused = lifted.grown = kPixVetoed;
  EXPECT_EQ(Of(lifted, false), Decider::kLift);
}

TEST(Attribution, NamesAreDistinct) {
  std::set<std::string> names;
  for (int d = 0; d < kDeciderCount; ++d) names.insert(DeciderName(static_cast<Decider>(d)));
  EXPECT_EQ(names.size(), size_t(kDeciderCount));
}

TEST(Attribution, SimulatedStreetEveryWrongPointHasADeciderOfItsKind) {
  const SensorProfile sensor = LoadSensorProfile("hdl64e", LPIR_SENSORS_DIR);
  SimOptions o;
  o.seed = 1;
  const SimScan scan = Simulate(sensor, o);
  const Params p = ParamsForSensor(sensor);
  Frame f;
  RunReference(scan.cloud, p, MakeTables(sensor, p), f);
  Params no_veto = p;
  no_veto.occ_rows = 0;
  Frame g = f;
  Fuse(no_veto, g);

  const std::set<Decider> fn_kinds = {
      Decider::kPrepareInvalid, Decider::kPrepareNoise, Decider::kBackProject,
      Decider::kComponent,      Decider::kVeto,         Decider::kClassAndCoarse,
      Decider::kGrowClassNg,    Decider::kGrowCoarseNg, Decider::kGrowHole};
  const std::set<Decider> fp_kinds = {Decider::kSeedBoth, Decider::kSeedCoarse, Decider::kGrow,
                                      Decider::kLift};
  size_t fn = 0, fp = 0, vetoed = 0;
  for (uint32_t i = 0; i < f.n; ++i) {
    const bool truth = IsSimGroundClass(scan.labels[i]), pred = f.label[i] != 0;
    if (truth == pred) continue;
    const Decider d = Attribute(f, i, truth);
    if (truth) {
      ++fn;
      EXPECT_TRUE(fn_kinds.count(d)) << "point " << i << ": " << DeciderName(d);
    } else {
      ++fp;
      EXPECT_TRUE(fp_kinds.count(d)) << "point " << i << ": " << DeciderName(d);
    }
    if (d == Decider::kVeto || d == Decider::kLift) {
      vetoed += d == Decider::kVeto;
      const uint32_t pix = f.point_pixel[i];
      EXPECT_EQ(f.pixel_fused[pix], kPixVetoed);
      EXPECT_NE(g.pixel_fused[pix], kPixNonGround) << "the veto took nothing at pixel " << pix;
    }
  }
  std::printf("seed 1: FN %zu (veto %zu), FP %zu\n", fn, vetoed, fp);
  EXPECT_GT(fn, 0u);
  EXPECT_GT(vetoed, 0u);
}

}  // namespace
}  // namespace lpir
