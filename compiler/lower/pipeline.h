// The whole compiler as one call: OSL source -> front end (preprocess, parse, sema) -> lowering
// -> optional optimisation (passes/optimize.h) -> verified Lobe IR, with every stage's
// diagnostics in one engine, resolved (diag::Report: id, severity, file, line, column) and
// rendered (`file:line:col: error: message`, the source line, a caret), and the time each stage
// took. The compile driver (compiler/driver/driver.h) runs it for OSL source; the lowering
// corpus (tests/lower) and the compile-pipeline benchmark call it directly.
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
  std::vector<diag::Report> reports;        // every diagnostic of every stage, in order
  std::string diagnostics;                  // the same, rendered; "" if none
  bool ok = false;                          // no error in any stage
  PipelineTimings timings;
};

PipelineResult compile_osl(const frontend::SourceInput& input, const PipelineOptions& options);

} // namespace lobe::lower
