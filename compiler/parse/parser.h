// The parser: recursive descent from tokens to the AST (ast/ast.h), for all of OSL's language:
// shader, function (nested, prototypes with [[ int builtin = 1 ]], operator overloads) and
// struct declarations, parameters with defaults and metadata, every statement and expression.
//
// Errors are reported and parsing resumes at the next statement or declaration boundary
// (panic mode), so one file reports many errors. A nesting-depth cap turns pathologically deep
// input into one error instead of a stack overflow.
#pragma once

#include "ast/ast.h"
#include "diag/diagnostics.h"
#include "lex/lexer.h"

namespace lobe::parse {

struct ParseOptions {
  int max_depth = 512; // nested blocks, parentheses, unary operators, operator chains
};

// Parses a token stream, appending declarations to `tu`.
void parse(const lex::TokenStream& ts, diag::DiagnosticEngine& diags, ast::TranslationUnit& tu,
           const ParseOptions& options = {});

} // namespace lobe::parse
