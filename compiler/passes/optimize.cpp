// The fold + DCE fixpoint (optimize.h).
#include "passes/optimize.h"

#include "passes/constfold.h"
#include "passes/dce.h"

namespace lobe::passes {

bool optimize(ir::Shader& shader, const OptimizeOptions& options) {
  bool any = false;
  for (int round = 0; round < options.max_rounds; ++round) {
    if (options.before_fold) options.before_fold(shader);
    bool changed = fold_constants(shader, options.math, options.algebraic);
    if (options.after_fold) changed |= options.after_fold(shader);
    changed |= eliminate_dead_code(shader);
    any |= changed;
    if (!changed) break;
  }
  return any;
}

} // namespace lobe::passes
