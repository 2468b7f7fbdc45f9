// lpir-gseg evaluate --pred DIR --gt PATH... --protocol P [--json] [--scans DIR]: scores predicted
// ground labels against SemanticKITTI ground truth under the DG, PP, PW and GG protocols
// (host/eval/metrics.h), per frame and in total, as a table or as one JSON object.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "apps/cli/args.h"
#include "apps/cli/commands.h"
#include "host/eval/metrics.h"
#include "host/io/io_error.h"
#include "host/io/kitti_bin.h"
#include "host/io/label_file.h"

namespace lpir {
namespace {

namespace fs = std::filesystem;

const char kHelp[] =
    "usage: lpir-gseg evaluate --pred DIR --gt PATH... --protocol dg|pp|pw|gg|all [--json]\n"
    "                          [--scans DIR]\n"
    "  --pred DIR       predictions: DIR/<stem>.label, uint32 per point, 1 ground, 0 non-ground\n"
    "  --gt PATH...     SemanticKITTI .label files and/or folders of them (every value up to the\n"
    "                   next --option); each is matched with DIR/<stem>.label\n"
    "  --protocol P     dg, pp, pw, gg, a comma-separated list of them, or all:\n"
    "                   dg  DipG-Seg: vegetation (70), unlabeled (0), outlier (1) are non-ground;\n"
    "                       TP/FP/FN summed over the frames\n"
    "                   pp  Patchwork++: classes 70, 0, 1 not scored; mean of per-frame scores\n"
    "                   pw  Patchwork: vegetation below z = -1.2975 m is ground; predicted\n"
    "                       ground of class 0/1 is no false positive; mean of per-frame scores\n"
    "                   gg  GroundGrid: classes 70, 0, 1 not scored; counts summed\n"
    "  --scans DIR      where <stem>.bin lies (KITTI layout), for pw's heights; by default the\n"
    "                   scan beside the labels: .../labels/X.label -> .../velodyne/X.bin\n"
    "  --json           print exactly one JSON object instead of the table:\n"
    "                   {\"frames\": [{\"name\": stem, \"dg\": {\"precision\", \"recall\", "
    "\"f1\",\n"
    "                   \"iou\"}, ...}], \"total\": {\"dg\": {...}, ...}}, fractions in [0, 1]\n"
    "Scores: precision TP/(TP+FP), recall TP/(TP+FN), F1 2PR/(P+R), IoU TP/(TP+FP+FN); a ratio\n"
    "with denominator 0 is 0. Ground classes: 40 44 48 49 60 72 (label & 0xFFFF).\n";

struct Options {
  std::string pred_dir;
  std::vector<std::string> gt;
  std::vector<Protocol> protocols;
  std::string scans_dir;
  bool json = false;
  bool help = false;
};

std::vector<Protocol> ParseProtocols(const std::string& text) {
  if (text == "all") return AllProtocols();
  std::vector<Protocol> out;
  size_t start = 0;
  while (true) {
    size_t comma = text.find(',', start);
    Protocol p = ParseProtocol(text.substr(start, comma - start));
    bool seen = false;
    for (Protocol q : out) seen = seen || q == p;
    if (!seen) out.push_back(p);
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return out;
}

// --gt takes every value up to the next --option, which Args cannot; it is taken out here and
// the rest goes through Args.
Options ParseOptions(int argc, char** argv) {
  Options o;
  std::vector<char*> rest;
  for (int i = 0; i < argc; ++i) {
    if (std::string(argv[i]) != "--gt") {
      rest.push_back(argv[i]);
      continue;
    }
    int j = i + 1;
    while (j < argc && std::string(argv[j]).rfind("--", 0) != 0) o.gt.push_back(argv[j++]);
    if (j == i + 1) throw std::invalid_argument("--gt needs at least one .label file or folder");
    i = j - 1;
  }
  Args args(int(rest.size()), rest.data(), {"--json", "--help"},
            {"--pred", "--protocol", "--scans"});
  if (!args.positional().empty())
    throw std::invalid_argument("unexpected argument '" + args.positional()[0] + "'");
  o.help = args.Has("--help");
  if (o.help) return o;
  o.pred_dir = args.Require("--pred");
  if (o.gt.empty()) throw std::invalid_argument("--gt is required");
  o.protocols = ParseProtocols(args.Require("--protocol"));
  o.scans_dir = args.Get("--scans");
  o.json = args.Has("--json");
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

// The heights protocol pw needs: the scan in --scans, else beside the labels.
std::vector<float> LoadHeights(const GtFile& gt, const std::string& scans_dir, size_t points) {
  std::vector<std::string> candidates;
  if (!scans_dir.empty()) candidates.push_back((fs::path(scans_dir) / (gt.stem + ".bin")).string());
  fs::path folder = fs::path(gt.path).parent_path();
  if (folder.filename() == "labels")
    candidates.push_back((folder.parent_path() / "velodyne" / (gt.stem + ".bin")).string());
  std::string scan;
  std::error_code ec;
  for (const std::string& c : candidates) {
    if (fs::is_regular_file(c, ec)) {
      scan = c;
      break;
    }
  }
  if (scan.empty()) {
    std::string looked;
    for (const std::string& c : candidates) looked += (looked.empty() ? "" : ", ") + c;
    throw std::invalid_argument(
        "protocol pw needs each point's z, but no scan was found for " + gt.path +
        (looked.empty() ? std::string(" (it is not in a labels/ folder beside velodyne/)")
                        : " (looked for " + looked + ")") +
        ": pass --scans DIR holding " + gt.stem + ".bin");
  }
  Cloud cloud = ReadKittiBin(scan);
  if (cloud.size() != points)
    throw std::invalid_argument("scan " + scan + " has " + std::to_string(cloud.size()) +
                                " points but ground truth " + gt.path + " has " +
                                std::to_string(points) + " labels");
  std::vector<float> z(points);
  for (size_t i = 0; i < points; ++i) z[i] = cloud.z(i);
  return z;
}

Labels LoadPrediction(const std::string& path, const GtFile& gt, size_t points) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec))
    throw std::invalid_argument("no prediction for ground truth " + gt.path + ": " + path +
                                " does not exist");
  std::vector<uint32_t> raw = ReadLabelFile(path);
  if (raw.size() != points)
    throw std::invalid_argument("prediction " + path + " has " + std::to_string(raw.size()) +
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

// The shortest of %.15g / %.17g that reads back as the same double.
std::string JsonNumber(double v) {
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%.15g", v);
  if (std::strtod(buf, nullptr) != v) std::snprintf(buf, sizeof(buf), "%.17g", v);
  return buf;
}

std::string JsonString(const std::string& s) {
  std::string out = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (static_cast<unsigned char>(c) < 0x20) {
      char buf[8];
      std::snprintf(buf, sizeof(buf), "\\u%04x", static_cast<unsigned>(c));
      out += buf;
    } else {
      out += c;
    }
  }
  return out + "\"";
}

std::string JsonScores(const Scores& s) {
  return "{\"precision\": " + JsonNumber(s.precision) + ", \"recall\": " + JsonNumber(s.recall) +
         ", \"f1\": " + JsonNumber(s.f1) + ", \"iou\": " + JsonNumber(s.iou) + "}";
}

const char* Describe(Protocol p) {
  switch (p) {
    case Protocol::kDG:
      return "DG (DipG-Seg): vegetation, unlabeled and outliers are non-ground; counts summed";
    case Protocol::kPP:
      return "PP (Patchwork++): vegetation, unlabeled and outliers not scored; mean over frames";
    case Protocol::kPW:
      return "PW (Patchwork): vegetation below z -1.2975 m is ground, predicted unlabeled/outlier "
             "no FP; mean over frames";
    case Protocol::kGG:
      return "GG (GroundGrid): vegetation, unlabeled and outliers not scored; counts summed";
    case Protocol::kRellis:
      return "RELLIS (RELLIS-3D): ground 1 3 6 10 23 31 33, void (0) not scored; counts summed";
  }
  return "";
}

}  // namespace

int RunEvaluate(int argc, char** argv) {
  const Options o = ParseOptions(argc, argv);
  if (o.help) {
    std::fputs(kHelp, stdout);
    return 0;
  }
  std::error_code ec;
  if (!fs::is_directory(o.pred_dir, ec)) throw IoError(o.pred_dir, "no such prediction folder");
  const std::vector<GtFile> gts = ListGroundTruth(o.gt);
  bool needs_z = false;
  for (Protocol p : o.protocols) needs_z = needs_z || p == Protocol::kPW;

  std::vector<SequenceScores> totals;
  for (Protocol p : o.protocols) totals.emplace_back(p);
  std::vector<std::vector<Scores>> per_frame;  // [frame][protocol]
  for (const GtFile& gt : gts) {
    const std::vector<uint32_t> truth = ReadLabelFile(gt.path);
    const std::string pred_path = (fs::path(o.pred_dir) / (gt.stem + ".label")).string();
    const Labels pred = LoadPrediction(pred_path, gt, truth.size());
    std::vector<float> z;
    if (needs_z) z = LoadHeights(gt, o.scans_dir, truth.size());
    std::vector<Scores> row;
    for (SequenceScores& seq : totals)
      row.push_back(seq.Add(CountFrame(seq.protocol(), pred, truth, needs_z ? &z : nullptr)));
    per_frame.push_back(row);
  }

  if (o.json) {
    std::string out = "{\"frames\": [";
    for (size_t f = 0; f < gts.size(); ++f) {
      out += std::string(f ? ", " : "") + "{\"name\": " + JsonString(gts[f].stem);
      for (size_t k = 0; k < totals.size(); ++k)
        out += ", \"" + std::string(ProtocolName(totals[k].protocol())) +
               "\": " + JsonScores(per_frame[f][k]);
      out += "}";
    }
    out += "], \"total\": {";
    for (size_t k = 0; k < totals.size(); ++k)
      out += std::string(k ? ", " : "") + "\"" + ProtocolName(totals[k].protocol()) +
             "\": " + JsonScores(totals[k].Total());
    out += "}}\n";
    std::fputs(out.c_str(), stdout);
    return 0;
  }

  size_t name_width = 5;
  for (const GtFile& g : gts) name_width = std::max(name_width, g.stem.size());
  const int w = int(name_width);
  for (size_t k = 0; k < totals.size(); ++k) {
    std::printf("%s%s\n", k ? "\n" : "", Describe(totals[k].protocol()));
    std::printf("%-*s  %9s  %9s  %9s  %9s\n", w, "frame", "precision", "recall", "F1", "IoU");
    auto print = [&](const std::string& name, const Scores& s) {
      std::printf("%-*s  %8.2f%%  %8.2f%%  %8.2f%%  %8.2f%%\n", w, name.c_str(), 100 * s.precision,
                  100 * s.recall, 100 * s.f1, 100 * s.iou);
    };
    for (size_t f = 0; f < gts.size(); ++f) print(gts[f].stem, per_frame[f][k]);
    print(AveragesPerFrame(totals[k].protocol()) ? "mean" : "total", totals[k].Total());
  }
  return 0;
}

}  // namespace lpir
