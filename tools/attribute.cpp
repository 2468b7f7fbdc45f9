// attribute: runs the CPU reference on labelled scans and says which stage decided every missed
// ground point (FN) and every false ground point (FP) (host/eval/attribution.h). Prints per scan
// and summed: DG P/R/F1, PP F1, the share of car points labelled ground, FN and FP per deciding
// stage, FN per range band, FN and FP per ground-truth class. docs/accuracy.md holds its tables.
#include <cmath>
#include <cstdio>
#include <exception>
#include <map>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "host/api/mount_estimate.h"
#include "host/eval/attribution.h"
#include "host/eval/by_range.h"
#include "host/eval/metrics.h"
#include "host/eval/ontology.h"
#include "host/io/kitti_bin.h"
#include "host/io/label_file.h"
#include "host/io/sensor_profile.h"
#include "reference_cpu/pipeline.h"

namespace lpir {
namespace {

const char kUsage[] =
    "usage: attribute --sensor NAME [--sensors DIR] [--ontology semantickitti|rellis3d]\n"
    "                 [--param NAME VALUE]... SCAN.bin LABELS.label [SCAN.bin LABELS.label]...\n"
    "Runs the CPU reference on each scan (KITTI .bin) and scores it against its labels:\n"
    "semantickitti under the DG protocol (vegetation, unlabeled and outliers are non-ground; PP\n"
    "F1 beside it), rellis3d under the rellis protocol (void not scored). Every wrong point is\n"
    "attributed to the first rule that holds:\n"
    "  prepare:invalid, prepare:noise   prepare marked the point invalid or reflection noise\n"
    "  back-project   the point's label differs from its pixel's final label (back_project)\n"
    "  component      FN: the pixel was grown ground, its component too small (grow)\n"
    "  veto           FN: the occlusion veto made the pixel non-ground (fuse), not lifted\n"
    "  class+coarse   FN: pixel class and coarse label both non-ground\n"
    "  grow:<why>     FN: fuse left the pixel unknown and growing did not reach it; it was\n"
    "                 unknown because: class-ng (class non-ground, coarse ground), coarse-ng\n"
    "                 (coarse non-ground), hole (hole-filled pixel, no coarse opinion)\n"
    "  seed:both      FP: a seed, class and coarse label both ground\n"
    "  seed:coarse    FP: a seed, class unknown and coarse label ground\n"
    "  grow           FP: an unknown pixel reached by growing\n"
    "  lift           FP: a vetoed pixel lifted by the ground around it (grow)\n"
    "--param overrides one parameter of the profile (as a profile's override line would).\n";

struct Args {
  std::string sensor, sensors_dir = LPIR_SENSORS_DIR;
  Ontology ontology = Ontology::kSemanticKitti;
  std::vector<std::pair<std::string, float>> params;
  std::vector<std::pair<std::string, std::string>> scans;  // cloud, labels
};

Args Parse(int argc, char** argv) {
  Args a;
  std::vector<std::string> files;
  for (int i = 1; i < argc; ++i) {
    const std::string s = argv[i];
    auto next = [&]() -> std::string {
      if (i + 1 >= argc) throw std::invalid_argument(s + " needs a value");
      return argv[++i];
    };
    if (s == "--help") {
      std::fputs(kUsage, stdout);
      std::exit(0);
    } else if (s == "--sensor") {
      a.sensor = next();
    } else if (s == "--sensors") {
      a.sensors_dir = next();
    } else if (s == "--ontology") {
      a.ontology = ParseOntology(next());
    } else if (s == "--param") {
      const std::string name = next();
      a.params.emplace_back(name, std::stof(next()));
    } else {
      files.push_back(s);
    }
  }
  if (a.sensor.empty() || files.empty() || files.size() % 2)
    throw std::invalid_argument("need --sensor and SCAN.bin LABELS.label pairs (--help)");
  for (size_t i = 0; i < files.size(); i += 2) a.scans.emplace_back(files[i], files[i + 1]);
  return a;
}

// Everything summed over the scans.
struct Tally {
  Counts scored, pp;
  uint64_t cars = 0, cars_ground = 0;
  uint64_t fn_by[kDeciderCount] = {}, fp_by[kDeciderCount] = {};
  uint64_t band_fn[kRangeBands] = {}, band_ground[kRangeBands] = {};
  std::map<uint32_t, uint64_t> fn_class, fp_class;
};

constexpr uint32_t kCar = 10;

// Scores one scan into `t` and returns its scored counts.
// The scan runs with the profile's mount, or with its own estimate (mount per_frame), as a
// Segmenter runs it.
Counts AddScan(const Args& a, const SensorProfile& sensor, const Params& p, const Tables& tables,
               const std::string& cloud_path, const std::string& label_path, Tally& t) {
  const Cloud cloud = ReadKittiBin(cloud_path);
  const std::vector<uint32_t> gt = ReadLabelFile(label_path, cloud.size());
  Frame f;
  const MountEstimate mount = FrameMount(cloud, sensor, p);
  if (sensor.mount == MountSource::kPerFrame)
    std::printf("%s: mount %s, k_xz %.4f k_yz %.4f height %.3f m\n", cloud_path.c_str(),
                mount.estimated ? "estimated" : "not estimated (the profile's)", mount.mount.k_xz,
                mount.mount.k_yz, mount.mount.sensor_height);
  RunReference(cloud, WithMount(p, mount.mount), tables, f);
  const Protocol protocol = a.ontology == Ontology::kRellis3d ? Protocol::kRellis : Protocol::kDG;
  Counts c;
  for (uint32_t i = 0; i < f.n; ++i) {
    const uint32_t cls = gt[i] & 0xFFFF;
    const bool pred = f.label[i] != 0;
    const Outcome o = ScorePoint(protocol, gt[i], pred, cloud.z(i));
    if (o == Outcome::kIgnored) continue;
    c.Add(o);
    if (protocol == Protocol::kDG) {
      if (cls == kCar) ++t.cars, t.cars_ground += pred;
      t.pp.Add(ScorePoint(Protocol::kPP, gt[i], pred, cloud.z(i)));
    }
    const bool truth = o == Outcome::kTP || o == Outcome::kFN;
    const size_t band = RangeBand(std::hypot(cloud.x(i), cloud.y(i)));
    if (truth) ++t.band_ground[band];
    if (o == Outcome::kTP || o == Outcome::kTN) continue;
    const int who = static_cast<int>(Attribute(f, i, truth));
    if (truth) {
      ++t.fn_by[who], ++t.band_fn[band], ++t.fn_class[cls];
    } else {
      ++t.fp_by[who], ++t.fp_class[cls];
    }
  }
  t.scored += c;
  return c;
}

void PrintClasses(const char* what, Ontology ontology, const std::map<uint32_t, uint64_t>& m) {
  std::printf("%s by class:", what);
  for (const auto& [cls, n] : m)
    std::printf("  %s %llu", ClassName(ontology, cls), static_cast<unsigned long long>(n));
  std::printf("\n");
}

int Main(int argc, char** argv) {
  const Args a = Parse(argc, argv);
  const SensorProfile sensor = LoadSensorProfile(a.sensor, a.sensors_dir);
  Params p = ParamsForSensor(sensor);
  for (const auto& [name, value] : a.params)
    if (!ApplyOverride(p, name, value)) throw std::invalid_argument("no parameter " + name);
  const Tables tables = MakeTables(sensor, p);

  Tally t;
  for (const auto& [cloud_path, label_path] : a.scans) {
    const Counts c = AddScan(a, sensor, p, tables, cloud_path, label_path, t);
    const Scores s = ScoreCounts(c);
    std::printf("%s: P %.2f R %.2f F1 %.2f, FN %llu FP %llu\n", cloud_path.c_str(),
                100 * s.precision, 100 * s.recall, 100 * s.f1,
                static_cast<unsigned long long>(c.fn), static_cast<unsigned long long>(c.fp));
  }
  const Scores s = ScoreCounts(t.scored);
  std::printf("summed: P %.2f R %.2f F1 %.2f", 100 * s.precision, 100 * s.recall, 100 * s.f1);
  if (a.ontology == Ontology::kSemanticKitti)
    std::printf(" | PP F1 %.2f | car points labelled ground %.3f %%", 100 * ScoreCounts(t.pp).f1,
                t.cars ? 100.0 * double(t.cars_ground) / double(t.cars) : 0.0);
  std::printf("\nstage     FN      FP\n");
  for (int d = 0; d < kDeciderCount; ++d)
    if (t.fn_by[d] || t.fp_by[d])
      std::printf("%-16s %6llu %6llu\n", DeciderName(static_cast<Decider>(d)),
                  static_cast<unsigned long long>(t.fn_by[d]),
                  static_cast<unsigned long long>(t.fp_by[d]));
  std::printf("FN / ground points by range band:");
  for (size_t b = 0; b < kRangeBands; ++b)
    std::printf("  %s %llu / %llu", RangeBandName(b).c_str(),
                static_cast<unsigned long long>(t.band_fn[b]),
                static_cast<unsigned long long>(t.band_ground[b]));
  std::printf("\n");
  PrintClasses("FN", a.ontology, t.fn_class);
  PrintClasses("FP", a.ontology, t.fp_class);
  return 0;
}

}  // namespace
}  // namespace lpir

int main(int argc, char** argv) {
  try {
    return lpir::Main(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "attribute: %s\n", e.what());
    return 2;
  }
}
