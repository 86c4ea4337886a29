// The compile driver (driver.h).
#include "driver/driver.h"

#include "diag/source_manager.h"
#include "ir/parser.h"
#include "ir/verifier.h"
#include "lower/pipeline.h"
#include "passes/derivs.h"
#include "passes/optimize.h"
#include "pp/preprocessor.h"

namespace lobe::driver {

std::string Loaded::rendered() const {
  std::string out;
  for (const diag::Report& d : diagnostics) out += d.text;
  return out;
}

bool is_ir_path(const std::string& path) { return path.ends_with(".lir"); }

namespace {

// OSL source through the compile pipeline (front end, lowering, optimisation).
Loaded compile_osl(const frontend::SourceInput& input, const Options& options) {
  lower::PipelineOptions po;
  po.frontend = options.frontend;
  po.lower = options.lower;
  po.optimize = options.optimize;
  po.fast_math = options.fast_math;
  po.warnings_as_errors = options.warnings_as_errors;
  lower::PipelineResult pr = lower::compile_osl(input, po);
  Loaded r;
  r.shader = std::move(pr.shader);
  r.tu = std::move(pr.tu);
  r.diagnostics = std::move(pr.reports);
  r.timings = {pr.timings.preprocess_ms, pr.timings.parse_ms, pr.timings.sema_ms,
               pr.timings.lower_ms};
  r.ok = pr.ok;
  return r;
}

// A parse error of IR text at its line and column, shown with the line and a caret.
diag::Report ir_parse_report(const std::string& where, const std::string& text,
                             const ir::ParseError& e) {
  diag::SourceManager sm;
  int id = sm.add_file(where, text);
  uint32_t offset = 0;
  for (int line = 1; line < e.line && offset < text.size(); ++offset) line += text[offset] == '\n';
  offset += uint32_t(std::max(0, e.column - 1));
  offset = std::min<uint32_t>(offset, uint32_t(text.size()));
  diag::DiagnosticEngine engine;
  engine.report(diag::DiagId::err_ir_parse,
                e.line > 0 ? sm.buffer_start(id).advanced(offset) : diag::SourceLoc{}, {e.message});
  return diag::resolve_all(engine, sm).front();
}

} // namespace

Loaded parse_ir(const std::string& where, const std::string& text, const Options& options) {
  Loaded r;
  ir::ParseResult pr = ir::parse(text);
  if (!pr.shader) {
    r.diagnostics.push_back(ir_parse_report(where, text, pr.error));
    return r;
  }
  for (const std::string& e : ir::verify(*pr.shader))
    r.diagnostics.push_back(diag::file_report(diag::DiagId::err_ir_invalid, where, {e}));
  if (!r.diagnostics.empty()) return r;
  if (options.optimize) passes::optimize(*pr.shader, {.math = {options.fast_math}});
  if (options.reanalyze_ir) passes::analyze_derivatives(*pr.shader);
  r.shader = std::move(pr.shader);
  r.ok = true;
  return r;
}

Loaded compile_source(const std::string& where, const std::string& text, const Options& options) {
  return compile_osl({where, text}, options);
}

Loaded load_file(const std::string& path, const Options& options) {
  if (!is_ir_path(path)) return compile_osl({path, std::nullopt}, options);
  const auto& read = options.frontend.read_file;
  std::optional<std::string> text = read ? read(path) : pp::read_file_from_disk(path);
  if (!text) {
    Loaded r;
    r.diagnostics.push_back(diag::file_report(diag::DiagId::err_file_unreadable, "", {path}));
    return r;
  }
  return parse_ir(path, *text, options);
}

} // namespace lobe::driver
