// Shader look-up and loading through the compile driver (see shader_source.h).
#include "shader_source.h"

#include "driver/driver.h"

namespace lobe::group {

namespace {

driver::Options driver_options(const CompileOptions& options) {
  driver::Options o;
  o.frontend.include_dirs = options.include_dirs;
  o.frontend.defines = options.defines;
  o.frontend.undefines = options.undefines;
  return o; // not optimised here: specialisation folds each layer (group_build.cpp)
}

std::optional<ir::Shader> finish(driver::Loaded& l, DiagnosticList& diags, CompileStats* stats) {
  for (const diag::Report& r : l.diagnostics) diags.push_back(to_public(r));
  if (stats) {
    stats->preprocess_ms += l.timings.preprocess_ms;
    stats->parse_ms += l.timings.parse_ms;
    stats->sema_ms += l.timings.sema_ms;
    stats->ir_ms += l.timings.lower_ms;
  }
  return std::move(l.shader);
}

} // namespace

Diagnostic to_public(const diag::Report& r) {
  Diagnostic d;
  d.severity = r.severity == diag::Severity::Note      ? Diagnostic::Severity::Note
               : r.severity == diag::Severity::Warning ? Diagnostic::Severity::Warning
                                                       : Diagnostic::Severity::Error;
  d.text = r.text;
  // One line: no trailing newline, as the runtime's own diagnostics.
  if (d.text.ends_with('\n') && d.text.find('\n') == d.text.size() - 1) d.text.pop_back();
  d.id = diag::diag_name(r.id);
  d.file = r.file;
  d.line = r.line;
  d.column = r.column;
  d.message = r.message;
  return d;
}

Diagnostic located_error(const std::string& text, const char* id) {
  Diagnostic d{Diagnostic::Severity::Error, text, id};
  size_t at = text.find(": error: ");
  if (at == std::string::npos) {
    d.text = "error: " + text;
    d.message = text;
    return d;
  }
  d.message = text.substr(at + 9);
  // `file:line:col` (the file may hold colons itself: split from the right).
  std::string place = text.substr(0, at);
  size_t c2 = place.rfind(':');
  size_t c1 = c2 == std::string::npos || c2 == 0 ? std::string::npos : place.rfind(':', c2 - 1);
  auto number = [](const std::string& s) {
    return !s.empty() && s.find_first_not_of("0123456789") == std::string::npos ? std::stoi(s) : 0;
  };
  if (c1 != std::string::npos && number(place.substr(c1 + 1, c2 - c1 - 1)) > 0) {
    d.file = place.substr(0, c1);
    d.line = number(place.substr(c1 + 1, c2 - c1 - 1));
    d.column = number(place.substr(c2 + 1));
  } else {
    d.file = place;
  }
  return d;
}

std::vector<std::string> search_dirs(const CompileOptions& options) {
  std::vector<std::string> dirs = options.include_dirs;
  dirs.push_back(".");
  return dirs;
}

std::string find_shader_file(const std::string& name, const CompileOptions& options) {
  return driver::find_shader(name, search_dirs(options));
}

std::optional<ir::Shader> compile_osl_source(const std::string& path, const std::string& text,
                                             const CompileOptions& options, DiagnosticList& diags,
                                             CompileStats& stats) {
  driver::Loaded l = driver::compile_source(path, text, driver_options(options));
  return finish(l, diags, &stats);
}

std::optional<ir::Shader> parse_ir_text(const std::string& text, const std::string& where,
                                        DiagnosticList& diags) {
  driver::Loaded l = driver::parse_ir(where, text, {});
  return finish(l, diags, nullptr);
}

std::optional<ir::Shader> compile_shader_file(const std::string& path,
                                              const CompileOptions& options, DiagnosticList& diags,
                                              CompileStats& stats) {
  driver::Loaded l = driver::load_file(path, driver_options(options));
  return finish(l, diags, &stats);
}

} // namespace lobe::group
