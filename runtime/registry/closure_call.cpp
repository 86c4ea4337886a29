// Matching a closure call against the registry (see closure_call.h).
#include "closure_call.h"

#include <algorithm>

namespace lobe::registry {

namespace {

// The first problem of calling `e` with `args`, or None with the summed positional cost.
struct Attempt {
  CallProblem problem = CallProblem::None;
  size_t arg = 0;
  int cost = 0;
};

Attempt attempt(const ClosureEntry& e, const CallArgs& args) {
  size_t npos = positional_count(e);
  if (args.count < npos) return {CallProblem::TooFewArguments, args.count, 0};
  Attempt a;
  for (size_t i = 0; i < npos; ++i) {
    int k = args.cost(i, e.params[i].type);
    if (k == kNoFit) return {CallProblem::ArgumentType, i, 0};
    a.cost += k;
  }
  for (size_t i = npos; i < args.count; i += 2) {
    if (!args.is_string(i)) return {CallProblem::KeywordName, i, 0};
    if (i + 1 >= args.count) return {CallProblem::KeywordWithoutValue, args.count, 0};
  }
  return a;
}

int keyword_param(const ClosureEntry& e, std::optional<std::string_view> name) {
  if (!name) return kNameNotLiteral;
  for (size_t p = 0; p < e.params.size(); ++p)
    if (e.params[p].keyword && *name == e.params[p].name) return int(p);
  return kUnknownKeyword;
}

} // namespace

size_t positional_count(const ClosureEntry& e) {
  return size_t(
      std::count_if(e.params.begin(), e.params.end(), [](auto& p) { return !p.keyword; }));
}

ClosureMatch match_closure_call(std::span<const ClosureEntry> entries, std::string_view name,
                                const CallArgs& args) {
  ClosureMatch m;
  int best_cost = 0;
  for (const ClosureEntry& e : entries) {
    if (name != e.name) continue;
    m.candidates.push_back(&e);
    Attempt a = attempt(e, args);
    if (a.problem == CallProblem::None) {
      if (!m.entry || a.cost < best_cost) {
        m.entry = &e;
        best_cost = a.cost;
      }
    } else if (!m.problem_entry || a.arg > m.problem_arg) {
      m.problem = a.problem;
      m.problem_arg = a.arg;
      m.problem_entry = &e;
    }
  }
  if (m.candidates.empty()) m.problem = CallProblem::UnknownClosure;
  if (!m.entry) return m;
  m.problem = CallProblem::None;
  m.problem_entry = nullptr;
  m.problem_arg = 0;
  m.positional = positional_count(*m.entry);
  for (size_t i = m.positional; i + 1 < args.count; i += 2)
    m.keywords.push_back({i, keyword_param(*m.entry, args.literal(i))});
  return m;
}

} // namespace lobe::registry
