// Compile-time evaluation of one op over constant operands, with the run-time semantics of
// docs/ir.md (conversion to the destination type, division by zero gives 0, ...). Used by
// constant folding. Covers the core arithmetic, comparison, integer, component ops, the math
// library (runtime/mathlib/mathops.h: the code the run time calls, so a folded value is the
// value the op computes) and hash() of numbers; anything else is "not evaluable"
// (std::nullopt), never a guess.
#pragma once

#include "ir/ir.h"

#include <optional>
#include <string>
#include <vector>

namespace lobe::passes {

// How the math builtins compute (CompileOptions::fast_math; docs/language.md, "Math").
struct EvalOptions {
  bool fast_math = true;
  // Float comparisons and `!` as C computes them (a NaN is unequal to everything, `!nan` is 0),
  // as OSL's -O2 optimiser folds them; otherwise as the generated code computes them (a NaN
  // makes every comparison true, and `!nan` 1).
  bool c_compares = false;
};

struct ConstArg {
  ir::Type type;
  const std::vector<ir::ConstValue>* value;
};

// Converts a constant by the `assign` rules; nullopt if not a defined conversion.
std::optional<std::vector<ir::ConstValue>>
convert_const(const ir::Type& from, const std::vector<ir::ConstValue>& v, const ir::Type& to);

// The value the op `opcode dst srcs...` writes to dst (of type `dst`), or nullopt.
std::optional<std::vector<ir::ConstValue>> evaluate(ir::Opcode opcode, const ir::Type& dst,
                                                    const std::vector<ConstArg>& srcs,
                                                    const EvalOptions& options = {});

} // namespace lobe::passes
