// Preprocessor directives other than conditionals: #include, #define, #undef, #pragma / #error
// / #warning, #line.
#include "pp/preprocessor.h"

#include <algorithm>
#include <cctype>
#include <cstdlib>

namespace lobe::pp {

using diag::DiagId;
using diag::SourceLoc;
using diag::SourceRange;

namespace {
// Decodes the escapes of a string literal token's text (quotes included).
std::string unquote(const std::string& s) {
  std::string out;
  for (size_t i = 1; i + 1 < s.size(); ++i) {
    if (s[i] == '\\' && i + 2 < s.size()) {
      char e = s[++i];
      out += e == 'n' ? '\n' : e == 't' ? '\t' : e;
    } else {
      out += s[i];
    }
  }
  return out;
}
std::string dirname(const std::string& p) {
  auto slash = p.find_last_of('/');
  return slash == std::string::npos ? "" : p.substr(0, slash + 1);
}
} // namespace

void Preprocessor::do_include(const std::vector<PPToken>& raw, Cursor& cur) {
  std::vector<PPToken> line(raw.begin() + 1, raw.end());
  if (!line.empty() && line[0].kind == PPKind::Ident) line = expand_list(line);
  std::string name;
  bool angled = false;
  if (!line.empty() && line[0].kind == PPKind::String && line[0].text.size() >= 2 &&
      line[0].text.back() == '"') {
    name = unquote(line[0].text);
  } else if (!line.empty() && line[0].is_punct("<")) {
    angled = true;
    size_t i = 1;
    for (; i < line.size() && !line[i].is_punct(">"); ++i) name += line[i].text;
    if (i == line.size()) name.clear();
  }
  SourceLoc loc = raw[0].loc;
  if (name.empty()) {
    diags_.report(DiagId::err_include_syntax, loc);
    return;
  }
  if (int(include_stack_.size()) >= opts_.max_include_depth) {
    diags_.report(DiagId::err_include_depth, loc, {std::to_string(opts_.max_include_depth)});
    return;
  }
  // Search order: the including file's folder ("" only), the -I paths, the working directory
  // (<> only), then the headers built into the compiler.
  std::vector<std::string> candidates;
  if (!angled) candidates.push_back(dirname(sm_.buffer_name(cur.buffer)) + name);
  for (const auto& d : opts_.include_dirs)
    candidates.push_back(d + (d.empty() || d.back() == '/' ? "" : "/") + name);
  if (angled) candidates.push_back(name);
  size_t on_disk = candidates.size();
  if (opts_.builtin_header) candidates.push_back(name);
  for (size_t c = 0; c < candidates.size(); ++c) {
    const std::string& path = candidates[c];
    auto text = c < on_disk ? read(path) : opts_.builtin_header(name);
    if (!text) continue;
    if (once_.count(path)) return;
    for (const auto& open : include_stack_) {
      if (open == path) {
        diags_.report(DiagId::err_include_cycle,
                      SourceRange(line[0].loc, SourceLoc{line.back().end_offset()}), {path});
        return;
      }
    }
    int id = sm_.add_file(path, std::move(*text), loc);
    if (c >= on_disk) builtin_buffers_.push_back(id);
    include_stack_.push_back(path);
    process_buffer(id);
    include_stack_.pop_back();
    return;
  }
  diags_.report(DiagId::err_include_not_found,
                SourceRange(line[0].loc, SourceLoc{line.back().end_offset()}), {name});
}

void Preprocessor::do_define(const std::vector<PPToken>& line) {
  if (line.size() < 2 || line[1].kind != PPKind::Ident) {
    diags_.report(DiagId::err_macro_name_missing, line[0].loc);
    return;
  }
  auto m = std::make_unique<Macro>();
  m->name = line[1].text;
  m->def_loc = line[1].loc;
  size_t i = 2;
  if (i < line.size() && line[i].is_punct("(") && !line[i].space_before) {
    m->function_like = true;
    ++i;
    bool closed = false;
    while (i < line.size()) {
      if (line[i].is_punct(")")) {
        closed = true;
        ++i;
        break;
      }
      if (line[i].is_punct(".") && i + 2 < line.size() && line[i + 1].is_punct(".") &&
          line[i + 2].is_punct(".")) {
        m->variadic = true;
        m->params.push_back("__VA_ARGS__");
        i += 3;
      } else if (line[i].kind == PPKind::Ident && !m->variadic) {
        m->params.push_back(line[i++].text);
      } else {
        break;
      }
      if (i < line.size() && line[i].is_punct(","))
        ++i;
      else if (!(i < line.size() && line[i].is_punct(")")))
        break;
    }
    if (!closed) {
      diags_.report(DiagId::err_macro_param_list, i < line.size() ? line[i].loc : line[1].loc,
                    {"expected a parameter name, '...' or ')'"});
      return;
    }
  }
  m->body.assign(line.begin() + long(i), line.end());
  if (!m->body.empty()) m->body[0].space_before = false;
  for (size_t k = 0; k < m->body.size(); ++k) {
    const PPToken& t = m->body[k];
    if ((k == 0 || k + 1 == m->body.size()) && t.is_punct("##")) {
      diags_.report(DiagId::err_paste_at_edge, t.loc);
      return;
    }
    if (m->function_like && t.is_punct("#")) {
      bool ok =
          k + 1 < m->body.size() && m->body[k + 1].kind == PPKind::Ident &&
          std::find(m->params.begin(), m->params.end(), m->body[k + 1].text) != m->params.end();
      if (!ok) {
        diags_.report(DiagId::err_hash_not_param, t.loc);
        return;
      }
    }
  }
  define_macro(std::move(m));
}

void Preprocessor::define_macro(std::unique_ptr<Macro> m) {
  auto it = macros_.find(m->name);
  if (it != macros_.end()) {
    const Macro& old = *it->second;
    bool same = old.function_like == m->function_like && old.params == m->params &&
                spell(old.body) == spell(m->body);
    if (!same) {
      diags_.report(DiagId::warn_macro_redefined, m->def_loc, {m->name});
      diags_.report(DiagId::note_previous_definition, old.def_loc);
    }
    retired_.push_back(std::move(it->second));
    it->second = std::move(m);
  } else {
    std::string name = m->name;
    macros_.emplace(std::move(name), std::move(m));
  }
}

void Preprocessor::do_undef(const std::vector<PPToken>& line) {
  if (line.size() < 2 || line[1].kind != PPKind::Ident) {
    diags_.report(DiagId::err_macro_name_missing, line[0].loc);
    return;
  }
  auto it = macros_.find(line[1].text);
  if (it != macros_.end()) {
    retired_.push_back(std::move(it->second));
    macros_.erase(it);
  }
  if (line.size() > 2) diags_.report(DiagId::warn_extra_tokens, line[2].loc, {"undef"});
}

namespace {
std::string lower(std::string s) {
  for (char& c : s) c = char(std::tolower(static_cast<unsigned char>(c)));
  return s;
}
} // namespace

// #pragma error "msg" / #pragma warning "msg" / #pragma once / #pragma osl nowarn (others are
// ignored, as OSL ignores pragmas it does not know); C-style #error / #warning take the rest
// of the line.
void Preprocessor::do_pragma(const std::vector<PPToken>& line, bool c_style) {
  size_t k = c_style ? 0 : 1;
  if (k >= line.size()) return;
  const std::string& what = line[k].text;
  if (what == "once" && !include_stack_.empty()) {
    once_.insert(include_stack_.back());
    return;
  }
  // oslc's own pragmas: `osl` in any case, then the pragma's name as written; `#pragma osl
  // nowarn` (extra words ignored) silences the warnings of the next line only. Any other name
  // gets oslc's warning. (oslc 1.13, `oslc -q`: `#pragma OSL nowarn` works, `#pragma nowarn`
  // and `#pragma foo nowarn` are ignored, `#pragma osl NoWarn` warns "Unknown pragma 'NoWarn'".)
  if (!c_style && lower(what) == "osl") {
    // The name is the word's leading letters, as oslc reads it (`nowarn2` is nowarn,
    // `Foo_Bar` warns "Unknown pragma 'Foo'", `9abc` "Unknown pragma ''").
    std::string name = k + 1 < line.size() ? line[k + 1].text : "";
    size_t letters = 0;
    while (letters < name.size() && std::isalpha(static_cast<unsigned char>(name[letters])))
      ++letters;
    name.resize(letters);
    if (name == "nowarn") {
      diag::PresumedLoc p = sm_.presumed(line[k].loc);
      nowarn_.lines.insert({p.file, p.line + 1});
    } else {
      diags_.report(DiagId::warn_unknown_pragma, line[k].loc, {name});
    }
    return;
  }
  if (what != "error" && what != "warning") return;
  std::vector<PPToken> rest(line.begin() + long(k) + 1, line.end());
  std::string msg =
      rest.size() == 1 && rest[0].kind == PPKind::String ? unquote(rest[0].text) : spell(rest);
  SourceRange r(line[k].loc, SourceLoc{line.back().end_offset()});
  diags_.report(what == "error" ? DiagId::err_pragma_error : DiagId::warn_pragma_warning, r, {msg});
}

// #line N ["file"] (and the GNU form `# N "file"`): renumbers the lines that follow.
void Preprocessor::do_line(const std::vector<PPToken>& raw, Cursor& cur) {
  size_t k = raw[0].kind == PPKind::Number ? 0 : 1;
  std::vector<PPToken> line = expand_list(std::vector<PPToken>(raw.begin() + long(k), raw.end()));
  long n = 0;
  if (!line.empty() && line[0].kind == PPKind::Number)
    n = std::strtol(line[0].text.c_str(), nullptr, 10);
  if (n <= 0) {
    diags_.report(DiagId::err_bad_line_directive, raw[0].loc);
    return;
  }
  std::string file = line.size() > 1 && line[1].kind == PPKind::String ? unquote(line[1].text) : "";
  // The directive applies from the start of the next line.
  const std::string& text = sm_.buffer_text(cur.buffer);
  size_t nl = text.find('\n', raw.back().end_offset() - sm_.buffer_start(cur.buffer).offset);
  uint32_t line_start = uint32_t(nl == std::string::npos ? text.size() : nl + 1);
  sm_.add_line_directive(cur.buffer, line_start, int(n), file);
}

} // namespace lobe::pp
