// A compact S-expression dump of the AST, for tests and `lobe compile --emit=ast`.
// After sema, expressions show their type and implicit casts: `(+:float a:float (cast:float 1))`.
#pragma once

#include "ast/ast.h"

#include <string>

namespace lobe::ast {

struct DumpOptions {
  bool types = false;  // append ":type" to expressions (after sema)
  bool stdlib = false; // include declarations from the standard header
};

std::string dump(const Expr* e, const DumpOptions& o = {});
std::string dump(const Stmt* s, const DumpOptions& o = {});
std::string dump(const Decl* d, const DumpOptions& o = {});
std::string dump(const TranslationUnit& tu, const DumpOptions& o = {});

} // namespace lobe::ast
