// The one optimisation fixpoint of Lobe IR: constant folding (constfold.h) then dead-code
// elimination (dce.h), repeated until neither changes the shader (at most 8 rounds: each round
// can only shrink the shader or turn ops into constants, and 8 has always been enough; the cap
// bounds time on pathological input). Run by lowering at -O1/-O2, by `lobe compile` on IR
// text, and by the runtime after specialising a layer.
#pragma once

#include "ir/ir.h"
#include "passes/consteval.h"

namespace lobe::passes {

struct OptimizeOptions {
  EvalOptions math;         // how folded math builtins compute
  int max_rounds = 8;       // see above
  bool algebraic = false;   // x * 0 and x - x fold (fold_constants): the runtime's pass only
  bool part_stores = false; // eliminate_dead_code's: the runtime's pass at OSL's -O2 only
};

// Folds and eliminates to a fixed point. Returns whether the shader changed.
bool optimize(ir::Shader& shader, const OptimizeOptions& options = {});

} // namespace lobe::passes
