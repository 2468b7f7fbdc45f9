// Label images for the grow tests (tests/grow_test.cpp checks the reference on them,
// tests/grow_vk_test.cpp the kernel's bytes against the reference's): an image builder, random
// images of every class mix, and adversarial ones (serpentine corridors of unknown pixels,
// checkerboards, one huge unknown region, chains across the column wrap, images one row or one
// or two columns wide, columns climbed up the bank's grade).
#pragma once
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "reference_cpu/frame.h"
#include "reference_cpu/params.h"
#include "reference_cpu/stages.h"

namespace lpir::test {

// A beams x width image of `fill` pixels, 10 m away and 1.7 m down, columns one revolution.
struct GrowImage {
  Params p = DefaultParams();
  Frame f;
  GrowImage(uint32_t width, uint32_t beams, uint32_t fill = kPixEmpty) {
    p.width = width;
    p.beams = beams;
    p.column_arc = float(2.0 * 3.14159265358979323846 / double(width));
    const size_t pixels = size_t(width) * beams;
    f.pixel_fused.assign(pixels, fill);
    f.f_range.assign(pixels, 10.0f);
    f.f_height.assign(pixels, -1.7f);
  }
  uint32_t Pix(uint32_t v, uint32_t u) const { return v * p.width + u; }
  void Set(uint32_t v, uint32_t u, uint32_t cls, float height, float range = 10.0f) {
    const uint32_t pix = Pix(v, u);
    f.pixel_fused[pix] = cls;
    f.f_height[pix] = height;
    f.f_range[pix] = range;
  }
  void Run() { Grow(p, f); }
  uint32_t Grown(uint32_t v, uint32_t u) const { return f.pixel_grown[Pix(v, u)]; }
};

// The rule that keeps a small component of seeds, drawn: off (share above 1), at its default, or
// at shares whose product with a size lands on a whole number of seeds (0.5, 1) or next to one
// (0.8, 0.75).
inline void SeedShare(std::mt19937& rng, Params& p) {
  const float shares[] = {2.0f, 0.8f, 0.5f, 1.0f, 0.75f};
  p.comp_seed_share = shares[rng() % 5];
  p.comp_seed_min = rng() % 8;
}

// A random label image, min_width..max_width x min_beams..max_beams: heights spread over about
// twice a typical step allowance, so that many steps sit near it, and ranges falling row by row;
// seeds are rare, so growth has to travel. With `every_rule`, min_component (0-15) and the seed
// share are drawn and vetoed pixels and a class the stages never give (7) appear too; without,
// min_component is 0 and the classes are those fuse gives but the veto.
struct GrowSizes {
  uint32_t min_width, max_width, min_beams, max_beams;
};
inline GrowImage RandomGrowImage(uint32_t seed, float grow_grade, const GrowSizes& sizes,
                                 bool every_rule) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<uint32_t> width_pick(sizes.min_width, sizes.max_width),
      beams_pick(sizes.min_beams, sizes.max_beams);
  GrowImage im(width_pick(rng), beams_pick(rng));
  im.p.min_component = every_rule ? rng() % 16 : 0;
  im.p.grow_grade = grow_grade;
  if (every_rule) SeedShare(rng, im.p);
  // ground, non-ground, unknown, empty, vetoed, 7, unknown off the coarse ground (a class of
  // weight 0 never comes, and the others come as they would without it)
  std::discrete_distribution<int> cls =
      every_rule ? std::discrete_distribution<int>({3, 2, 8, 1, 2, 0.2, 4})
                 : std::discrete_distribution<int>({3, 2, 8, 1, 0, 0, 4});
  std::uniform_real_distribution<float> uni(0.0f, 1.0f);
  const uint32_t classes[7] = {kPixGround, kPixNonGround, kPixUnknown, kPixEmpty, kPixVetoed,
                               7u,         kPixUnknownOff};
  const float typical = im.p.grow_dz + grow_grade * (1.0f + 20.0f * im.p.column_arc);
  for (uint32_t v = 0; v < im.p.beams; ++v)
    for (uint32_t u = 0; u < im.p.width; ++u) {
      const uint32_t pix = im.Pix(v, u);
      im.f.pixel_fused[pix] = classes[cls(rng)];
      im.f.f_height[pix] = -1.7f + 2.0f * typical * uni(rng);
      im.f.f_range[pix] = 30.0f - 1.5f * float(v) + 2.0f * uni(rng);
    }
  for (uint32_t& c : im.f.pixel_fused)
    if (c == kPixGround && uni(rng) < 0.7f) c = kPixUnknown;
  return im;
}

// A random image with its own class mix: mostly unknown (long growing chains), mostly ground, or
// mostly non-ground (small scattered components).
inline GrowImage MixedGrowImage(std::mt19937& rng, uint32_t max_width, uint32_t max_beams) {
  std::uniform_int_distribution<uint32_t> width_pick(1, max_width), beams_pick(1, max_beams);
  GrowImage im(width_pick(rng), beams_pick(rng));
  std::uniform_real_distribution<float> uni(0.0f, 1.0f);
  im.p.min_component = rng() % 40;
  im.p.grow_grade = uni(rng) < 0.5f ? 0.0f : 0.05f;
  SeedShare(rng, im.p);
  const double weights[7] = {1.0 + 10 * uni(rng), 1.0 + 10 * uni(rng), 1.0 + 20 * uni(rng),
                             5 * uni(rng),        5 * uni(rng),        0.3 * uni(rng),
                             10 * uni(rng)};
  std::discrete_distribution<int> cls(weights, weights + 7);
  const uint32_t classes[7] = {kPixGround, kPixNonGround, kPixUnknown, kPixEmpty, kPixVetoed,
                               7u,         kPixUnknownOff};
  const float allowed = im.p.grow_dz + im.p.grow_grade * (1.0f + 20.0f * im.p.column_arc);
  const float step_share = 0.5f + 1.5f * uni(rng);  // heights spread over this many allowances
  for (uint32_t pix = 0; pix < im.p.width * im.p.beams; ++pix) {
    const uint32_t v = pix / im.p.width;
    im.f.pixel_fused[pix] = classes[cls(rng)];
    im.f.f_height[pix] = -1.7f + step_share * allowed * uni(rng);
    im.f.f_range[pix] = 30.0f - 0.4f * float(v) + 2.0f * uni(rng);
  }
  return im;
}

// An adversarial image, unseeded.
struct Adversary {
  std::string name;
  GrowImage im;
};

inline GrowImage Blank(uint32_t width, uint32_t beams, uint32_t fill) {
  GrowImage im(width, beams);
  for (uint32_t& c : im.f.pixel_fused) c = fill;
  return im;
}

// A serpentine corridor of unknown pixels, `wide` pixels across, through non-ground pixels: rows
// of corridor joined at alternate ends. `vertical` turns it by 90 degrees.
inline GrowImage Serpentine(uint32_t width, uint32_t beams, uint32_t wide, bool vertical) {
  GrowImage im = Blank(width, beams, kPixNonGround);
  const uint32_t period = 2 * wide;
  const uint32_t lanes = vertical ? width : beams, length = vertical ? beams : width;
  for (uint32_t a = 0; a < lanes; ++a)
    for (uint32_t b = 0; b < length; ++b) {
      const uint32_t lane = a / period, in = a % period;
      const bool corridor = in < wide || (in >= wide && (lane % 2 ? b < wide : b + wide >= length));
      if (!corridor) continue;
      const uint32_t v = vertical ? b : a, u = vertical ? a : b;
      im.f.pixel_fused[v * width + u] = kPixUnknown;
    }
  return im;
}

inline std::vector<Adversary> Adversaries() {
  std::vector<Adversary> out;
  out.push_back({"serpentine 1 wide", Serpentine(512, 64, 1, false)});
  out.push_back({"serpentine 2 wide", Serpentine(500, 61, 2, false)});
  out.push_back({"serpentine vertical", Serpentine(257, 128, 1, true)});
  out.push_back({"huge unknown region", Blank(1024, 64, kPixUnknown)});
  {
    GrowImage im = Blank(1000, 64, kPixUnknown);  // no seed at all: nothing grows
    out.push_back({"huge unknown region, no seed", im});
  }
  for (uint32_t fill : {kPixGround, kPixNonGround}) {  // checkerboards: diagonal-only contact
    GrowImage im = Blank(333, 40, kPixUnknown);
    for (uint32_t pix = 0; pix < im.f.pixel_fused.size(); ++pix)
      if (((pix / 333) + (pix % 333)) % 2) im.f.pixel_fused[pix] = fill;
    out.push_back({fill == kPixGround ? "checkerboard ground" : "checkerboard non-ground", im});
  }
  {
    GrowImage im = Blank(64, 32, kPixNonGround);  // a spiral of unknown pixels
    uint32_t top = 0, left = 0, bottom = 31, right = 63;
    while (top <= bottom && left <= right) {
      for (uint32_t u = left; u <= right; ++u) im.f.pixel_fused[top * 64 + u] = kPixUnknown;
      for (uint32_t v = top; v <= bottom; ++v) im.f.pixel_fused[v * 64 + right] = kPixUnknown;
      if (bottom < top + 2 || right < left + 2) break;
      top += 2, left += 2, bottom -= 2, right -= 2;
      if (left >= 2) im.f.pixel_fused[(top - 1) * 64 + left - 2] = kPixUnknown;
    }
    out.push_back({"spiral", im});
  }
  {
    GrowImage im = Blank(300, 8, kPixNonGround);  // a chain that crosses the column wrap each row
    for (uint32_t v = 0; v < 8; ++v) {
      im.f.pixel_fused[v * 300 + 299] = kPixUnknown;
      im.f.pixel_fused[v * 300 + 0] = kPixUnknown;
      if (v + 1 < 8) im.f.pixel_fused[(v + 1) * 300 + 1] = kPixUnknown;  // diagonal step down
    }
    out.push_back({"chain across the wrap", im});
  }
  out.push_back({"one row", Blank(2048, 1, kPixUnknown)});
  out.push_back({"one column", Blank(1, 1000, kPixUnknown)});
  out.push_back({"two columns", Blank(2, 700, kPixUnknown)});
  {
    GrowImage im = Blank(2048, 32, kPixUnknown);  // a huge region cut by walls no step may cross
    for (uint32_t pix = 0; pix < im.f.pixel_fused.size(); ++pix)
      if (pix % 2048 % 97 == 0) im.f.f_height[pix] = 5.0f;
    out.push_back({"huge region behind walls", im});
  }
  {
    // Columns off the coarse ground climbed only by the bank's step: each row up lies 0.5 m
    // farther and 0.15 m higher; neighbouring columns 1 m apart in height, so no other step
    // joins them (a chain of 200 union-find links up one column).
    GrowImage im = Blank(64, 200, kPixUnknownOff);
    for (uint32_t v = 0; v < 200; ++v)
      for (uint32_t u = 0; u < 64; ++u) {
        im.f.f_range[v * 64 + u] = 5.0f + 0.5f * float(199 - v);
        im.f.f_height[v * 64 + u] = -1.7f + 0.15f * float(199 - v) + float(u % 2);
      }
    out.push_back({"banks climbed up their columns", im});
  }
  return out;
}

// Every adversary with min_component 5, seeded (one ground pixel) at the first and, as a second
// image, at the last pixel of its unknown region (a component's lowest pixel is then its seed or
// far from it); the "no seed" one once, unseeded. `unknown`: the region's pixels.
struct SeededAdversary {
  std::string name;
  GrowImage im;
  std::vector<uint32_t> unknown;
  bool seeded;
};
inline std::vector<SeededAdversary> SeededAdversaries() {
  std::vector<SeededAdversary> out;
  for (Adversary& a : Adversaries()) {
    a.im.p.min_component = 5;
    std::vector<uint32_t> unknown;
    for (uint32_t pix = 0; pix < a.im.f.pixel_fused.size(); ++pix)
      if (a.im.f.pixel_fused[pix] == kPixUnknown || a.im.f.pixel_fused[pix] == kPixUnknownOff)
        unknown.push_back(pix);
    const bool seeded = a.name.find("no seed") == std::string::npos;
    for (int end = 0; end < (seeded ? 2 : 1); ++end) {
      SeededAdversary s{a.name + (end ? ", seed last" : ", seed first"), a.im, unknown, seeded};
      if (seeded && !unknown.empty())
        s.im.f.pixel_fused[end ? unknown.back() : unknown.front()] = kPixGround;
      out.push_back(std::move(s));
    }
  }
  return out;
}

}  // namespace lpir::test
