// The front end's one entry point: preprocess (with the standard header included
// automatically) -> lex -> parse -> type-check, giving a typed AST (ast/ast.h) and diagnostics.
//
//   lobe::diag::DiagnosticEngine diags;
//   lobe::frontend::FrontendTimings t;
//   auto tu = lobe::frontend::compile_to_ast({"shader.osl"}, {}, diags, &t);
//   if (diags.has_errors()) print(lobe::diag::render_all(diags, *tu->sources));
//
// The translation unit is always returned (with its SourceManager in tu->sources, which
// renders the diagnostics); it is fit for lowering only when no error was reported.
// preprocess() stops after the first stage, for `lobe compile -E`.
#pragma once

#include "ast/ast.h"
#include "diag/diagnostics.h"

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace lobe::frontend {

// What to compile: a file path, or source text (`path` then only names it in diagnostics and
// is the base for relative #includes).
struct SourceInput {
  std::string path;
  std::optional<std::string> text;
};

struct FrontendOptions {
  std::vector<std::string> include_dirs; // -I
  std::vector<std::string> defines;      // -D NAME or NAME=value
  std::vector<std::string> undefines;    // -U
  bool include_stdlib = true;            // include stdosl.h first
  // Reads files (tests use a virtual file system); null: the real file system.
  std::function<std::optional<std::string>(const std::string&)> read_file;
};

// Wall-clock time per stage, for `--stats` and bench/.
struct FrontendTimings {
  double preprocess_ms = 0;
  double parse_ms = 0; // lex + parse
  double sema_ms = 0;
};

std::unique_ptr<ast::TranslationUnit> compile_to_ast(const SourceInput& input,
                                                     const FrontendOptions& options,
                                                     diag::DiagnosticEngine& diags,
                                                     FrontendTimings* timings = nullptr);

// Only preprocesses (`lobe compile -E`): the preprocessed text of the standard header (unless
// include_stdlib is false) and the input, with cpp's `# N "file"` line markers. Diagnostics go
// to `diags`, rendered with `sources`.
std::string preprocess(const SourceInput& input, const FrontendOptions& options,
                       diag::DiagnosticEngine& diags, diag::SourceManager& sources);

} // namespace lobe::frontend
