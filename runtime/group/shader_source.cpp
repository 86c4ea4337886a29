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

std::vector<std::string> search_dirs(const CompileOptions& options) {
  std::vector<std::string> dirs = options.include_dirs;
  dirs.push_back(".");
  return dirs;
}

std::string find_shader_file(const std::string& name, const CompileOptions& options) {
  // Preprocessor definitions given now apply to the source: a compiled form made without them
  // would drop them.
  bool defines = !options.defines.empty() || !options.undefines.empty();
  return driver::find_shader(name, search_dirs(options),
                             defines ? driver::Prefer::Source : driver::Prefer::Compiled);
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
