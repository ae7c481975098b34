#include "core/suggest.h"

#include <algorithm>
#include <limits>

namespace brdfit {

std::size_t EditDistance(const std::string& a, const std::string& b) {
  // d[i][j]: distance between the first i characters of a and the first j of b.
  const std::size_t n = a.size(), m = b.size();
  std::vector<std::vector<std::size_t>> d(n + 1, std::vector<std::size_t>(m + 1));
  for (std::size_t i = 0; i <= n; ++i) d[i][0] = i;
  for (std::size_t j = 0; j <= m; ++j) d[0][j] = j;
  for (std::size_t i = 1; i <= n; ++i) {
    for (std::size_t j = 1; j <= m; ++j) {
      const std::size_t cost = a[i - 1] == b[j - 1] ? 0 : 1;
      d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + cost});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1]) {
        d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);  // a transposition
      }
    }
  }
  return d[n][m];
}

std::vector<std::string> ClosestNames(const std::string& given,
                                      const std::vector<std::string>& candidates) {
  const std::size_t limit = given.size() <= 4 ? 1 : given.size() <= 8 ? 2 : 3;
  std::size_t best = std::numeric_limits<std::size_t>::max();
  std::vector<std::string> out;
  for (const std::string& c : candidates) {
    if (c == given) continue;
    const std::size_t d = EditDistance(given, c);
    if (d > limit || d > best) continue;
    if (d < best) out.clear();
    best = d;
    if (out.size() < 3) out.push_back(c);
  }
  return out;
}

std::string DidYouMean(const std::string& given, const std::vector<std::string>& candidates) {
  const std::vector<std::string> c = ClosestNames(given, candidates);
  if (c.empty()) return "";
  std::string s = "did you mean " + c[0];
  for (std::size_t i = 1; i < c.size(); ++i) s += (i + 1 == c.size() ? " or " : ", ") + c[i];
  return s + "?";
}

std::string SuggestionAfter(const std::string& given, const std::vector<std::string>& candidates) {
  const std::string hint = DidYouMean(given, candidates);
  return hint.empty() ? "" : " (" + hint + ")";
}

}  // namespace brdfit
