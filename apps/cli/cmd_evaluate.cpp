// lpir-gseg evaluate --pred DIR --gt PATH... [--protocol P] [--json] [--scans DIR] [--by-class]
// [--by-range] [--ontology O]: scores predicted ground labels against SemanticKITTI ground truth
// under the DG, PP, PW and GG protocols (DG by default), or RELLIS-3D ground truth under the
// rellis one (host/eval/metrics.h), per frame and in total, and with the flags per class and per
// range band; printed by evaluate_output.cpp. A ground truth without its prediction file is left
// out and named, the rest scored, and the exit code is then 1.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "apps/cli/args.h"
#include "apps/cli/commands.h"
#include "apps/cli/evaluate_output.h"
#include "apps/cli/exit_codes.h"
#include "host/eval/metrics.h"
#include "host/eval/ontology.h"
#include "host/io/io_error.h"
#include "host/io/kitti_bin.h"
#include "host/io/label_file.h"

namespace lpir {
namespace {

namespace fs = std::filesystem;

const char kHelp[] =
    "usage: lpir-gseg evaluate --pred DIR --gt PATH... [--protocol dg|pp|pw|gg|all] [--json]\n"
    "                          [--scans DIR] [--by-class] [--by-range]\n"
    "                          [--ontology semantickitti|rellis3d]\n"
    "  (--opt VALUE and --opt=VALUE alike; -p --protocol)\n"
    "  --pred DIR       predictions: DIR/<stem>.label, uint32 per point, 1 ground, 0 non-ground;\n"
    "                   a ground truth without one is named and left out, the rest scored, and\n"
    "                   the exit code is then 1\n"
    "  --gt PATH...     ground-truth .label files and/or folders of them (every value up to the\n"
    "                   next --option); each is matched with DIR/<stem>.label\n"
    "  -p, --protocol P dg (default), pp, pw, gg, a comma-separated list of them, or all:\n"
    "                   dg  DipG-Seg: vegetation (70), unlabeled (0), outlier (1) are non-ground;\n"
    "                       TP/FP/FN summed over the frames\n"
    "                   pp  Patchwork++: classes 70, 0, 1 not scored; mean of per-frame scores\n"
    "                   pw  Patchwork: vegetation below z = -1.2975 m is ground; predicted\n"
    "                       ground of class 0/1 is no false positive; mean of per-frame scores\n"
    "                   gg  GroundGrid: classes 70, 0, 1 not scored; counts summed\n"
    "                   rellis  the one protocol of --ontology rellis3d, and its default (all\n"
    "                       means it there): ground 1 dirt, 3 grass, 6 water, 10 asphalt,\n"
    "                       23 concrete, 31 puddle, 33 mud; void (0) not scored; every other\n"
    "                       class non-ground; counts summed. dg/pp/pw/gg are refused there: they\n"
    "                       differ only in classes 70, 0, 1 and KITTI's sensor height\n"
    "  --ontology O     the ground truth's classes: semantickitti (default) or rellis3d "
    "(RELLIS-3D\n"
    "                   .label files); class = label & 0xFFFF in both\n"
    "  --scans DIR      where <stem>.bin lies, for pw's heights and --by-range; by default the "
    "scan\n"
    "                   beside the labels: .../labels/X.label -> .../velodyne/X.bin, else X.bin "
    "in\n"
    "                   the label's own folder (RELLIS-3D's layout)\n"
    "  --by-class       per ground-truth class present (with its name): points, how many the\n"
    "                   prediction calls ground and their share, and FP and FN under each\n"
    "                   protocol ('-': the protocol scores none of the class)\n"
    "  --by-range       per band of horizontal range sqrt(x^2 + y^2) of the scan's points, bands\n"
    "                   [0,5) [5,10) [10,20) [20,30) [30,40) [40,60) [60,inf) m (NaN: the last):\n"
    "                   points, TP, FP, FN under each protocol; needs the scans (see --scans)\n"
    "                   Both count points summed over the frames, also for pp and pw, whose\n"
    "                   scores are per-frame means; summed over the rows they give the\n"
    "                   protocol's TP/FP/FN over all frames\n"
    "  --json           print exactly one JSON object instead of the tables:\n"
    "                   {\"frames\": [{\"name\": stem, \"dg\": {\"precision\", \"recall\", "
    "\"f1\",\n"
    "                   \"iou\"}, ...}], \"total\": {\"dg\": {...}, ...}}, fractions in [0, 1];\n"
    "                   --by-class adds \"by_class\": [{\"class\", \"name\", \"points\",\n"
    "                   \"predicted_ground\", \"share\", \"dg\": {\"tp\", \"fp\", \"fn\", \"tn\",\n"
    "                   \"ignored\"}, ...}], --by-range \"by_range\": [{\"band\", \"from\", "
    "\"to\"\n"
    "                   (metres; no \"to\" in the last), \"points\", \"dg\": {...}, ...}]\n"
    "Scores: precision TP/(TP+FP), recall TP/(TP+FN), F1 2PR/(P+R), IoU TP/(TP+FP+FN); a ratio\n"
    "with denominator 0 is 0. SemanticKITTI ground classes: 40 44 48 49 60 72.\n";

struct Options {
  std::string pred_dir;
  std::vector<std::string> gt;
  Ontology ontology = Ontology::kSemanticKitti;
  std::vector<Protocol> protocols;
  std::string scans_dir;
  bool json = false;
  bool by_class = false;
  bool by_range = false;
  bool help = false;
};

// "all", or a comma-separated list of the ontology's protocols (repeats dropped).
std::vector<Protocol> ParseProtocols(const std::string& text, Ontology ontology) {
  if (text == "all") return ProtocolsOf(ontology);
  std::vector<Protocol> out;
  size_t start = 0;
  while (true) {
    size_t comma = text.find(',', start);
    Protocol p = ParseProtocol(text.substr(start, comma - start), ontology);
    bool seen = false;
    for (Protocol q : out) seen = seen || q == p;
    if (!seen) out.push_back(p);
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return out;
}

// --gt (or --gt=PATH) takes every value up to the next option, which Args cannot; it is taken
// out here and the rest goes through Args.
Options ParseOptions(int argc, char** argv) {
  Options o;
  std::vector<char*> rest;
  for (int i = 0; i < argc; ++i) {
    const std::string arg = argv[i];
    const bool joined = arg.rfind("--gt=", 0) == 0;
    if (arg != "--gt" && !joined) {
      rest.push_back(argv[i]);
      continue;
    }
    if (joined) o.gt.push_back(arg.substr(5));
    int j = i + 1;
    while (j < argc && !IsOptionArgument(argv[j])) o.gt.push_back(argv[j++]);
    if (o.gt.empty() || o.gt.back().empty())
      throw std::invalid_argument("--gt needs at least one .label file or folder");
    i = j - 1;
  }
  Args args(int(rest.size()), rest.data(), {"--json", "--help", "--by-class", "--by-range"},
            {"--pred", "--protocol", "--scans", "--ontology"});
  if (!args.positional().empty())
    throw std::invalid_argument("unexpected argument '" + args.positional()[0] + "'");
  o.help = args.Has("--help");
  if (o.help) return o;
  o.pred_dir = args.Require("--pred");
  if (o.gt.empty()) throw std::invalid_argument("--gt is required");
  o.ontology = ParseOntology(args.Get("--ontology", OntologyName(Ontology::kSemanticKitti)));
  // By default the ontology's first protocol: DG for SemanticKITTI (the one the paper compares
  // against), rellis for RELLIS-3D, as lpir_gseg.evaluate does.
  o.protocols = args.Has("--protocol") ? ParseProtocols(args.Get("--protocol"), o.ontology)
                                       : std::vector<Protocol>{ProtocolsOf(o.ontology).front()};
  o.scans_dir = args.Get("--scans");
  o.json = args.Has("--json");
  o.by_class = args.Has("--by-class");
  o.by_range = args.Has("--by-range");
  return o;
}

struct GtFile {
  std::string path;
  std::string stem;
};

// Every ground-truth file named by the --gt values, folders expanded (sorted by name).
std::vector<GtFile> ListGroundTruth(const std::vector<std::string>& values) {
  std::vector<GtFile> files;
  std::error_code ec;
  for (const std::string& v : values) {
    if (fs::is_directory(v, ec)) {
      std::vector<std::string> found;
      for (fs::directory_iterator it(v, ec), end; !ec && it != end; it.increment(ec))
        if (it->path().extension() == ".label" && it->is_regular_file(ec))
          found.push_back(it->path().string());
      if (found.empty()) throw IoError(v, "folder holds no .label files");
      std::sort(found.begin(), found.end());
      for (const std::string& f : found) files.push_back({f, fs::path(f).stem().string()});
    } else if (fs::is_regular_file(v, ec)) {
      files.push_back({v, fs::path(v).stem().string()});
    } else {
      throw IoError(v, "no such ground-truth file or folder");
    }
  }
  // The same file named twice (a file and its folder) counts once; two files of one stem clash.
  std::map<std::string, std::string> by_stem;
  std::vector<GtFile> unique;
  for (const GtFile& g : files) {
    auto [it, fresh] = by_stem.emplace(g.stem, g.path);
    if (fresh) {
      unique.push_back(g);
    } else if (fs::weakly_canonical(it->second, ec) != fs::weakly_canonical(g.path, ec)) {
      throw std::invalid_argument("ground truth " + it->second + " and " + g.path +
                                  " share the stem '" + g.stem +
                                  "' but predictions are matched by stem: evaluate them apart");
    }
  }
  return unique;
}

// Where a ground truth's scan may lie, in the order tried: --scans, the KITTI layout beside the
// labels, the label's own folder.
std::vector<std::string> ScanCandidates(const GtFile& gt, const std::string& scans_dir) {
  std::vector<std::string> candidates;
  if (!scans_dir.empty()) candidates.push_back((fs::path(scans_dir) / (gt.stem + ".bin")).string());
  fs::path folder = fs::path(gt.path).parent_path();
  if (folder.filename() == "labels")
    candidates.push_back((folder.parent_path() / "velodyne" / (gt.stem + ".bin")).string());
  candidates.push_back((folder / (gt.stem + ".bin")).string());
  return candidates;
}

// The scan of a ground truth, checked to hold `points` points; `needs` says what wants it
// ("protocol pw needs each point's z"), for the error when none is found. Files that are
// missing or do not match throw std::runtime_error (exit code kExitCannotRun), not
// std::invalid_argument, which is kept for the command line (apps/cli/exit_codes.h).
Cloud LoadScan(const GtFile& gt, const std::string& scans_dir, size_t points,
               const std::string& needs) {
  const std::vector<std::string> candidates = ScanCandidates(gt, scans_dir);
  std::string scan, looked;
  std::error_code ec;
  for (const std::string& c : candidates) {
    if (fs::is_regular_file(c, ec)) {
      scan = c;
      break;
    }
    looked += (looked.empty() ? "" : ", ") + c;
  }
  if (scan.empty())
    throw std::runtime_error(needs + ", but no scan was found for " + gt.path + " (looked for " +
                             looked + "): pass --scans DIR holding " + gt.stem + ".bin");
  Cloud cloud = ReadKittiBin(scan);
  if (cloud.size() != points)
    throw std::runtime_error("scan " + scan + " has " + std::to_string(cloud.size()) +
                             " points but ground truth " + gt.path + " has " +
                             std::to_string(points) + " labels");
  return cloud;
}

Labels LoadPrediction(const std::string& path, const GtFile& gt, size_t points) {
  std::vector<uint32_t> raw = ReadLabelFile(path);
  if (raw.size() != points)
    throw std::runtime_error("prediction " + path + " has " + std::to_string(raw.size()) +
                             " labels but ground truth " + gt.path + " has " +
                             std::to_string(points));
  Labels pred(points);
  for (size_t i = 0; i < points; ++i) {
    if (raw[i] > 1)
      throw IoError(path, "label " + std::to_string(i) + " is " + std::to_string(raw[i]) +
                              "; a prediction holds 1 (ground) or 0 (non-ground) per point");
    pred[i] = uint8_t(raw[i]);
  }
  return pred;
}

// What needs the scan, for LoadScan's error; "" when nothing does.
std::string ScanNeeds(const Options& o) {
  for (Protocol p : o.protocols)
    if (p == Protocol::kPW) return "protocol pw needs each point's z";
  return o.by_range ? "--by-range needs each point's x and y" : "";
}

// Scores one ground-truth file against its prediction into `r`; `needs`: ScanNeeds(o). A
// prediction that does not exist goes into r->missing instead.
void AddFrame(const Options& o, const GtFile& gt, const std::string& needs, EvaluateResults* r) {
  const std::string pred_path = (fs::path(o.pred_dir) / (gt.stem + ".label")).string();
  std::error_code ec;
  if (!fs::is_regular_file(pred_path, ec)) {
    r->missing.push_back(pred_path);
    return;
  }
  const std::vector<uint32_t> truth = ReadLabelFile(gt.path);
  const Labels pred = LoadPrediction(pred_path, gt, truth.size());
  Cloud cloud;
  if (!needs.empty()) cloud = LoadScan(gt, o.scans_dir, truth.size(), needs);
  std::vector<float> z(cloud.size());
  for (size_t i = 0; i < z.size(); ++i) z[i] = cloud.z(i);
  const std::vector<float>* zp = needs.empty() ? nullptr : &z;
  std::vector<Scores> row;
  for (SequenceScores& seq : r->totals)
    row.push_back(seq.Add(CountFrame(seq.protocol(), pred, truth, zp)));
  r->per_frame.push_back(row);
  r->frames.push_back(gt.stem);
  if (r->by_class) r->by_class->Add(pred, truth, zp);
  if (r->by_range) r->by_range->Add(cloud, pred, truth);
}

// Scores every ground-truth file, with the breakdowns asked for.
EvaluateResults Evaluate(const Options& o, const std::vector<GtFile>& gts) {
  EvaluateResults r;
  r.ontology = o.ontology;
  for (Protocol p : o.protocols) r.totals.emplace_back(p);
  if (o.by_class) r.by_class.emplace(o.protocols);
  if (o.by_range) r.by_range.emplace(o.protocols);
  const std::string needs = ScanNeeds(o);
  for (const GtFile& gt : gts) AddFrame(o, gt, needs, &r);
  return r;
}

}  // namespace

int RunEvaluate(int argc, char** argv) {
  const Options o = ParseOptions(argc, argv);
  if (o.help) {
    std::fputs(kHelp, stdout);
    std::fputs(kExitCodesLine, stdout);
    return kExitOk;
  }
  std::error_code ec;
  if (!fs::is_directory(o.pred_dir, ec)) throw IoError(o.pred_dir, "no such prediction folder");
  const std::vector<GtFile> gts = ListGroundTruth(o.gt);
  const EvaluateResults r = Evaluate(o, gts);
  if (r.frames.empty() && gts.size() == 1)
    throw std::runtime_error("no prediction for ground truth " + gts[0].path + ": " + r.missing[0] +
                             " does not exist");
  if (r.frames.empty())
    throw std::runtime_error("no prediction for any of the " + std::to_string(gts.size()) +
                             " ground-truth files in " + o.pred_dir + " (looked for " +
                             r.missing[0] + ", ...)");
  const std::string out = o.json ? FormatJson(r) : FormatTables(r);
  std::fputs(out.c_str(), stdout);
  if (r.missing.empty()) return kExitOk;
  std::string missing;
  for (const std::string& m : r.missing) missing += "\n  " + m;
  std::fprintf(stderr,
               "lpir-gseg evaluate: %zu of %zu predictions missing, left out (the other %zu "
               "scored):%s\n",
               r.missing.size(), gts.size(), r.frames.size(), missing.c_str());
  return kExitSomeFailed;
}

}  // namespace lpir
