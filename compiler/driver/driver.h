// The compile driver: the one way from a shader file or text to verified Lobe IR, used by the
// runtime (ShadingSystem: group layers, add_shader_source, add_shader_ir, and through it
// `lobe shade`, `lobe render` and renderer plugins), `lobe compile` and `lobe info`.
//
//   lobe::driver::Options o;                    // -I/-D/-U, optimise, -Werror, ...
//   std::string path = lobe::driver::find_shader("matte", dirs);     // search.h
//   lobe::driver::Loaded l = lobe::driver::load_file(path, o);
//   for (const lobe::diag::Report& d : l.diagnostics) ...;           // or l.rendered()
//   if (l.shader) ...;
//
// A path ending in .lir is Lobe IR text (what `lobe compile` writes): parsed and verified;
// anything else is OSL source: preprocess, parse, type-check (frontend.h), lower
// (lower/lower.h). Optimisation is passes::optimize (passes/optimize.h), the one fold + DCE
// fixpoint. Every stage reports through one diag::DiagnosticEngine with ids
// (docs/diagnostics.md); the result carries them resolved (id, severity, file, line, column,
// message) and rendered once (the caret form the CLI prints). Nothing here prints.
#pragma once

#include "ast/ast.h"
#include "diag/diagnostics.h"
#include "driver/search.h"
#include "frontend.h"
#include "ir/ir.h"

#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace lobe::driver {

struct Options {
  frontend::FrontendOptions frontend; // -I, -D, -U, the standard header, a virtual file system
  bool lower = true;                  // false: OSL source stops after type checking (--emit=ast)
  bool optimize = false;              // passes::optimize after lowering, and on IR text
  bool fast_math = true;              // how folded math builtins compute
  bool warnings_as_errors = false;    // -Werror
  // IR text: recompute the derivative flags (after optimising), as `lobe compile` does for the
  // .lir it writes; off, the flags are the text's (the runtime's add_shader_ir).
  bool reanalyze_ir = false;
};

struct Timings {
  double preprocess_ms = 0, parse_ms = 0, sema_ms = 0, lower_ms = 0;
};

struct Loaded {
  std::optional<ir::Shader> shader;         // set when every stage succeeded (and lowering ran)
  std::unique_ptr<ast::TranslationUnit> tu; // OSL source: the typed AST
  std::vector<diag::Report> diagnostics;    // every stage's, in order, warnings and notes too
  Timings timings;
  bool ok = false; // no error in any stage
  // Every diagnostic's rendered text, concatenated ("" if none).
  std::string rendered() const;
};

// True for a path naming Lobe IR text (.lir).
bool is_ir_path(const std::string& path);

// Loads the file at `path` (IR text or OSL source, by its extension).
Loaded load_file(const std::string& path, const Options& options);
// OSL source text; `where` names it in diagnostics and is the base of relative #includes.
Loaded compile_source(const std::string& where, const std::string& text, const Options& options);
// Lobe IR text; `where` names it in diagnostics.
Loaded parse_ir(const std::string& where, const std::string& text, const Options& options);

} // namespace lobe::driver
