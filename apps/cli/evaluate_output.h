// What `lpir-gseg evaluate` prints: its results as tables or as one JSON object.
#pragma once
#include <optional>
#include <string>
#include <vector>

#include "host/eval/by_class.h"
#include "host/eval/by_range.h"
#include "host/eval/metrics.h"
#include "host/eval/ontology.h"

namespace lpir {

struct EvaluateResults {
  Ontology ontology = Ontology::kSemanticKitti;
  std::vector<std::string> frames;             // ground-truth stems, in the order scored
  std::vector<SequenceScores> totals;          // one per protocol, in the order asked
  std::vector<std::vector<Scores>> per_frame;  // [frame][protocol]
  std::optional<ClassBreakdown> by_class;      // with --by-class
  std::optional<RangeBreakdown> by_range;      // with --by-range
  std::vector<std::string> missing;            // predictions not found, not scored
};

// {"frames": [...], "total": {...}}, then "by_class" and "by_range" when present, and
// "missing" (the prediction files not found) when some were; one line.
std::string FormatJson(const EvaluateResults& r);
// One table per protocol (frames, then total or mean), then the per-class and per-range tables
// when present.
std::string FormatTables(const EvaluateResults& r);

}  // namespace lpir
