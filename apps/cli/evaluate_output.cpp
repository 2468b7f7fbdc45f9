// The tables and the JSON object of `lpir-gseg evaluate` (see evaluate_output.h and its --help).
#include "apps/cli/evaluate_output.h"

#include <algorithm>
#include <cctype>
#include <cstdarg>
#include <cstdio>
#include <cstdlib>

namespace lpir {
namespace {

__attribute__((format(printf, 2, 3))) void Appendf(std::string* out, const char* format, ...) {
  char buf[512];
  va_list args;
  va_start(args, format);
  std::vsnprintf(buf, sizeof(buf), format, args);
  va_end(args);
  *out += buf;
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

std::string JsonCounts(const Counts& c) {
  return "{\"tp\": " + std::to_string(c.tp) + ", \"fp\": " + std::to_string(c.fp) +
         ", \"fn\": " + std::to_string(c.fn) + ", \"tn\": " + std::to_string(c.tn) +
         ", \"ignored\": " + std::to_string(c.ignored) + "}";
}

// `, "dg": {counts}, "pp": {counts}...` for one tally row.
std::string JsonCountsPerProtocol(const std::vector<Protocol>& protocols,
                                  const std::vector<Counts>& counts) {
  std::string out;
  for (size_t k = 0; k < protocols.size(); ++k)
    out += ", \"" + std::string(ProtocolName(protocols[k])) + "\": " + JsonCounts(counts[k]);
  return out;
}

std::string JsonByClass(const ClassBreakdown& b, Ontology ontology) {
  std::string out = "[";
  for (const auto& [cls, t] : b.classes()) {
    out += std::string(out.size() > 1 ? ", " : "") + "{\"class\": " + std::to_string(cls) +
           ", \"name\": " + JsonString(ClassName(ontology, cls)) +
           ", \"points\": " + std::to_string(t.points) +
           ", \"predicted_ground\": " + std::to_string(t.predicted_ground) +
           ", \"share\": " + JsonNumber(double(t.predicted_ground) / double(t.points)) +
           JsonCountsPerProtocol(b.protocols(), t.counts) + "}";
  }
  return out + "]";
}

std::string JsonByRange(const RangeBreakdown& b) {
  std::string out = "[";
  for (size_t band = 0; band < kRangeBands; ++band) {
    const RangeTally& t = b.bands()[band];
    out += std::string(band ? ", " : "") + "{\"band\": " + JsonString(RangeBandName(band)) +
           ", \"from\": " + JsonNumber(band ? kRangeBandEdges[band - 1] : 0.0);
    if (band < kRangeBandEdges.size()) out += ", \"to\": " + JsonNumber(kRangeBandEdges[band]);
    out += ", \"points\": " + std::to_string(t.points) +
           JsonCountsPerProtocol(b.protocols(), t.counts) + "}";
  }
  return out + "]";
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

std::string Upper(const char* s) {
  std::string out(s);
  for (char& c : out) c = char(std::toupper(static_cast<unsigned char>(c)));
  return out;
}

void AppendScoreTables(const EvaluateResults& r, std::string* out) {
  size_t name_width = 5;
  for (const std::string& f : r.frames) name_width = std::max(name_width, f.size());
  const int w = int(name_width);
  for (size_t k = 0; k < r.totals.size(); ++k) {
    Appendf(out, "%s%s\n", k ? "\n" : "", Describe(r.totals[k].protocol()));
    Appendf(out, "%-*s  %9s  %9s  %9s  %9s\n", w, "frame", "precision", "recall", "F1", "IoU");
    auto row = [&](const std::string& name, const Scores& s) {
      Appendf(out, "%-*s  %8.2f%%  %8.2f%%  %8.2f%%  %8.2f%%\n", w, name.c_str(), 100 * s.precision,
              100 * s.recall, 100 * s.f1, 100 * s.iou);
    };
    for (size_t f = 0; f < r.frames.size(); ++f) row(r.frames[f], r.per_frame[f][k]);
    row(AveragesPerFrame(r.totals[k].protocol()) ? "mean" : "total", r.totals[k].Total());
  }
}

// `-` where the row has points and the protocol scores none of them (all ignored).
void AppendCount(uint64_t value, const Counts& c, uint64_t points, std::string* out) {
  if (points > 0 && c.ignored == points)
    Appendf(out, "  %9s", "-");
  else
    Appendf(out, "  %9llu", static_cast<unsigned long long>(value));
}

void AppendByClassTable(const ClassBreakdown& b, Ontology ontology, size_t frames,
                        std::string* out) {
  int w = 5;
  for (const auto& entry : b.classes())
    w = std::max(w, 4 + int(std::string(ClassName(ontology, entry.first)).size()));
  Appendf(out,
          "\nBy ground-truth class (%s), summed over %zu frame%s; FP and FN per protocol, "
          "'-' where it scores none of the class\n",
          OntologyName(ontology), frames, frames == 1 ? "" : "s");
  Appendf(out, "%-*s  %10s  %10s  %7s", w, "class", "points", "pred.gnd", "share");
  for (Protocol p : b.protocols())
    Appendf(out, "  %9s  %9s", (Upper(ProtocolName(p)) + " FP").c_str(),
            (Upper(ProtocolName(p)) + " FN").c_str());
  *out += "\n";
  for (const auto& [cls, t] : b.classes()) {
    Appendf(out, "%3u %-*s  %10llu  %10llu  %6.2f%%", cls, w - 4, ClassName(ontology, cls),
            static_cast<unsigned long long>(t.points),
            static_cast<unsigned long long>(t.predicted_ground),
            100.0 * double(t.predicted_ground) / double(t.points));
    for (const Counts& c : t.counts) {
      AppendCount(c.fp, c, t.points, out);
      AppendCount(c.fn, c, t.points, out);
    }
    *out += "\n";
  }
}

void AppendByRangeTable(const RangeBreakdown& b, size_t frames, std::string* out) {
  Appendf(out, "\nBy horizontal range sqrt(x^2 + y^2) in metres, summed over %zu frame%s\n", frames,
          frames == 1 ? "" : "s");
  Appendf(out, "%-6s  %10s", "band", "points");
  for (Protocol p : b.protocols())
    for (const char* what : {" TP", " FP", " FN"})
      Appendf(out, "  %9s", (Upper(ProtocolName(p)) + what).c_str());
  *out += "\n";
  for (size_t band = 0; band < kRangeBands; ++band) {
    const RangeTally& t = b.bands()[band];
    Appendf(out, "%-6s  %10llu", RangeBandName(band).c_str(),
            static_cast<unsigned long long>(t.points));
    for (const Counts& c : t.counts)
      for (uint64_t v : {c.tp, c.fp, c.fn}) AppendCount(v, c, t.points, out);
    *out += "\n";
  }
}

}  // namespace

std::string FormatJson(const EvaluateResults& r) {
  std::string out = "{\"frames\": [";
  for (size_t f = 0; f < r.frames.size(); ++f) {
    out += std::string(f ? ", " : "") + "{\"name\": " + JsonString(r.frames[f]);
    for (size_t k = 0; k < r.totals.size(); ++k)
      out += ", \"" + std::string(ProtocolName(r.totals[k].protocol())) +
             "\": " + JsonScores(r.per_frame[f][k]);
    out += "}";
  }
  out += "], \"total\": {";
  for (size_t k = 0; k < r.totals.size(); ++k)
    out += std::string(k ? ", " : "") + "\"" + ProtocolName(r.totals[k].protocol()) +
           "\": " + JsonScores(r.totals[k].Total());
  out += "}";
  if (r.by_class) out += ", \"by_class\": " + JsonByClass(*r.by_class, r.ontology);
  if (r.by_range) out += ", \"by_range\": " + JsonByRange(*r.by_range);
  if (!r.missing.empty()) {
    out += ", \"missing\": [";
    for (size_t k = 0; k < r.missing.size(); ++k)
      out += std::string(k ? ", " : "") + JsonString(r.missing[k]);
    out += "]";
  }
  return out + "}\n";
}

std::string FormatTables(const EvaluateResults& r) {
  std::string out;
  AppendScoreTables(r, &out);
  if (r.by_class) AppendByClassTable(*r.by_class, r.ontology, r.frames.size(), &out);
  if (r.by_range) AppendByRangeTable(*r.by_range, r.frames.size(), &out);
  return out;
}

}  // namespace lpir
