// Lowering: a type-checked AST (compiler/ast/ast.h, after sema) to Lobe IR (docs/ir.md).
//
// User functions and the standard header's functions are inlined (OSL has no recursion);
// `output` arguments alias the caller's variable (or go through a copy-in/copy-out temporary
// for an element or component); `return` jumps to the end of the inlined body; structs are
// flattened into one symbol per field ("s.a"; arrays of structs into one array per field);
// operator overloads are inlined calls; parameters whose default is not a constant get init
// ops; metadata is copied as given; every op has a source location; temporaries are reused
// after the statement that needed them; literal constants are deduplicated.
#pragma once

#include "ast/ast.h"
#include "diag/diagnostics.h"
#include "ir/ir.h"

#include <optional>
#include <string>
#include <vector>

namespace lobe::lower {

struct LowerOptions {
  bool optimize = false; // run constant folding and dead-code elimination afterwards
  bool fast_math = true; // how folded math builtins compute (CompileOptions::fast_math)
};

struct LowerResult {
  std::optional<ir::Shader> shader; // set on success
};

// Lowers the translation unit's shader. Derivative flags are computed (passes/derivs.h).
// Constructs that have no IR form are reported to `diags` (err_lower_*, with the source range
// of the construct; rendered with the front end's diagnostics and tu.sources).
LowerResult lower(const ast::TranslationUnit& tu, diag::DiagnosticEngine& diags,
                  const LowerOptions& options = {});

} // namespace lobe::lower
