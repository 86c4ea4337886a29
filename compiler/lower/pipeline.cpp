// The compile pipeline (pipeline.h): front end, lowering, passes, with stage timings.
#include "lower/pipeline.h"

#include "diag/source_manager.h"

#include <chrono>

namespace lobe::lower {

namespace {

// Every stage's diagnostics, resolved and rendered once.
void collect(PipelineResult& r, const diag::DiagnosticEngine& diags) {
  if (!r.tu->sources) return;
  r.reports = diag::resolve_all(diags, *r.tu->sources);
  for (const diag::Report& d : r.reports) r.diagnostics += d.text;
}

} // namespace

PipelineResult compile_osl(const frontend::SourceInput& input, const PipelineOptions& options) {
  PipelineResult r;
  diag::DiagnosticEngine diags;
  diags.set_warnings_as_errors(options.warnings_as_errors);
  frontend::FrontendTimings ft;
  r.tu = frontend::compile_to_ast(input, options.frontend, diags, &ft);
  r.timings.preprocess_ms = ft.preprocess_ms;
  r.timings.parse_ms = ft.parse_ms;
  r.timings.sema_ms = ft.sema_ms;
  if (diags.has_errors() || !options.lower) {
    collect(r, diags);
    r.ok = !diags.has_errors();
    return r;
  }
  auto t0 = std::chrono::steady_clock::now();
  LowerResult lr = lower(*r.tu, diags, LowerOptions{options.optimize, options.fast_math});
  r.timings.lower_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  collect(r, diags);
  if (!lr.shader) return r;
  r.shader = std::move(lr.shader);
  r.ok = true;
  return r;
}

} // namespace lobe::lower
