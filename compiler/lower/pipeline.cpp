// The compile pipeline (pipeline.h): front end, lowering, passes, with stage timings.
#include "lower/pipeline.h"

#include "diag/source_manager.h"

#include <chrono>

namespace lobe::lower {

std::string render_lower_diag(const LowerDiag& d, const diag::SourceManager& sm) {
  if (!d.range.valid()) return "error: " + d.message + "\n";
  diag::PresumedLoc p = sm.presumed(d.range.begin);
  if (!p.valid()) return "error: " + d.message + "\n";
  std::string out = std::string(p.file) + ":" + std::to_string(p.line) + ":" +
                    std::to_string(p.column) + ": error: " + d.message + "\n";
  std::string_view line = sm.line_text(d.range.begin);
  if (line.empty()) return out;
  out += std::string(line) + "\n";
  std::string caret;
  for (int i = 1; i < p.column && size_t(i - 1) < line.size(); ++i)
    caret += line[size_t(i - 1)] == '\t' ? '\t' : ' ';
  return out + caret + "^\n";
}

PipelineResult compile_osl(const frontend::SourceInput& input, const PipelineOptions& options) {
  PipelineResult r;
  diag::DiagnosticEngine diags;
  diags.set_warnings_as_errors(options.warnings_as_errors);
  frontend::FrontendTimings ft;
  r.tu = frontend::compile_to_ast(input, options.frontend, diags, &ft);
  r.timings.preprocess_ms = ft.preprocess_ms;
  r.timings.parse_ms = ft.parse_ms;
  r.timings.sema_ms = ft.sema_ms;
  if (r.tu->sources) r.diagnostics = diag::render_all(diags, *r.tu->sources);
  if (diags.has_errors()) return r;
  if (!options.lower) {
    r.ok = true;
    return r;
  }
  auto t0 = std::chrono::steady_clock::now();
  LowerResult lr = lower(*r.tu, LowerOptions{options.optimize, options.fast_math});
  r.timings.lower_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  for (const LowerDiag& d : lr.diags) r.diagnostics += render_lower_diag(d, *r.tu->sources);
  if (!lr.shader) return r;
  r.shader = std::move(lr.shader);
  r.ok = true;
  return r;
}

} // namespace lobe::lower
