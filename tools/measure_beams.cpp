// measure_beams: measures a spinning LiDAR's beam elevation table from its scans and prints it as
// a sensor-profile `elevation_deg` line (top beam first). Used for sensors/hdl64e.txt (KITTI) and
// sensors/os1-64.txt (RELLIS-3D); `measure_beams --help` explains the method.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "host/io/kitti_bin.h"

namespace {

const char kUsage[] =
    "usage: measure_beams [--beams N] [--layout sweep|columns|rows] [--cut DEG] [--blocks B]\n"
    "                     [--min-range M] FILE.bin...\n"
    "\n"
    "Splits every scan into N rings, then measures each ring's elevation.\n"
    "  --layout sweep    (default) points stored laser by laser, each laser sweeping once\n"
    "                    around (KITTI): a ring ends where the azimuth wraps past --cut\n"
    "                    (default 0, straight ahead; the sweep direction is detected). Every\n"
    "                    scan must split into exactly N rings.\n"
    "  --layout columns  organised scan, column-major: point i is in ring i % N (RELLIS OS1).\n"
    "  --layout rows     organised scan, row-major: point i is in ring i / (points / N).\n"
    "Per ring, tan(elevation) is the slope of z against the planar range r, least squares within\n"
    "2-degree azimuth bins of each scan, pooled (immune to a laser origin above the sensor centre\n"
    "and to per-azimuth shifts such as KITTI's motion correction); the ring's origin height h is\n"
    "then the median of z - r tan(e). --blocks B (default 0) splits the rings into B equal blocks\n"
    "(HDL-64E: 2, its upper and lower laser blocks) and models h within a block as a straight\n"
    "line in the ring index (Theil-Sen fit over the block's rings, robust to the rings with too\n"
    "little range spread); 0 puts every origin at the sensor centre. The reported elevation is\n"
    "the mean over 10-degree azimuth bins of the bin medians of atan2(z - h, r) over points with\n"
    "r >= --min-range (default 3 m). The plain median of atan2(z, r) over r > 20 m is printed\n"
    "beside it for comparison, and the table is cross-checked against the peaks of the histogram\n"
    "of corrected elevations.\n";

constexpr double kPi = 3.14159265358979323846;
constexpr double kDeg = 180.0 / kPi;

struct Sample {
  float az;  // azimuth atan2(y, x), degrees in [0, 360)
  float r;   // planar range, m
  float z;   // m
};

double Median(std::vector<double> v) {
  if (v.empty()) return std::nan("");
  size_t m = v.size() / 2;
  std::nth_element(v.begin(), v.begin() + m, v.end());
  double hi = v[m];
  if (v.size() % 2) return hi;
  double lo = *std::max_element(v.begin(), v.begin() + m);
  return 0.5 * (lo + hi);
}

// The mean over 10-degree azimuth bins (with at least 5 values) of each bin's median: every
// direction weighs the same however many points it holds, and a distortion that changes sign
// around the turn (KITTI's motion correction) averages out. The plain median when fewer than 3
// bins qualify (a sparse top ring).
double AzimuthBalancedMean(const std::vector<Sample>& s, double (*value)(const Sample&, double),
                           double arg) {
  std::vector<std::vector<double>> bins(36);
  std::vector<double> all;
  for (const Sample& p : s) {
    bins[std::min(35, static_cast<int>(p.az / 10.0f))].push_back(value(p, arg));
    all.push_back(value(p, arg));
  }
  double sum = 0;
  int used = 0;
  for (auto& b : bins) {
    if (b.size() < 5) continue;
    sum += Median(b);
    ++used;
  }
  return used >= 3 ? sum / used : Median(all);  // too few for bins (a sparse top ring): plain
}

double CorrectedElevation(const Sample& p, double h) { return std::atan2(p.z - h, p.r) * kDeg; }
double Intercept(const Sample& p, double tan_e) { return p.z - p.r * tan_e; }

struct Options {
  unsigned beams = 64;
  std::string layout = "sweep";
  double cut = 0.0;
  unsigned blocks = 0;
  double min_range = 3.0;
  std::vector<std::string> files;
};

// Ring index of every point of one scan (-1: point skipped), or an error message.
std::vector<int> AssignRings(const lpir::Cloud& c, const Options& o, std::string* error) {
  const size_t n = c.size();
  std::vector<int> ring(n, -1);
  if (o.layout == "columns" || o.layout == "rows") {
    if (n % o.beams) {
      *error = std::to_string(n) + " points is not a whole number of " + std::to_string(o.beams) +
               "-point " + (o.layout == "columns" ? "columns" : "rows");
      return {};
    }
    for (size_t i = 0; i < n; ++i)
      ring[i] = static_cast<int>(o.layout == "columns" ? i % o.beams : i / (n / o.beams));
    return ring;
  }
  // Sweep layout: detect the direction from the majority sign of the (wrapped) azimuth steps.
  // Points without a direction (0,0,0 "no return" entries, NaN) stay out of the sweep.
  std::vector<double> az(n, std::nan(""));
  for (size_t i = 0; i < n; ++i)
    if ((c.x(i) != 0 || c.y(i) != 0) && std::isfinite(c.x(i)) && std::isfinite(c.y(i)))
      az[i] = std::atan2(c.y(i), c.x(i)) * kDeg;
  long votes = 0;
  double last = std::nan("");
  for (size_t i = 0; i < n; ++i) {
    if (std::isnan(az[i])) continue;
    double d = std::remainder(az[i] - last, 360.0);
    votes += d > 0 ? 1 : d < 0 ? -1 : 0;  // NaN (the first point) votes neither way
    last = az[i];
  }
  const double dir = votes >= 0 ? 1.0 : -1.0;
  int current = 0;
  double progress = 0;  // degrees swept by the current ring
  double prev_b = std::nan("");
  for (size_t i = 0; i < n; ++i) {
    if (std::isnan(az[i])) continue;
    double b = std::fmod(dir * (az[i] - o.cut), 360.0);
    if (b < 0) b += 360.0;
    if (!std::isnan(prev_b)) {
      // A new ring starts where the azimuth falls back across the cut, once the ring has swept
      // half a turn (so jitter of a few points around the cut cannot split a ring twice).
      if (prev_b - b > 180.0 && progress > 180.0) {
        ++current;
        progress = 0;
      } else {
        progress += std::remainder(b - prev_b, 360.0);
      }
    }
    prev_b = b;
    ring[i] = current;
  }
  if (static_cast<unsigned>(current + 1) != o.beams) {
    *error = "found " + std::to_string(current + 1) + " sweeps, expected " +
             std::to_string(o.beams) + " (wrong --beams or --cut?)";
    return {};
  }
  return ring;
}

int Run(const Options& o) {
  const unsigned nb = o.beams;
  std::vector<std::vector<Sample>> rings(nb);
  // Pooled within-bin least-squares sums per ring.
  std::vector<double> sxx(nb, 0.0), sxy(nb, 0.0);
  std::vector<std::vector<double>> far(nb);  // atan2(z, r) of points beyond 20 m
  for (const std::string& path : o.files) {
    lpir::Cloud c = lpir::ReadKittiBin(path);
    std::string error;
    std::vector<int> ring = AssignRings(c, o, &error);
    if (ring.empty()) {
      std::fprintf(stderr, "measure_beams: %s: %s\n", path.c_str(), error.c_str());
      return 1;
    }
    struct Bin {
      double n = 0, r = 0, z = 0, rr = 0, rz = 0;
    };
    std::map<std::pair<int, int>, Bin> bins;  // (ring, 2-degree azimuth bin) of this scan
    for (size_t i = 0; i < c.size(); ++i) {
      const double x = c.x(i), y = c.y(i), z = c.z(i);
      const double r = std::sqrt(x * x + y * y);
      if (ring[i] < 0 || !std::isfinite(r) || !std::isfinite(z) || r < o.min_range) continue;
      double az = std::atan2(y, x) * kDeg;
      if (az < 0) az += 360.0;
      if (az >= 360.0) az = 0.0;
      rings[ring[i]].push_back(
          {static_cast<float>(az), static_cast<float>(r), static_cast<float>(z)});
      if (r > 20.0) far[ring[i]].push_back(std::atan2(z, r) * kDeg);
      Bin& b = bins[{ring[i], static_cast<int>(az / 2.0)}];
      b.n += 1;
      b.r += r;
      b.z += z;
      b.rr += r * r;
      b.rz += r * z;
    }
    for (const auto& [key, b] : bins) {
      if (b.n < 3) continue;
      sxx[key.first] += b.rr - b.r * b.r / b.n;
      sxy[key.first] += b.rz - b.r * b.z / b.n;
    }
  }
  std::vector<double> slope_deg(nb), h(nb);
  for (unsigned k = 0; k < nb; ++k) {
    if (rings[k].size() < 10) {
      std::fprintf(stderr, "measure_beams: ring %u has only %zu usable points\n", k,
                   rings[k].size());
      return 1;
    }
    if (!(sxx[k] > 0)) {  // no range spread at all: no slope, no origin estimate
      slope_deg[k] = h[k] = std::nan("");
      continue;
    }
    const double t = sxy[k] / sxx[k];
    slope_deg[k] = std::atan(t) * kDeg;
    h[k] = AzimuthBalancedMean(rings[k], Intercept, t);
  }
  // Origin height per ring: within each block a straight line in the ring index, fitted to the
  // rings' own estimates by Theil-Sen (median of pairwise slopes), which ignores the few rings
  // whose range spread is too small for a reliable fit.
  std::vector<double> h_block(nb, 0.0);
  if (o.blocks > 0) {
    const unsigned size = nb / o.blocks;
    for (unsigned b = 0; b < o.blocks; ++b) {
      const unsigned first = b * size, last = (b + 1) * size - 1;
      std::vector<double> slopes, offsets;
      for (unsigned i = first; i <= last; ++i)
        for (unsigned j = i + 1; j <= last; ++j)
          if (std::isfinite(h[i]) && std::isfinite(h[j])) slopes.push_back((h[j] - h[i]) / (j - i));
      const double slope = slopes.empty() ? 0.0 : Median(slopes);
      for (unsigned i = first; i <= last; ++i)
        if (std::isfinite(h[i])) offsets.push_back(h[i] - slope * (i - first));
      const double h0 = offsets.empty() ? 0.0 : Median(offsets);
      for (unsigned k = first; k <= last; ++k) h_block[k] = h0 + slope * (k - first);
      std::printf(
          "# block %u (rings %u-%u): laser origins %.3f .. %.3f m above the sensor centre\n", b,
          first, last, h_block[first], h_block[last]);
    }
  }
  std::vector<double> elev(nb);
  std::printf("# ring  points  elevation  step   | slope-fit  origin_h | r>20m: median  points\n");
  for (unsigned k = 0; k < nb; ++k) {
    elev[k] = AzimuthBalancedMean(rings[k], CorrectedElevation, h_block[k]);
    std::string step = k ? std::to_string(elev[k - 1] - elev[k]).substr(0, 6) : "";
    std::printf("# %4u %7zu %10.3f  %-6s | %9.3f %9.3f | %13.3f %7zu\n", k, rings[k].size(),
                elev[k], step.c_str(), slope_deg[k], h[k], Median(far[k]), far[k].size());
  }
  const bool descending = elev.front() > elev.back();
  std::printf("# ring 0 is the %s beam\n", descending ? "top" : "bottom");
  std::vector<double> top_first = elev;
  if (!descending) std::reverse(top_first.begin(), top_first.end());
  for (size_t k = 1; k < top_first.size(); ++k) {
    if (!(top_first[k] < top_first[k - 1]))
      std::printf("# WARNING: not strictly monotonic at ring %zu\n", descending ? k : nb - 1 - k);
  }
  // Cross-check: peaks of the histogram of corrected elevations (0.02-degree bins smoothed over
  // 5 bins; a peak is the largest value within +-0.1 degree). Rings smeared by per-azimuth
  // distortions (KITTI's lower block) blur into each other and show no peak of their own.
  std::map<long, double> histo;
  for (unsigned k = 0; k < nb; ++k)
    for (const Sample& p : rings[k])
      histo[std::lround(CorrectedElevation(p, h_block[k]) / 0.02)] += 1;
  auto at = [&](long bin) {
    double v = 0;
    for (long d = -2; d <= 2; ++d) {
      auto it = histo.find(bin + d);
      if (it != histo.end()) v += it->second * (3 - std::labs(d));
    }
    return v;
  };
  std::vector<double> peaks;
  for (const auto& entry : histo) {
    const long bin = entry.first;
    const double v = at(bin);
    bool is_peak = v >= 200;
    for (long d = -5; d <= 5 && is_peak; ++d)
      is_peak = d == 0 || (d < 0 ? v > at(bin + d) : v >= at(bin + d));
    if (is_peak) peaks.push_back(bin * 0.02);
  }
  // Per ring (file order), whether a peak lies within 0.1 degree; counted per block.
  const unsigned groups = o.blocks > 0 ? o.blocks : 1;
  for (unsigned b = 0; b < groups; ++b) {
    int matched = 0;
    std::string misses;
    for (unsigned k = b * (nb / groups); k < (b + 1) * (nb / groups); ++k) {
      bool near = false;
      for (double pk : peaks) near = near || std::fabs(pk - elev[k]) <= 0.1;
      matched += near;
      if (!near) misses += " " + std::to_string(k);
    }
    std::printf("# histogram: %zu peaks; rings %u-%u: %d of %u lie within 0.1 deg of one%s%s\n",
                peaks.size(), b * (nb / groups), (b + 1) * (nb / groups) - 1, matched, nb / groups,
                misses.empty() ? "" : "; not:", misses.c_str());
  }
  std::printf("elevation_deg");
  for (size_t k = 0; k < top_first.size(); ++k)
    std::printf("%s %.3f", k && k % 8 == 0 ? "\n " : "", top_first[k]);
  std::printf("\n");
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  try {
    for (int i = 1; i < argc; ++i) {
      std::string a = argv[i];
      auto value = [&]() -> std::string {
        if (i + 1 >= argc) throw std::invalid_argument(a + " needs a value");
        return argv[++i];
      };
      if (a == "--help" || a == "-h") {
        std::fputs(kUsage, stdout);
        return 0;
      } else if (a == "--beams") {
        o.beams = static_cast<unsigned>(std::stoul(value()));
      } else if (a == "--layout") {
        o.layout = value();
        if (o.layout != "sweep" && o.layout != "columns" && o.layout != "rows")
          throw std::invalid_argument("--layout must be sweep, columns or rows");
      } else if (a == "--cut") {
        o.cut = std::stod(value());
      } else if (a == "--blocks") {
        o.blocks = static_cast<unsigned>(std::stoul(value()));
      } else if (a == "--min-range") {
        o.min_range = std::stod(value());
      } else if (a.rfind("--", 0) == 0) {
        throw std::invalid_argument("unknown option " + a);
      } else {
        o.files.push_back(a);
      }
    }
    if (o.files.empty() || o.beams < 2)
      throw std::invalid_argument("need FILE.bin and --beams >= 2");
    if (o.blocks > 0 && o.beams % o.blocks)
      throw std::invalid_argument("--blocks must divide --beams");
    return Run(o);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "measure_beams: %s\n%s", e.what(), kUsage);
    return 1;
  }
}
