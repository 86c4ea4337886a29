// Constant folding and propagation, on any ir::Shader (the runtime re-runs it after turning
// instance values into Const symbols):
//  * within a basic block, a symbol last assigned a constant is replaced by that constant in
//    the ops that read it;
//  * a pure op whose inputs are all constants becomes `assign dst $c` (values computed with
//    the run-time semantics, consteval.h);
//  * `cbr` on a constant becomes `br` to the taken target;
//  * closure algebra: a closure scaled by a zero weight becomes the null closure, adding a null
//    closure becomes a copy of the other operand;
//  * with `algebraic` (the runtime's pass over a specialised group, as OSL's runtime optimizer;
//    not oslc's compile-time folding), for float, int and triple x and a constant all 0 or all
//    1: x * 0 = 0 * x = 0 and x - x = 0 (also for a copy of x made in the same block: y = x;
//    x - y), and x + 0 = 0 + x = x - 0 = x * 1 = 1 * x = x / 1 = x. They differ from computing
//    only where x is infinite or NaN, and in the sign of a zero.
// Leaves dead ops and unreachable code for dead-code elimination (dce.h).
#pragma once

#include "ir/ir.h"
#include "passes/consteval.h"

namespace lobe::passes {

// Returns whether the shader changed. `options` decide how math builtins fold. `late` (with
// `algebraic`): also pow(0, x) = 0 for a varying x, which a caller asks for only once folding
// and dead-code elimination change nothing else (optimize()): applied while the exponent could
// still become a constant, it would answer 0 where pow(0, 0) is 1.
bool fold_constants(ir::Shader& shader, const EvalOptions& options = {}, bool algebraic = false,
                    bool late = false);

} // namespace lobe::passes
