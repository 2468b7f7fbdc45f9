#include "host/io/suggest.h"

#include <algorithm>
#include <cctype>

namespace lpir {
namespace {

char Lower(char c) { return char(std::tolower(static_cast<unsigned char>(c))); }

// Optimal string alignment distance between a and b, letter case ignored: insertions,
// deletions, substitutions and transpositions of adjacent letters each cost 1 ("segmnet" is 1
// from "segment").
size_t EditDistance(const std::string& a, const std::string& b) {
  const size_t n = a.size(), m = b.size();
  std::vector<std::vector<size_t>> d(n + 1, std::vector<size_t>(m + 1));
  for (size_t i = 0; i <= n; ++i) d[i][0] = i;
  for (size_t j = 0; j <= m; ++j) d[0][j] = j;
  for (size_t i = 1; i <= n; ++i) {
    for (size_t j = 1; j <= m; ++j) {
      const size_t cost = Lower(a[i - 1]) == Lower(b[j - 1]) ? 0 : 1;
      d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + cost});
      if (i > 1 && j > 1 && Lower(a[i - 1]) == Lower(b[j - 2]) &&
          Lower(a[i - 2]) == Lower(b[j - 1]))
        d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
    }
  }
  return d[n][m];
}

}  // namespace

std::string ClosestName(const std::string& typed, const std::vector<std::string>& known) {
  std::string best;
  size_t best_distance = 0;
  for (const std::string& k : known) {
    const size_t distance = EditDistance(typed, k);
    const size_t limit = std::max<size_t>(1, std::max(typed.size(), k.size()) / 3);
    if (distance > limit || (!best.empty() && distance >= best_distance)) continue;
    best = k;
    best_distance = distance;
  }
  return best;
}

std::string DidYouMean(const std::string& typed, const std::vector<std::string>& known) {
  const std::string name = ClosestName(typed, known);
  return name.empty() ? "" : " (did you mean " + name + "?)";
}

}  // namespace lpir
