// The type checker: resolves names, types every expression, resolves calls (overloads of user
// functions and builtins, struct constructors, closures from the registry with their keyword
// arguments), makes every implicit conversion an explicit CastExpr, and reports every semantic
// error (see the invariants listed at the top of ast/ast.h).
#pragma once

#include "ast/ast.h"
#include "diag/diagnostics.h"

#include <span>

namespace lobe::registry {
struct ClosureEntry;
}

namespace lobe::sema {

struct SemaOptions {
  std::span<const registry::ClosureEntry> closures; // the closure registry's entries
};

// Type-checks `tu` in place; true when no error was reported.
bool check(ast::TranslationUnit& tu, diag::DiagnosticEngine& diags, const SemaOptions& options);

} // namespace lobe::sema
