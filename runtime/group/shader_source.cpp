// Shader look-up and source compilation (see shader_source.h).
#include "shader_source.h"

#include "ir/parser.h"
#include "ir/verifier.h"

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
  (void)options;
  (void)stats;
  diags.push_back({Diagnostic::Severity::Error,
                   path + ": error: compiling OSL source needs the front end (not linked yet)"});
  return std::nullopt;
}

} // namespace lobe::group
