// The virtual LiDAR: casts the rays of a SensorProfile (a spinning sensor's beams x azimuth steps,
// or a non-repetitive sensor's firing pattern, scan_pattern.h) into a SimScene with analytic
// intersections (planes, boxes, cylinders, ellipsoids), adds range noise, surface roughness and
// reflection noise, and writes the points in firing order with their classes. Primitives are
// culled per azimuth sector (a spinning sensor's column) by the azimuth interval of their
// footprint and per ray by a bounding sphere (docs/decisions/apps.md).
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "apps/sim/scan_pattern.h"
#include "apps/sim/scene.h"
#include "apps/sim/sim_random.h"

namespace lpir {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kEps = 1e-9;
constexpr double kReflectionNoiseChance = 6e-4;  // per road/sidewalk hit within 40 m
constexpr double kReflectionNoiseMaxRange = 40.0;

// Whether a world-frame direction lies within 1e-4 rad of straight up or down (its azimuth,
// and so its sector, is undefined).
bool NearVertical(const double dw[3]) { return dw[0] * dw[0] + dw[1] * dw[1] < 1e-8; }

double WrapAngle(double a) {
  while (a > kPi) a -= 2 * kPi;
  while (a <= -kPi) a += 2 * kPi;
  return a;
}

struct Ray {
  double o[3];  // origin, world frame
  double d[3];  // unit direction, world frame
};

// Entry distance of the ray into an axis-aligned box, kInf when it misses (or starts inside).
double HitBox(const Ray& r, const double lo[3], const double hi[3]) {
  double t_near = -kInf, t_far = kInf;
  for (int a = 0; a < 3; ++a) {
    if (std::abs(r.d[a]) < kEps) {
      if (r.o[a] < lo[a] || r.o[a] > hi[a]) return kInf;
      continue;
    }
    double t0 = (lo[a] - r.o[a]) / r.d[a];
    double t1 = (hi[a] - r.o[a]) / r.d[a];
    if (t0 > t1) std::swap(t0, t1);
    t_near = std::max(t_near, t0);
    t_far = std::min(t_far, t1);
  }
  if (t_near > t_far || t_near <= kEps) return kInf;
  return t_near;
}

// Finite cylinder along `axis` inscribed in the box lo..hi (the other two extents give the
// centre and the radius; they are equal for wheels, poles and trunks).
double HitCylinder(const Ray& r, const double lo[3], const double hi[3], int axis) {
  const int i = 0, j = axis == 2 ? 1 : 2;
  const double ci = 0.5 * (lo[i] + hi[i]), cj = 0.5 * (lo[j] + hi[j]);
  const double rad = 0.5 * (hi[i] - lo[i]);
  const double oi = r.o[i] - ci, oj = r.o[j] - cj;
  double best = kInf;
  const double a = r.d[i] * r.d[i] + r.d[j] * r.d[j];
  if (a > kEps) {
    const double b = oi * r.d[i] + oj * r.d[j];
    const double c = oi * oi + oj * oj - rad * rad;
    const double disc = b * b - a * c;
    if (disc >= 0) {
      const double t = (-b - std::sqrt(disc)) / a;
      const double h = r.o[axis] + t * r.d[axis];
      if (t > kEps && h >= lo[axis] && h <= hi[axis]) best = t;
    }
  }
  if (std::abs(r.d[axis]) > kEps) {  // the two caps
    for (double cap : {lo[axis], hi[axis]}) {
      const double t = (cap - r.o[axis]) / r.d[axis];
      if (t <= kEps || t >= best) continue;
      const double pi = oi + t * r.d[i], pj = oj + t * r.d[j];
      if (pi * pi + pj * pj <= rad * rad) best = t;
    }
  }
  return best;
}

// Axis-aligned ellipsoid inscribed in lo..hi; `unit` receives the hit in the unit sphere's frame.
double HitEllipsoid(const Ray& r, const double lo[3], const double hi[3], double unit[3]) {
  double o[3], d[3];
  for (int a = 0; a < 3; ++a) {
    const double c = 0.5 * (lo[a] + hi[a]), rad = 0.5 * (hi[a] - lo[a]);
    o[a] = (r.o[a] - c) / rad;
    d[a] = r.d[a] / rad;
  }
  const double a = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
  const double b = o[0] * d[0] + o[1] * d[1] + o[2] * d[2];
  const double c = o[0] * o[0] + o[1] * o[1] + o[2] * o[2] - 1.0;
  const double disc = b * b - a * c;
  if (disc < 0 || c < 0) return kInf;  // miss, or the sensor inside
  const double t = (-b - std::sqrt(disc)) / a;
  if (t <= kEps) return kInf;
  for (int k = 0; k < 3; ++k) unit[k] = o[k] + t * d[k];
  return t;
}

// Height patch z = z0 + slope (x - lo.x) over its rectangle; `denom` receives dz/dt of the ray
// relative to the surface (for roughness).
double HitPatch(const Ray& r, const SimPrimitive& p, double* denom) {
  const double den = r.d[2] - p.slope * r.d[0];
  if (std::abs(den) < kEps) return kInf;
  const double t = (p.z0 + p.slope * (r.o[0] - p.lo[0]) - r.o[2]) / den;
  if (t <= kEps) return kInf;
  const double x = r.o[0] + t * r.d[0], y = r.o[1] + t * r.d[1];
  if (x < p.lo[0] || x > p.hi[0] || y < p.lo[1] || y > p.hi[1]) return kInf;
  *denom = den;
  return t;
}

double HitCurb(const Ray& r, const SimPrimitive& p) {
  if (std::abs(r.d[1]) < kEps) return kInf;
  const double t = (p.lo[1] - r.o[1]) / r.d[1];
  if (t <= kEps) return kInf;
  const double x = r.o[0] + t * r.d[0];
  if (x < p.lo[0] || x > p.hi[0]) return kInf;
  const double bottom = p.z0 + p.slope * (x - p.lo[0]);
  const double z = r.o[2] + t * r.d[2];
  if (z < bottom || z > bottom + p.height) return kInf;
  return t;
}

// Per primitive: a bounding sphere and the azimuth interval of its footprint seen from the
// sensor (x = y = 0), as centre and half width; `always` when the footprint holds the origin.
struct Culling {
  double c[3];
  double radius;
  double az_mid, az_half;
  bool always;
};

Culling MakeCulling(const SimPrimitive& p) {
  Culling k;
  double r2 = 0;
  for (int a = 0; a < 3; ++a) {
    k.c[a] = 0.5 * (p.lo[a] + p.hi[a]);
    const double h = 0.5 * (p.hi[a] - p.lo[a]);
    r2 += h * h;
  }
  // Margin for roughness and bumps, which move points along the ray after the hit.
  k.radius = std::sqrt(r2) + 0.5;
  const double margin = 0.05;
  k.always = p.lo[0] - margin <= 0 && p.hi[0] + margin >= 0 && p.lo[1] - margin <= 0 &&
             p.hi[1] + margin >= 0;
  k.az_mid = 0, k.az_half = kPi;
  if (!k.always) {
    const double mid = std::atan2(k.c[1], k.c[0]);
    double lo = kInf, hi = -kInf;
    for (double x : {p.lo[0] - margin, p.hi[0] + margin}) {
      for (double y : {p.lo[1] - margin, p.hi[1] + margin}) {
        const double da = WrapAngle(std::atan2(y, x) - mid);
        lo = std::min(lo, da);
        hi = std::max(hi, da);
      }
    }
    k.az_mid = WrapAngle(mid + 0.5 * (lo + hi));
    k.az_half = 0.5 * (hi - lo);
  }
  return k;
}

void Validate(const SensorProfile& s, const SimOptions& o) {
  auto fail = [](const std::string& what) { throw std::invalid_argument("simulate: " + what); };
  if (s.beams == 0 || s.width == 0) fail("the sensor profile needs beams > 0 and width > 0");
  if (s.elevation_deg.size() != s.beams)
    fail("the elevation table has " + std::to_string(s.elevation_deg.size()) + " entries for " +
         std::to_string(s.beams) + " beams");
  for (float e : s.elevation_deg)
    if (!std::isfinite(e) || std::abs(e) >= 90.0f) fail("beam elevation out of range");
  if (!(s.sensor_height > 0.0f) || !std::isfinite(s.sensor_height))
    fail("sensor_height must be > 0");
  if (!(s.min_range >= 0.0f) || !(s.max_range > s.min_range) || !std::isfinite(s.max_range))
    fail("range limits must satisfy 0 <= min_range < max_range");
  if (!(std::abs(o.pitch_deg) <= 30.0f) || !(std::abs(o.roll_deg) <= 30.0f))
    fail("pitch and roll must lie within [-30, 30] degrees");
  if (!(o.range_noise_m >= 0.0f) || !(o.range_noise_m <= 1.0f))
    fail("range noise must lie within [0, 1] m");
  if (o.emit_rings && s.pattern != ScanPattern::kSpinning)
    fail("the " + s.name + " profile scans a non-repetitive pattern: its points have no rings");
}

// The nearest surface a ray meets: its distance along the ray, the primitive (-1: none), and
// what the surface effects need (a height patch's dz/dt, an ellipsoid's unit-sphere point).
struct Hit {
  double t = kInf;
  int prim = -1;
  double denom = 0;
  double unit[3] = {0, 0, 0};
};

// Casts rays into a scene among the primitives culled by azimuth sector, and writes each hit as
// a point with its class: the surface effects (lane paint, roughness, reflection noise, leaf
// bumps), the range noise, the range limits. The noise stream is consumed in emission order.
class Caster {
 public:
  Caster(const SensorProfile& sensor, const SimOptions& options, SimScan* scan)
      : scene_(scan->scene),
        options_(options),
        scan_(scan),
        rng_(options.seed ^ 0xA5F00D17u),
        min_r2_(static_cast<double>(sensor.min_range) * sensor.min_range),
        max_r2_(static_cast<double>(sensor.max_range) * sensor.max_range) {
    cull_.reserve(scene_.primitives.size());
    for (const SimPrimitive& p : scene_.primitives) cull_.push_back(MakeCulling(p));
  }

  // Adds a sector: the primitives whose footprint's azimuth interval (world frame) meets
  // mid -+ half (radians), or all of them when `all`. Sectors are numbered from 0 as added.
  void AddSector(bool all, double mid, double half) {
    for (size_t i = 0; i < cull_.size(); ++i) {
      const Culling& k = cull_[i];
      if (all || k.always || std::abs(WrapAngle(k.az_mid - mid)) <= k.az_half + half)
        cand_.push_back(static_cast<uint32_t>(i));
    }
    cand_begin_.push_back(static_cast<uint32_t>(cand_.size()));
  }

  // Casts the ray from the sensor frame's point (0, 0, oz) along the sensor-frame unit direction
  // `ds` against sector `sector`'s primitives and emits its point, if any, with `ring` (when
  // rings are emitted).
  void Cast(double oz, const double ds[3], size_t sector, int32_t ring) {
    Ray ray;
    const double origin_sensor[3] = {0.0, 0.0, oz};
    scene_.SensorToWorld(origin_sensor, ray.o);
    scene_.DirectionToWorld(ds, ray.d);
    const Hit hit = Nearest(ray, cand_begin_[sector], cand_begin_[sector + 1]);
    if (hit.prim >= 0) Emit(ray, ds, oz, hit, ring);  // no hit: sky, no point
  }

 private:
  Hit Nearest(const Ray& ray, uint32_t first, uint32_t last) const {
    Hit best;
    for (uint32_t ci = first; ci < last; ++ci) {
      const uint32_t i = cand_[ci];
      const Culling& k = cull_[i];
      const double oc[3] = {k.c[0] - ray.o[0], k.c[1] - ray.o[1], k.c[2] - ray.o[2]};
      const double b = oc[0] * ray.d[0] + oc[1] * ray.d[1] + oc[2] * ray.d[2];
      if (b + k.radius < 0 || b - k.radius > best.t) continue;
      if (oc[0] * oc[0] + oc[1] * oc[1] + oc[2] * oc[2] - b * b > k.radius * k.radius) continue;
      const SimPrimitive& p = scene_.primitives[i];
      double t = kInf, denom = 0, unit[3] = {0, 0, 0};
      switch (p.shape) {
        case SimShape::kHeightPatch:
          t = HitPatch(ray, p, &denom);
          break;
        case SimShape::kCurbFace:
          t = HitCurb(ray, p);
          break;
        case SimShape::kBox:
          t = HitBox(ray, p.lo, p.hi);
          break;
        case SimShape::kCylinderY:
          t = HitCylinder(ray, p.lo, p.hi, 1);
          break;
        case SimShape::kCylinderZ:
          t = HitCylinder(ray, p.lo, p.hi, 2);
          break;
        case SimShape::kEllipsoid:
          t = HitEllipsoid(ray, p.lo, p.hi, unit);
          break;
      }
      if (t < best.t) {
        best.t = t, best.prim = static_cast<int>(i), best.denom = denom;
        if (p.shape == SimShape::kEllipsoid) std::copy(unit, unit + 3, best.unit);
      }
    }
    return best;
  }

  void Emit(const Ray& ray, const double ds[3], double oz, const Hit& hit, int32_t ring) {
    const SimPrimitive& p = scene_.primitives[hit.prim];
    double t = hit.t;
    const double x = ray.o[0] + t * ray.d[0], y = ray.o[1] + t * ray.d[1];
    uint32_t label = p.label;
    double refl = p.reflectivity + p.reflectivity_jitter * (2.0 * rng_.Uniform() - 1.0);
    if (p.shape == SimShape::kHeightPatch) {
      if (p.lane_markings && scene_.IsLaneMarking(x, y)) {
        label = SkClass::kLaneMarking;
        refl = 0.55 + 0.15 * rng_.Uniform();
      }
      if (p.roughness > 0) {  // raise the surface by dz: the ray meets it dz / denom earlier
        const double dz = p.roughness * (2.0 * rng_.Uniform() - 1.0);
        t += std::max(-0.5, std::min(0.5, dz / hit.denom));
      }
      const bool paved = p.label == SkClass::kRoad || p.label == SkClass::kSidewalk;
      const bool near = x * x + y * y < kReflectionNoiseMaxRange * kReflectionNoiseMaxRange;
      if (options_.reflection_noise && paved && near && ray.d[2] < -0.01 &&
          rng_.Chance(kReflectionNoiseChance)) {
        // Multipath: the return arrives late, as if from 0.5-2 m under the surface.
        const double depth = rng_.Uniform(0.5, 2.0);
        t += depth / -ray.d[2];
        label = SkClass::kOutlier;
        refl = 0.05 * rng_.Uniform();
      }
    } else if (p.shape == SimShape::kEllipsoid) {  // leaves: bumps and a little scatter
      const double* q = hit.unit;
      const double bumps = std::sin(5.0 * q[0] + p.bump_phase[0]) *
                           std::sin(4.0 * q[1] + p.bump_phase[1]) *
                           std::sin(3.0 * q[2] + p.bump_phase[2]);
      t += p.bump * (bumps + 0.4 * (2.0 * rng_.Uniform() - 1.0));
    }
    if (options_.range_noise_m > 0) t += options_.range_noise_m * rng_.Normal();

    const double px = t * ds[0], py = t * ds[1], pz = oz + t * ds[2];
    const double r2 = px * px + py * py;
    if (t <= 0 || r2 < min_r2_ || r2 > max_r2_) return;
    refl = std::max(0.0, std::min(1.0, refl));
    scan_->cloud.Push(static_cast<float>(px), static_cast<float>(py), static_cast<float>(pz),
                      static_cast<float>(refl));
    scan_->labels.push_back(label);
    if (options_.emit_rings) scan_->cloud.ring.push_back(ring);
  }

  const SimScene& scene_;
  const SimOptions& options_;
  SimScan* scan_;
  SimRandom rng_;  // the per-point noise stream, separate from the scene's
  double min_r2_, max_r2_;
  std::vector<Culling> cull_;
  std::vector<uint32_t> cand_begin_{0}, cand_;  // sector s: cand_[cand_begin_[s]..[s + 1])
};

// A spinning sensor: beams x width rays, beam by beam from the top, a sector per column.
void CastSpinning(const SensorProfile& sensor, Caster& caster, SimScan* scan) {
  const SimScene& scene = scan->scene;
  const unsigned rows = sensor.beams, cols = sensor.width;

  // Ray directions in the sensor frame, from the tables (eq. 1's azimuth, the profile's beams).
  std::vector<double> cos_el(rows), sin_el(rows), cos_az(cols), sin_az(cols);
  for (unsigned v = 0; v < rows; ++v) {
    const double e = sensor.elevation_deg[v] * (kPi / 180.0);
    cos_el[v] = std::cos(e), sin_el[v] = std::sin(e);
  }
  for (unsigned u = 0; u < cols; ++u) {
    const double a = kPi - 2.0 * kPi * (u + 0.5) / cols;
    cos_az[u] = std::cos(a), sin_az[u] = std::sin(a);
  }
  auto sensor_dir = [&](unsigned v, unsigned u, double d[3]) {
    d[0] = cos_el[v] * cos_az[u];
    d[1] = cos_el[v] * sin_az[u];
    d[2] = sin_el[v];
  };

  // Column u's sector: the azimuth interval its rays sweep in the world frame (the tilt spreads
  // it a little).
  for (unsigned u = 0; u < cols; ++u) {
    double ref = 0, lo = kInf, hi = -kInf;
    bool all = false;
    for (unsigned v = 0; v < rows; ++v) {
      double ds[3], dw[3];
      sensor_dir(v, u, ds);
      scene.DirectionToWorld(ds, dw);
      if (NearVertical(dw)) {
        all = true;
        break;
      }
      const double az = std::atan2(dw[1], dw[0]);
      if (v == 0) ref = az;
      const double da = WrapAngle(az - ref);
      lo = std::min(lo, da);
      hi = std::max(hi, da);
    }
    caster.AddSector(all, WrapAngle(ref + 0.5 * (lo + hi)), 0.5 * (hi - lo) + 1e-6);
  }

  scan->cloud.xyzi.reserve(static_cast<size_t>(rows) * cols * 4 * 3 / 4);
  scan->labels.reserve(static_cast<size_t>(rows) * cols * 3 / 4);
  for (unsigned v = 0; v < rows; ++v) {
    // Each beam fires from its laser's origin, beam_origin_z above the sensor frame's origin (the
    // HDL-64E's blocks sit 0.1-0.2 m above its centre), as the profile says the real one does.
    const double oz = sensor.beam_origin_z.empty() ? 0.0 : sensor.beam_origin_z[v];
    const int32_t ring = static_cast<int32_t>(sensor.ring_zero_is_top ? v : rows - 1 - v);
    for (unsigned u = 0; u < cols; ++u) {
      double ds[3];
      sensor_dir(v, u, ds);
      caster.Cast(oz, ds, u, ring);
    }
  }
}

// A non-repetitive sensor: the frame's rays in firing order (scan_pattern.h) from the sensor
// frame's origin, a sector per 1 / width of a turn of world azimuth and one of every primitive
// for the rays within 1e-4 rad of straight up or down.
void CastPattern(const SensorProfile& sensor, uint32_t seed, Caster& caster, SimScan* scan) {
  const std::vector<std::array<double, 3>> rays = PatternRays(sensor, seed);
  const unsigned cols = sensor.width;
  const double step = 2.0 * kPi / cols;
  for (unsigned s = 0; s < cols; ++s)
    caster.AddSector(false, -kPi + (s + 0.5) * step, 0.5 * step + 1e-6);
  caster.AddSector(true, 0.0, 0.0);

  scan->cloud.xyzi.reserve(rays.size() * 4);
  scan->labels.reserve(rays.size());
  for (const std::array<double, 3>& ds : rays) {
    double dw[3];
    scan->scene.DirectionToWorld(ds.data(), dw);
    size_t sector = cols;
    if (!NearVertical(dw)) {
      const double turn = (std::atan2(dw[1], dw[0]) + kPi) / (2.0 * kPi);
      sector = std::min<size_t>(cols - 1, static_cast<size_t>(turn * cols));
    }
    caster.Cast(0.0, ds.data(), sector, -1);
  }
}

}  // namespace

SimScan Simulate(const SensorProfile& sensor, const SimOptions& options) {
  Validate(sensor, options);
  SimScan scan;
  scan.scene = BuildScene(options, sensor.sensor_height);
  Caster caster(sensor, options, &scan);
  if (sensor.pattern == ScanPattern::kSpinning) {
    CastSpinning(sensor, caster, &scan);
  } else {
    CastPattern(sensor, options.seed, caster, &scan);
  }
  return scan;
}

}  // namespace lpir
