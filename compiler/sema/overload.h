// Choosing one of a call's candidates, as oslc 1.13 does. The rules were measured on oslc
// (about 3,000 shaders); docs/language.md, "Calls and overload resolution", states them.
//
//   1. Only the candidates whose every argument matches (match_score > 0) apply; among them the
//      highest sum of argument scores wins.
//   2. A tie is decided by the type the context expects, if exactly one tied candidate's return
//      type matches it best (match_score(expected, ret) > 0); otherwise the expected type is
//      ignored altogether.
//   3. Still tied: two or more candidates returning structs are an error; otherwise the lowest
//      return_rank wins, the newest declaration among equal ranks, with a warning.
//
// Pure: the caller scores the candidates (newest declaration first) and reports diagnostics.
#pragma once

#include "sema/types.h"

#include <span>
#include <vector>

namespace lobe::sema {

inline constexpr int kNotViable = -1; // a candidate's score when some argument does not match

struct OverloadChoice {
  enum class Kind {
    NoMatch,        // no candidate applies
    Unique,         // one best argument score
    ByExpectedType, // a tie the expected type decided
    ByRank,         // a tie decided by return rank: a warning
    StructTie,      // a tie between struct-returning candidates: an error
  } kind = Kind::NoMatch;
  size_t chosen = 0;          // index of the chosen candidate (Unique, ByExpectedType, ByRank)
  std::vector<size_t> others; // ByRank: the other tied candidates; StructTie: all tied ones;
                              // in rank order, newest first within a rank
};

// `scores[i]` is candidate i's summed argument score (or kNotViable) and `returns[i]` its return
// type; candidates are ordered newest declaration first. `expected` may be null (no context).
OverloadChoice choose_overload(std::span<const int> scores, std::span<const Type> returns,
                               const Type* expected);

} // namespace lobe::sema
