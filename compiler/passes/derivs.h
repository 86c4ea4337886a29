// Derivative analysis: sets Symbol::derivs on exactly the symbols whose d/dx, d/dy some op
// reads (Dx, Dy, Dz, filterwidth, area, calculatenormal, filtered texture lookups: the
// `derivs` column of opcodes.h), closed backwards through the ops that propagate derivatives
// (`kPropagates`): if an op's result needs derivatives, so do its float-based inputs.
// Constants, ints and strings never carry derivatives.
#pragma once

#include "ir/ir.h"

namespace lobe::passes {

// Returns whether any symbol's `derivs` flag changed.
bool analyze_derivatives(ir::Shader& shader);

} // namespace lobe::passes
