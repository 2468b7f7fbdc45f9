// Hand-made images for the fuse tests (tests/fuse_test.cpp checks the reference's verdicts on
// them, tests/fuse_vk_test.cpp the kernel's bytes against the reference's): an image builder, and
// columns whose occluders sit exactly on the veto's, the step spare's and the passed-under rule's
// thresholds or one ulp beside them, each with the verdict reference_cpu/fuse.cpp must give.
// Bounds are computed as the reference rounds them (tests build with -ffp-contract=off).
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "reference_cpu/exact.h"
#include "reference_cpu/frame.h"
#include "reference_cpu/params.h"

namespace lpir::test {

// An image of `beams` x `width` pixels, every pixel empty; Measure() gives a pixel a point.
struct FuseImage {
  Params p = DefaultParams();
  Frame f;
  FuseImage(uint32_t width, uint32_t beams) {
    p.width = width;
    p.beams = beams;
    const size_t pixels = size_t(width) * beams;
    f.pixel_class.assign(pixels, kPixEmpty);
    f.pixel_point.assign(pixels, kNone);
    f.pixel_filled.assign(pixels, 0u);
    f.f_range.assign(pixels, 0.0f);
    f.f_height.assign(pixels, 0.0f);
  }
  uint32_t Pix(uint32_t v, uint32_t u) const { return v * p.width + u; }
  // A measured pixel with its own point and that point's coarse label.
  void Measure(uint32_t v, uint32_t u, uint32_t cls, bool coarse_ground, float range = 10.0f,
               float height = -1.7f) {
    const uint32_t pix = Pix(v, u);
    f.pixel_class[pix] = cls;
    f.pixel_point[pix] = f.n++;
    f.coarse.push_back(coarse_ground ? 1u : 0u);
    f.pixel_filled[pix] = 1u;
    f.f_range[pix] = range;
    f.f_height[pix] = height;
  }
  // A hole-filled pixel: features and a class, no point.
  void Fill(uint32_t v, uint32_t u, uint32_t cls, float range = 10.0f, float height = -1.7f) {
    const uint32_t pix = Pix(v, u);
    f.pixel_class[pix] = cls;
    f.pixel_filled[pix] = 2u;
    f.f_range[pix] = range;
    f.f_height[pix] = height;
  }
  uint32_t Fused(uint32_t v, uint32_t u) const { return f.pixel_fused[Pix(v, u)]; }
};

// An image of threshold columns: on row `row`, each (column, vetoed) of `expect` must come out
// kPixVetoed when vetoed, else kPixGround; `spares` whether some column is spared at all.
struct FuseVerdicts {
  FuseVerdicts(std::string name, uint32_t width, uint32_t beams, uint32_t v, bool spare = true)
      : what(std::move(name)), im(width, beams), row(v), spares(spare) {}
  std::string what;
  FuseImage im;
  uint32_t row;
  std::vector<std::pair<uint32_t, bool>> expect;
  bool spares;
};

// The veto's reach of a pixel of class `cls` at range r, and its top at height z.
inline float VetoReach(const Params& p, float r, uint32_t cls) {
  const float rr = r * r;
  const float grade = p.occ_grade * rr;
  const float near = r + p.occ_margin;
  const float any = near + grade;
  return cls == kPixGround ? std::min(any, r + p.occ_front) : any;
}
inline float VetoTop(const Params& p, float z) { return z + p.occ_rise; }

// Every column: a seed at row v (coarse ground, class ground or unknown: their reaches differ),
// one occluder candidate k rows above, measured or hole filled; the candidate's range and height
// on the reach and top or one ulp either side; and the same values on an empty pixel above.
inline std::vector<FuseVerdicts> VetoThresholdImages() {
  std::vector<FuseVerdicts> out;
  for (uint32_t cls : {kPixGround, kPixUnknown})
    for (uint32_t occ_rows : {1u, 2u, 3u}) {
      const uint32_t v = 5;
      FuseVerdicts c("veto thresholds, class " + std::to_string(cls) + ", occ_rows " +
                         std::to_string(occ_rows),
                     64, 8, v);
      FuseImage& im = c.im;
      im.p.occ_rows = occ_rows;
      uint32_t u = 0;
      for (float r : {2.5f, 10.0f, 15.0f, 37.3f, 80.0f}) {
        const float z = -1.7f + 0.01f * float(u);
        const float reach = VetoReach(im.p, r, cls), top = VetoTop(im.p, z);
        const float below_reach = std::nextafter(reach, 0.0f);
        const float above_top = std::nextafter(top, 1e9f);
        const struct {
          float range, height;
          bool veto;
        } cands[] = {{below_reach, above_top, true},
                     {reach, above_top, false},  // range == reach: not nearer
                     {below_reach, top, false},  // height == top: not higher
                     {std::nextafter(reach, 1e9f), above_top, false},
                     {below_reach, std::nextafter(top, -1e9f), false},
                     {reach, top, false}};
        for (const auto& cand : cands)
          for (uint32_t k = 1; k <= occ_rows + 1 && u < im.p.width; ++k, ++u) {
            im.Measure(v, u, cls, true, r, z);
            if (k % 2)
              im.Measure(v - k, u, kPixNonGround, false, cand.range, cand.height);
            else
              im.Fill(v - k, u, kPixUnknown, cand.range, cand.height);  // filled occluders count
            c.expect.push_back({u, cand.veto && k <= occ_rows});
          }
        if (u < im.p.width) {  // the same values on an empty pixel above (filled 0) never veto
          im.Measure(v, u, cls, true, r, z);
          im.f.f_range[im.Pix(v - 1, u)] = below_reach;
          im.f.f_height[im.Pix(v - 1, u)] = above_top;
          c.expect.push_back({u++, false});
        }
      }
      out.push_back(std::move(c));
    }
  return out;
}

// The step spare's bound for a pixel above at range ra, and its far limit.
inline float StepBound(const Params& p, float r, float z, float ra) {
  const float base = exact::Ftz0(z + p.occ_step);
  const float d = exact::Ftz0(ra - r);
  const float beyond = d > 0.0f ? d : 0.0f;
  return exact::Ftz0(base + exact::Ftz0(p.occ_step_grade * beyond));
}
inline float StepFar(const Params& p, float r) { return exact::Ftz0(r + p.occ_step_reach); }

// Every column: a seed at row v under an occluder one row up (nearer, higher than the veto's top,
// not above the step's base), a landing two rows up (class ground, farther) and a candidate three
// rows up whose range and height sit on the step's bounds or one ulp beside them. A candidate
// beyond occ_step_rows is not looked at: a steep one then spares.
inline std::vector<FuseVerdicts> StepSpareThresholdImages() {
  std::vector<FuseVerdicts> out;
  for (uint32_t cls : {kPixGround, kPixUnknown})
    for (uint32_t step_rows : {2u, 3u, 10u}) {
      const uint32_t v = 6;
      FuseVerdicts c("step thresholds, class " + std::to_string(cls) + ", step rows " +
                         std::to_string(step_rows),
                     64, 8, v);
      FuseImage& im = c.im;
      im.p.occ_step_rows = step_rows;
      im.p.occ_pass = 1000.0f;  // the occluder is nearer: no pixel here is passed under
      uint32_t u = 0;
      for (float r : {5.0f, 10.0f, 37.3f}) {
        const float z = -1.7f + 0.01f * float(u);
        const float far = StepFar(im.p, r), far_in = std::nextafter(far, 0.0f);
        const float ra = r + 1.5f, bound = StepBound(im.p, r, z, ra);
        const struct {
          float landing_range, range, height;
          bool veto;
        } cands[] = {
            {r + 1.0f, ra, bound, false},                                // at the bound: not steep
            {r + 1.0f, ra, std::nextafter(bound, 1e9f), true},           // steep
            {r + 1.0f, far, z + 2.0f, false},                            // at far: not looked at
            {r + 1.0f, far_in, z + 2.0f, true},                          // inside far: steep
            {r, ra, z, true},                                            // landing at d == 0: none
            {far, ra, z, true},                                          // landing at far: none
            {std::nextafter(r, 1e9f), ra, z, false},                     // landing one ulp beyond
            {far_in, r - 1.0f, StepBound(im.p, r, z, r - 1.0f), false},  // nearer, at base
        };
        for (const auto& cand : cands) {
          im.Measure(v, u, cls, true, r, z);
          im.Measure(v - 1, u, kPixNonGround, false, r - 0.5f, z + 0.1f);
          im.Measure(v - 2, u, kPixGround, true, cand.landing_range, z);
          im.Measure(v - 3, u, kPixNonGround, false, cand.range, cand.height);
          const bool landing = cand.landing_range > r && cand.landing_range < far;
          c.expect.push_back({u++, step_rows >= 3 ? cand.veto : !landing});
        }
      }
      out.push_back(std::move(c));
    }
  return out;
}

// The ray's clearance at the occluder's range, Ftz0(z * Ftz0(ra - r)), and the farthest range
// ra < r at which it still reaches Ftz0(occ_pass * r) (one ulp farther it no longer does, or ra
// is the pixel's own range).
inline float Clearance(float r, float z, float ra) { return exact::Ftz0(z * exact::Ftz0(ra - r)); }
inline float PassedAt(const Params& p, float r, float z) {
  const float pass = exact::Ftz0(p.occ_pass * r);
  float ra = std::min(r + pass / z, std::nextafter(r, 0.0f));
  while (!(Clearance(r, z, ra) >= pass)) ra = std::nextafter(ra, -1e9f);
  for (float up = std::nextafter(ra, 1e9f); up < r && Clearance(r, z, up) >= pass;
       up = std::nextafter(ra, 1e9f))
    ra = up;
  return ra;
}

// Every column: a seed at row v under one occluder a row up (higher than the veto's top) whose
// range gives the ray a clearance at occ_pass or one ulp short of it; only a pixel of class
// ground is spared, and only by an occluder nearer than itself.
inline std::vector<FuseVerdicts> PassedUnderThresholdImages() {
  std::vector<FuseVerdicts> out;
  for (float occ_pass : {0.15f, 0.0f})
    for (uint32_t cls : {kPixGround, kPixUnknown}) {
      const uint32_t v = 3;
      FuseVerdicts c(
          "passed under, class " + std::to_string(cls) + ", occ_pass " + std::to_string(occ_pass),
          64, 4, v, cls == kPixGround);
      FuseImage& im = c.im;
      im.p.occ_pass = occ_pass;
      uint32_t u = 0;
      for (float r : {5.0f, 10.0f, 15.0f, 37.3f}) {
        const float z = -1.7f + 0.01f * float(u);
        const float at = PassedAt(im.p, r, z);
        const struct {
          float range;
          bool passed;
        } cands[] = {{at, true},
                     {std::nextafter(at, 1e9f), false},
                     {r, false},  // d == 0: not nearer
                     {std::nextafter(r, 0.0f), occ_pass == 0.0f},
                     {0.5f * at, true}};
        for (const auto& cand : cands) {
          im.Measure(v, u, cls, true, r, z);
          im.Measure(v - 1, u, kPixNonGround, false, cand.range, z + 1.0f);
          c.expect.push_back({u++, !(cand.passed && cls == kPixGround)});
        }
      }
      out.push_back(std::move(c));
    }
  return out;
}

}  // namespace lpir::test
