// Evaluates the constant expression of #if / #elif after macro expansion (identifiers left
// over are 0, as in C). Integer arithmetic in 64 bits with C's operators and precedence.
#pragma once

#include "pp/pp_token.h"

#include <optional>
#include <string>
#include <vector>

namespace lobe::pp {

struct PPExprResult {
  std::optional<long long> value; // empty on error
  std::string error;              // what went wrong
  diag::SourceLoc where;
};

PPExprResult evaluate_pp_expr(const std::vector<PPToken>& toks);

} // namespace lobe::pp
