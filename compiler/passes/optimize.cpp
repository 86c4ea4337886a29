// The fold + DCE fixpoint (optimize.h).
#include "passes/optimize.h"

#include "passes/constfold.h"
#include "passes/dce.h"

namespace lobe::passes {

bool optimize(ir::Shader& shader, const OptimizeOptions& options) {
  bool any = false;
  for (int round = 0; round < options.max_rounds; ++round) {
    bool changed = fold_constants(shader, options.math, options.algebraic);
    changed |= eliminate_dead_code(shader, options.part_stores);
    if (!changed && options.algebraic) { // nothing else folds: pow(0, x) = 0 (fold_constants)
      changed = fold_constants(shader, options.math, true, /*late=*/true);
      changed |= eliminate_dead_code(shader, options.part_stores);
    }
    any |= changed;
    if (!changed) break;
  }
  return any;
}

} // namespace lobe::passes
