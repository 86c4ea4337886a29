// Shader look-up and source compilation (see shader_source.h).
#include "shader_source.h"

#include "frontend.h"
#include "ir/parser.h"
#include "ir/verifier.h"
#include "lower/lower.h"

#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace lobe::group {
namespace fs = std::filesystem;

namespace {
bool is_file(const fs::path& p) {
  std::error_code ec;
  return fs::is_regular_file(p, ec);
}
bool read_file(const std::string& path, std::string& out) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return false;
  std::ostringstream ss;
  ss << in.rdbuf();
  out = ss.str();
  return true;
}
} // namespace

// OSL source: front end (preprocess, parse, type-check) then lowering to IR.
std::optional<ir::Shader> compile_osl_source(const std::string& path, const std::string& text,
                                             const CompileOptions& options, DiagnosticList& diags,
                                             CompileStats& stats) {
  frontend::FrontendOptions fo;
  fo.include_dirs = options.include_dirs;
  fo.defines = options.defines;
  fo.undefines = options.undefines;
  diag::DiagnosticEngine engine;
  frontend::FrontendTimings t;
  auto tu = frontend::compile_to_ast({path, text}, fo, engine, &t);
  stats.preprocess_ms += t.preprocess_ms;
  stats.parse_ms += t.parse_ms;
  stats.sema_ms += t.sema_ms;
  if (tu && tu->sources)
    for (Diagnostic& d : diag::to_runtime(engine, *tu->sources)) diags.push_back(std::move(d));
  if (!tu || engine.has_errors()) return std::nullopt;
  auto t0 = std::chrono::steady_clock::now();
  lower::LowerResult lr = lower::lower(*tu);
  stats.ir_ms +=
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  for (const std::string& e : lr.errors) diags.push_back({Diagnostic::Severity::Error, e});
  if (!lr.shader) return std::nullopt;
  return std::move(lr.shader);
}

std::string find_shader_file(const std::string& name, const CompileOptions& options) {
  fs::path p(name);
  if ((p.extension() == ".osl" || p.extension() == ".lir" || p.has_parent_path()) && is_file(p))
    return name;
  std::vector<std::string> dirs = options.include_dirs;
  dirs.push_back(".");
  for (const std::string& d : dirs)
    for (const char* ext : {".osl", ".lir"}) {
      fs::path f = fs::path(d) / (name + ext);
      if (is_file(f)) return f.string();
    }
  return "";
}

std::optional<ir::Shader> parse_ir_text(const std::string& text, const std::string& where,
                                        DiagnosticList& diags) {
  ir::ParseResult r = ir::parse(text);
  if (!r.shader) {
    diags.push_back({Diagnostic::Severity::Error, where + ":" + r.error.to_string()});
    return std::nullopt;
  }
  auto problems = ir::verify(*r.shader);
  if (!problems.empty()) {
    diags.push_back({Diagnostic::Severity::Error, where + ": invalid IR: " + problems[0]});
    return std::nullopt;
  }
  return std::move(r.shader);
}

std::optional<ir::Shader> compile_shader_file(const std::string& path,
                                              const CompileOptions& options, DiagnosticList& diags,
                                              CompileStats& stats) {
  std::string text;
  if (!read_file(path, text)) {
    diags.push_back({Diagnostic::Severity::Error, "error: cannot read '" + path + "'"});
    return std::nullopt;
  }
  if (fs::path(path).extension() == ".lir") return parse_ir_text(text, path, diags);
  return compile_osl_source(path, text, options, diags, stats);
}

} // namespace lobe::group
