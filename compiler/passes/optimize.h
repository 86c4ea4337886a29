// The one optimisation fixpoint of Lobe IR: constant folding (constfold.h) then dead-code
// elimination (dce.h), repeated until neither changes the shader (at most 8 rounds: each round
// can only shrink the shader or turn ops into constants, and 8 has always been enough; the cap
// bounds time on pathological input). Run by lowering at -O1/-O2, by `lobe compile` on IR
// text, and by the runtime after specialising a layer (with its string-compare hooks).
#pragma once

#include "ir/ir.h"
#include "passes/consteval.h"

#include <functional>

namespace lobe::passes {

struct OptimizeOptions {
  EvalOptions math;       // how folded math builtins compute
  int max_rounds = 8;     // see above
  bool algebraic = false; // x * 0 and x - x fold (fold_constants): the runtime's pass only
  // Optional steps of each round, for a caller that folds something constant folding must not
  // see (the runtime's string compares, runtime/group/group_build.cpp): `before_fold` runs
  // before folding (its result is not counted as a change), `after_fold` after it (its result
  // is). Null: none.
  std::function<void(ir::Shader&)> before_fold;
  std::function<bool(ir::Shader&)> after_fold;
};

// Folds and eliminates to a fixed point. Returns whether the shader changed.
bool optimize(ir::Shader& shader, const OptimizeOptions& options = {});

} // namespace lobe::passes
