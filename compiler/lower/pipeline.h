// The whole compiler as one call: OSL source -> front end (preprocess, parse, sema) -> lowering
// -> optional optimisation (constant folding + dead-code elimination) -> verified Lobe IR, with
// every diagnostic rendered as text (`file:line:col: error: message`, the source line, a caret)
// and the time each stage took. Used by `lobe compile` / `lobe info`, the lowering corpus
// (tests/lower) and the compile-pipeline benchmark.
#pragma once

#include "frontend.h"
#include "lower/lower.h"

#include <memory>
#include <optional>
#include <string>

namespace lobe::lower {

struct PipelineOptions {
  frontend::FrontendOptions frontend;
  bool lower = true;               // false: stop after sema (--emit=ast)
  bool optimize = false;           // constant folding + dead-code elimination after lowering
  bool fast_math = true;           // how folded math builtins compute (LowerOptions)
  bool warnings_as_errors = false; // -Werror
};

struct PipelineTimings {
  double preprocess_ms = 0, parse_ms = 0, sema_ms = 0, lower_ms = 0;
};

struct PipelineResult {
  std::unique_ptr<ast::TranslationUnit> tu; // the typed AST (always set)
  std::optional<ir::Shader> shader;         // set when every stage succeeded (and lower was asked)
  std::string diagnostics;                  // rendered errors and warnings, "" if none
  bool ok = false;                          // no error in any stage
  PipelineTimings timings;
};

PipelineResult compile_osl(const frontend::SourceInput& input, const PipelineOptions& options);

// Renders a lowering error like the front end's diagnostics (location, source line, caret).
std::string render_lower_diag(const LowerDiag& d, const diag::SourceManager& sm);

} // namespace lobe::lower
