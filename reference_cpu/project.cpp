// project (paper eq. 1) without trigonometry.
// In: cloud xyz (+ ring), flags, r2; tables.column_dir, tables.beam_bound.
// Out: point_pixel (v * width + u, kNone when invalid), pixel_key, pixel_point.
// Column: u = #{k in 1..width-1 : phi_k > theta}, theta = atan2(y, x), phi_k = pi - 2 pi k / width:
//   u = floor((1 - theta / pi) / 2 * width) of eq. 1, found by walking from a polynomial guess with
//   the exact angle order AngleBelow (half-plane, then the sign of one cross product x*s - y*c).
//   The answer is unique, so the reference first tries the previous point's column plus its last
//   step (scans come in sweep order) and walks only when it is not there: same column, less work.
//   Rows likewise: the previous point's row is checked first (RowNear), then the search.
// Row: with ring indices, v = ring (ring_zero_is_top) or beams - 1 - ring; else v = #{b :
//   beam_bound[b] * r2 > h * |h|}, h = z - beam_origin[b], i.e. the beams whose lower boundary
//   lies above the point's elevation seen from that boundary's laser origin, compared as tan^2
//   with signs, by binary search. (The HDL-64E's lasers sit 0.1-0.2 m above its centre: seen
//   from the centre, a point 10 m away reads up to 1 degree high, three rows.)
// Winner: the smallest r2 on the pixel (ordered key, atomic min), then the lowest point index
//   among those with that key. Noise points get a pixel but never compete (they are not ground
//   evidence); invalid points get neither.
// Threads (reference_cpu/threads.h): pieces of points find their pixels, then pieces of rows take
// their pixels' winners, each reading every point in index order.
#include <algorithm>
#include <cmath>
#include <vector>

#include "reference_cpu/exact.h"
#include "reference_cpu/stages.h"

namespace lpir {
namespace {

// True when the point's angle is in the upper half-plane (0, pi].
inline bool Upper(float x, float y) { return y > 0.0f || (y == 0.0f && x < 0.0f); }

// atan2(py, px) < atan2(by, bx), exactly as the shader evaluates it; up and bup are the two
// angles' half-planes (Upper).
inline bool AngleBelow(float px, float py, bool up, float bx, float by, bool bup) {
  if (up != bup) return bup;
  const float a = px * by, b = py * bx;
  return a - b > 0.0f;
}
inline bool AngleBelow(float px, float py, float bx, float by) {
  return AngleBelow(px, py, Upper(px, py), bx, by, Upper(bx, by));
}

}  // namespace

// A first guess of the column from a polynomial arctangent (|error| < 2e-5 rad, a hundredth of a
// column). Only a starting point: ColumnOf walks from it to the exact answer.
inline int32_t GuessColumn(float x, float y, uint32_t width) {
  const float ax = std::fabs(x), ay = std::fabs(y);
  const float lo = std::min(ax, ay), hi = std::max(ax, ay);
  const float t = exact::Div(lo, hi);
  const float t2 = t * t;
  float a = 0.0208351f * t2;
  a = (a - 0.0851330f) * t2;
  a = (a + 0.1801410f) * t2;
  a = (a - 0.3302995f) * t2;
  a = (a + 0.9998660f) * t;  // atan(lo / hi) in [0, pi/4]
  if (ay > ax) a = 1.57079637f - a;
  if (x < 0.0f) a = 3.14159274f - a;
  if (y < 0.0f) a = -a;                                  // theta = atan2(y, x)
  const float turns = (3.14159274f - a) * 0.159154937f;  // (pi - theta) / (2 pi), eq. 1
  return int32_t(exact::FloorToInt(turns * float(width)));
}

uint32_t ColumnOf(float x, float y, const float* dir, uint32_t width) {
  // The largest k in [0, width-1] with phi_k > theta (k = 0 stands for "none": u = 0). The
  // predicate is a prefix over k: adjacent boundaries are 2 pi / width apart (3e-3 rad at 2048
  // columns) and the sign of the rounded cross product is exact beyond 2.4e-7 rad, so it changes
  // once. Its change point is therefore unique, and a walk from any guess finds the same column
  // as a binary search would, on every device.
  int32_t u = std::min(std::max(GuessColumn(x, y, width), 0), int32_t(width) - 1);
  while (u + 1 < int32_t(width) && AngleBelow(x, y, dir[2 * (u + 1)], dir[2 * (u + 1) + 1])) ++u;
  while (u > 0 && !AngleBelow(x, y, dir[2 * u], dir[2 * u + 1])) --u;
  return uint32_t(u);
}

namespace {

// The column boundaries and their half-planes, read by Below.
struct Columns {
  const float* dir;
  const uint8_t* upper;  // Upper of each boundary direction
  uint32_t width;
};

// P(k) of ColumnOf for k in [0, width]: true for k = 0 ("none"), false for k = width. up is
// Upper(x, y).
inline bool Below(float x, float y, bool up, const Columns& c, uint32_t k) {
  if (k == 0) return true;
  if (k >= c.width) return false;
  return AngleBelow(x, y, up, c.dir[2 * k], c.dir[2 * k + 1], c.upper[k] != 0);
}

// ColumnOf when a likely column is known (the previous point's column plus its last step: scans
// come in sweep order). The column is the unique k with P(k) and not P(k + 1), so confirming that
// at the guess or a neighbour gives exactly ColumnOf's answer; otherwise ColumnOf decides. An
// interior guess (both boundaries in the table, nearly every point) is confirmed first without
// Below's end cases.
inline uint32_t ColumnNear(float x, float y, const Columns& c, uint32_t guess) {
  const bool up = Upper(x, y);
  if ((guess >= 1) & (guess + 1 < c.width)) {
    const float* d = c.dir + 2 * guess;
    const bool at = AngleBelow(x, y, up, d[0], d[1], c.upper[guess] != 0);
    const bool next = AngleBelow(x, y, up, d[2], d[3], c.upper[guess + 1] != 0);
    if (at & !next) return guess;
  }
  const bool at = Below(x, y, up, c, guess), next = Below(x, y, up, c, guess + 1);
  if (at && !next) return guess;
  if (next) {  // the column lies after the guess
    if (!Below(x, y, up, c, guess + 2)) return guess + 1;
  } else if (Below(x, y, up, c, guess - 1)) {  // before it (guess > 0 here: P(0) holds)
    return guess - 1;
  }
  return ColumnOf(x, y, c.dir, c.width);
}

}  // namespace

namespace {

// True when boundary b lies above the point: tan^2 of the boundary (signed) times r2 exceeds
// h * |h|, h the point's height above that boundary's laser origin.
inline bool BoundAbove(float z, float r2, const float* bound, const float* origin, uint32_t b) {
  const float h = z - origin[b];
  const float hh = h * std::fabs(h);  // only its sign differs from h * (h < 0 ? -h : h), at h = 0
  const float s = bound[b] * r2;
  return s > hh;
}

}  // namespace

uint32_t RowOf(float z, float r2, const float* bound, const float* origin, uint32_t beams) {
  // Count of boundaries above the point; boundaries descend, so the predicate is a prefix.
  uint32_t lo = 0, hi = beams - 1;
  while (lo < hi) {
    const uint32_t mid = (lo + hi + 1) >> 1;  // boundary index mid - 1
    if (BoundAbove(z, r2, bound, origin, mid - 1))
      lo = mid;
    else
      hi = mid - 1;
  }
  return lo;
}

namespace {

// RowOf when the previous point's row is known: the row is the unique v with boundary v - 1 above
// the point and boundary v not (boundary -1 counts as above, boundary beams - 1 as not), so
// checking the hint gives exactly RowOf's answer when it is right; otherwise RowOf decides. An
// interior hint (nearly every point) is checked first without the end cases.
inline uint32_t RowNear(float z, float r2, const float* bound, const float* origin, uint32_t beams,
                        uint32_t hint) {
  if ((hint >= 1) & (hint + 1 < beams)) {
    const bool above_before = BoundAbove(z, r2, bound, origin, hint - 1);
    const bool above_here = BoundAbove(z, r2, bound, origin, hint);
    if (above_before & !above_here) return hint;
  }
  const bool above_before = hint == 0 || BoundAbove(z, r2, bound, origin, hint - 1);
  const bool above_here = hint + 1 < beams && BoundAbove(z, r2, bound, origin, hint);
  if (above_before && !above_here) return hint;
  return RowOf(z, r2, bound, origin, beams);
}

}  // namespace

namespace {

// The pixel of every point of `points` (point_pixel: v * width + u, kNone when invalid). Each
// search starts from the previous valid point's row and column in the range (the range's first
// from row 0, column 0): the answer is unique, so where a range starts changes no byte. With
// `winners` (the points are all of them, in one range), each non-noise point also takes its pixel
// where its key is smaller than the pixel's so far (pixel_key and pixel_point start at kNone):
// Winners' pass, while the point is at hand.
void PointPixels(const Cloud& cloud, const Params& p, const Tables& t, const Columns columns,
                 Frame& f, Range points, bool winners) {
  const uint32_t width = p.width, beams = p.beams;
  const bool ring_zero_is_top = p.ring_zero_is_top;
  const int32_t* __restrict rings = cloud.ring.data();
  const float* __restrict xyzi = cloud.xyzi.data();
  const uint32_t* __restrict flags = f.flags.data();
  const float* __restrict r2 = f.r2.data();
  uint32_t* __restrict point_pixel = f.point_pixel.data();
  const float* bound = t.beam_bound.data();
  const float* origin = t.beam_origin.data();
  const bool has_ring = !cloud.ring.empty();
  uint32_t* __restrict pixel_key = f.pixel_key.data();
  uint32_t* __restrict pixel_point = f.pixel_point.data();
  uint32_t column = 0, row = 0;  // the previous valid point's
  int32_t step = 0;              // and its column step, clamped to -1..1
  for (uint32_t i = points.begin; i < points.end; ++i) {
    if (!(flags[i] & kPointValid)) {
      point_pixel[i] = kNone;
      continue;
    }
    const float x = xyzi[4 * i], y = xyzi[4 * i + 1], z = xyzi[4 * i + 2];
    const int32_t guess = std::min(std::max(int32_t(column) + step, 0), int32_t(width) - 1);
    const uint32_t u = ColumnNear(x, y, columns, uint32_t(guess));
    step = u > column ? 1 : (u < column ? -1 : 0);
    column = u;
    uint32_t v;
    if (has_ring) {
      const uint32_t ring = uint32_t(rings[i]);
      v = ring_zero_is_top ? ring : beams - 1 - ring;
    } else {
      v = RowNear(z, r2[i], bound, origin, beams, row);
      row = v;
    }
    const uint32_t pix = v * width + u;
    point_pixel[i] = pix;
    if (winners && !(flags[i] & kPointNoise)) {
      const uint32_t key = exact::Key(r2[i]);
      if (key < pixel_key[pix]) pixel_key[pix] = key, pixel_point[pix] = i;
    }
  }
}

// The winner of every pixel in `pixels` (pixel_key, pixel_point; kNone where no point competes).
// The points are read in index order, so the first to reach a pixel's smallest key is the lowest
// index with it: one pass instead of the shader's atomic min, then its tie-break.
void Winners(const Frame& f, Range pixels, uint32_t* __restrict pixel_key,
             uint32_t* __restrict pixel_point) {
  const uint32_t n = f.n, first = pixels.begin, count = pixels.end - pixels.begin;
  const uint32_t* __restrict flags = f.flags.data();
  const float* __restrict r2 = f.r2.data();
  const uint32_t* __restrict point_pixel = f.point_pixel.data();
  std::fill(pixel_key + first, pixel_key + pixels.end, kNone);
  std::fill(pixel_point + first, pixel_point + pixels.end, kNone);
  for (uint32_t i = 0; i < n; ++i) {
    const uint32_t pix = point_pixel[i];
    // Outside the range (kNone, an invalid point's, included), or noise: not competing here.
    if (pix - first >= count || (flags[i] & kPointNoise)) continue;
    const uint32_t key = exact::Key(r2[i]);
    if (key < pixel_key[pix]) pixel_key[pix] = key, pixel_point[pix] = i;
  }
}

}  // namespace

// Pieces of points find their pixels; then pieces of rows take their pixels' winners from every
// point (each reads all the pixels, but writes only its own). One piece does both in one pass.
void Project(const Cloud& cloud, const Params& p, const Tables& t, Frame& f, Threads threads) {
  const uint32_t n = f.n, pixels = p.width * p.beams, width = p.width;
  f.point_pixel.resize(n);
  f.pixel_key.resize(pixels);
  f.pixel_point.resize(pixels);
  thread_local std::vector<uint8_t> upper;  // scratch reused from frame to frame
  upper.resize(width);
  for (uint32_t k = 0; k < width; ++k)
    upper[k] = Upper(t.column_dir[2 * k], t.column_dir[2 * k + 1]);
  const Columns columns{t.column_dir.data(), upper.data(), width};
  const uint32_t pieces = PiecesFor(threads, n, 4096);
  if (pieces == 1) {
    std::fill(f.pixel_key.begin(), f.pixel_key.end(), kNone);
    std::fill(f.pixel_point.begin(), f.pixel_point.end(), kNone);
    return RunWide([&] { PointPixels(cloud, p, t, columns, f, {0, n}, true); });
  }
  ForPieces(threads, pieces, n,
            [&](uint32_t, Range points) { PointPixels(cloud, p, t, columns, f, points, false); });
  ForPieces(threads, PiecesFor(threads, p.beams, 4), p.beams, [&](uint32_t, Range rows) {
    Winners(f, {rows.begin * width, rows.end * width}, f.pixel_key.data(), f.pixel_point.data());
  });
}

}  // namespace lpir
