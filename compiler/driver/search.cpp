// The shader search order (search.h).
#include "driver/search.h"

#include "pp/preprocessor.h"

#include <algorithm>
#include <cctype>
#include <filesystem>

namespace lobe::driver {
namespace fs = std::filesystem;

namespace {

bool is_file(const fs::path& p) {
  std::error_code ec;
  return fs::is_regular_file(p, ec);
}

// The shader name `file` declares once preprocessed (`shader NAME(sqrt)` with a macro NAME, as
// OSL's *_xmacro.h test headers build names): oslc names the compiled file after it. Includes
// are searched beside the file and in `dirs`; a header not found (stdosl.h) reads as empty.
std::string preprocessed_shader_name(const fs::path& file, const std::vector<std::string>& dirs) {
  pp::PPOptions o;
  o.include_dirs = {file.has_parent_path() ? file.parent_path().string() : "."};
  o.include_dirs.insert(o.include_dirs.end(), dirs.begin(), dirs.end());
  o.builtin_header = [](const std::string&) -> std::optional<std::string> { return ""; };
  diag::SourceManager sm;
  diag::DiagnosticEngine diags;
  pp::Preprocessor p(sm, diags, o);
  if (!p.process_file(file.string())) return "";
  return declared_shader_name(sm.buffer_text(p.finish()));
}

// Step 4 of the search: an .osl in one of `dirs` declaring shader `name`, as written, else once
// preprocessed.
std::string find_by_declared_name(const std::string& name, const std::vector<std::string>& dirs) {
  std::vector<fs::path> macro_named; // declaring no name as written
  for (const std::string& d : dirs) {
    std::error_code ec;
    std::vector<fs::path> files;
    for (fs::directory_iterator it(d.empty() ? "." : d, ec), end; !ec && it != end;
         it.increment(ec))
      if (it->path().extension() == ".osl" && is_file(it->path())) files.push_back(it->path());
    std::sort(files.begin(), files.end());
    for (const fs::path& f : files) {
      std::optional<std::string> text = pp::read_file_from_disk(f.string());
      if (!text) continue;
      std::string declared = declared_shader_name(*text);
      if (declared == name) return f.lexically_normal().string();
      if (declared.empty() || text->find("#define") != std::string::npos ||
          text->find("#include") != std::string::npos)
        macro_named.push_back(f);
    }
  }
  for (const fs::path& f : macro_named)
    if (preprocessed_shader_name(f, dirs) == name) return f.lexically_normal().string();
  return "";
}

// True when `lir` was written no earlier than `osl` was last changed.
bool up_to_date(const fs::path& lir, const fs::path& osl) {
  std::error_code e1, e2;
  auto tl = fs::last_write_time(lir, e1), ts = fs::last_write_time(osl, e2);
  return !e1 && !e2 && tl >= ts;
}

} // namespace

std::string find_shader(std::string name, const std::vector<std::string>& dirs, Prefer prefer) {
  if (name.size() > 4 && name.ends_with(".oso")) name.resize(name.size() - 4);
  fs::path p(name);
  bool named_file = p.extension() == ".osl" || p.extension() == ".lir";
  if ((named_file || p.has_parent_path()) && is_file(p)) return name;
  std::vector<std::string> files = {name};
  if (!named_file) files = {name + ".osl", name + ".lir"};
  std::vector<std::string> places = p.is_absolute() ? std::vector<std::string>{""} : dirs;
  for (const std::string& d : places) {
    auto in_dir = [&](const std::string& f) {
      return d.empty() || d == "." ? fs::path(f) : fs::path(d) / f;
    };
    if (!named_file && prefer == Prefer::Compiled) {
      fs::path src = in_dir(files[0]), ir = in_dir(files[1]);
      if (is_file(ir) && (!is_file(src) || up_to_date(ir, src)))
        return ir.lexically_normal().string();
    }
    for (const std::string& f : files)
      if (fs::path q = in_dir(f); is_file(q)) return q.lexically_normal().string();
  }
  if (named_file || p.has_parent_path()) return "";
  return find_by_declared_name(name, dirs);
}

// Comments, strings and preprocessor lines are skipped; the first shader-type keyword followed
// by a name and `(` or `[[` gives the name.
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

} // namespace lobe::driver
