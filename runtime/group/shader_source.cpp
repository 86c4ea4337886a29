// Shader look-up and source compilation (see shader_source.h).
#include "shader_source.h"

#include "frontend.h"
#include "ir/parser.h"
#include "ir/verifier.h"
#include "lower/lower.h"

#include <algorithm>
#include <cctype>
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

// The name an OSL source declares for its shader (`surface raytype_envmap (...)`), or "":
// comments and strings skipped, the first shader-type keyword followed by a name and `(` or
// `[[` taken.
std::string declared_shader_name(const std::string& text) {
  std::string code; // comments and string contents blanked
  for (size_t i = 0; i < text.size(); ++i) {
    if (text.compare(i, 2, "//") == 0) {
      while (i < text.size() && text[i] != '\n') ++i;
      code += '\n';
    } else if (text.compare(i, 2, "/*") == 0) {
      size_t e = text.find("*/", i + 2);
      i = e == std::string::npos ? text.size() : e + 1;
      code += ' ';
    } else if (text[i] == '"') {
      while (++i < text.size() && text[i] != '"') i += text[i] == '\\';
      code += "\"\"";
    } else if (text[i] == '#') { // preprocessor line
      while (i < text.size() && text[i] != '\n') i += text[i] == '\\' ? 2 : 1;
      code += '\n';
    } else {
      code += text[i];
    }
  }
  auto ident = [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; };
  for (size_t i = 0; i < code.size();) {
    if (!ident(code[i])) {
      ++i;
      continue;
    }
    size_t b = i;
    while (i < code.size() && ident(code[i])) ++i;
    std::string word = code.substr(b, i - b);
    if (word != "surface" && word != "shader" && word != "displacement" && word != "volume" &&
        word != "light")
      continue;
    size_t j = i;
    while (j < code.size() && std::isspace(static_cast<unsigned char>(code[j]))) ++j;
    size_t nb = j;
    while (j < code.size() && ident(code[j])) ++j;
    if (j == nb) continue;
    std::string name = code.substr(nb, j - nb);
    while (j < code.size() && std::isspace(static_cast<unsigned char>(code[j]))) ++j;
    if (j < code.size() && (code[j] == '(' || code.compare(j, 2, "[[") == 0)) return name;
  }
  return "";
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
  // As OSL finds name.oso, which oslc names after the shader the source declares (a file
  // raytype-envmap.osl declaring raytype_envmap): an .osl in the same places that declares
  // `name` (files in name order, the first found).
  for (const std::string& d : dirs) {
    std::error_code ec;
    std::vector<fs::path> files;
    for (fs::directory_iterator it(d.empty() ? "." : d, ec), end; !ec && it != end;
         it.increment(ec))
      if (it->path().extension() == ".osl" && is_file(it->path())) files.push_back(it->path());
    std::sort(files.begin(), files.end());
    for (const fs::path& f : files) {
      std::string text;
      if (read_file(f.string(), text) && declared_shader_name(text) == name) return f.string();
    }
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
