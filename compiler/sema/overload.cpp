// oslc's choice among scored candidates (see overload.h).
#include "sema/overload.h"

#include <algorithm>
#include <optional>

namespace lobe::sema {

namespace {

// The candidates with the best score (newest first), or none.
std::vector<size_t> best_scored(std::span<const int> scores) {
  int best = kNotViable;
  for (int s : scores) best = std::max(best, s);
  std::vector<size_t> tied;
  if (best == kNotViable) return tied;
  for (size_t i = 0; i < scores.size(); ++i)
    if (scores[i] == best) tied.push_back(i);
  return tied;
}

// The one tied candidate whose return type matches `expected` strictly best, if there is one.
std::optional<size_t> by_expected(const std::vector<size_t>& tied, std::span<const Type> returns,
                                  const Type& expected) {
  int best = 0, count = 0;
  size_t at = 0;
  for (size_t i : tied) {
    int s = match_score(expected, returns[i]);
    if (s > best) {
      best = s;
      count = 0;
      at = i;
    }
    count += s == best;
  }
  if (best == 0 || count != 1) return std::nullopt;
  return at;
}

} // namespace

OverloadChoice choose_overload(std::span<const int> scores, std::span<const Type> returns,
                               const Type* expected) {
  OverloadChoice c;
  std::vector<size_t> tied = best_scored(scores);
  if (tied.empty()) return c;
  if (tied.size() == 1) {
    c.kind = OverloadChoice::Kind::Unique;
    c.chosen = tied[0];
    return c;
  }
  if (expected) {
    if (auto one = by_expected(tied, returns, *expected)) {
      c.kind = OverloadChoice::Kind::ByExpectedType;
      c.chosen = *one;
      return c;
    }
  }
  // Stable: within a rank the chain order (newest first) stays.
  std::stable_sort(tied.begin(), tied.end(), [&](size_t a, size_t b) {
    return return_rank(returns[a]) < return_rank(returns[b]);
  });
  auto structs = std::count_if(tied.begin(), tied.end(),
                               [&](size_t i) { return return_rank(returns[i]) == kStructRank; });
  if (structs >= 2) {
    c.kind = OverloadChoice::Kind::StructTie;
    c.others = std::move(tied);
    return c;
  }
  c.kind = OverloadChoice::Kind::ByRank;
  c.chosen = tied[0];
  c.others.assign(tied.begin() + 1, tied.end());
  return c;
}

} // namespace lobe::sema
