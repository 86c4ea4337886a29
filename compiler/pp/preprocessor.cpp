// Preprocessor: the file loop, directives and output with its location segments.
#include "pp/preprocessor.h"

#include "pp/pp_expr.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace lobe::pp {

using diag::DiagId;
using diag::SourceLoc;
using diag::SourceRange;

Preprocessor::Preprocessor(diag::SourceManager& sm, diag::DiagnosticEngine& diags, PPOptions o)
    : sm_(sm), diags_(diags), opts_(std::move(o)) {
  define_predefined();
}

Preprocessor::~Preprocessor() = default;

// OSL's predefined macros and -D/-U, written as a small "<built-in>" file so that macro
// definitions have a location like any other.
void Preprocessor::define_predefined() {
  std::string text = "#define OSL_VERSION_MAJOR 1\n#define OSL_VERSION_MINOR 13\n"
                     "#define OSL_VERSION_PATCH 12\n#define OSL_VERSION 11312\n";
  for (const auto& d : opts_.defines) {
    auto eq = d.find('=');
    text += "#define " +
            (eq == std::string::npos ? d + " 1" : d.substr(0, eq) + " " + d.substr(eq + 1)) + "\n";
  }
  for (const auto& u : opts_.undefines) text += "#undef " + u + "\n";
  int id = sm_.add_file("<built-in>", text);
  auto toks = tokenize(sm_.buffer_text(id), sm_.buffer_start(id), diags_);
  Cursor cur{&toks, 0, id};
  run(cur);
}

std::optional<std::string> Preprocessor::read(const std::string& path) const {
  return opts_.read_file ? opts_.read_file(path) : read_file_from_disk(path);
}

std::optional<std::string> read_file_from_disk(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) return std::nullopt;
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

bool Preprocessor::process_file(const std::string& path) {
  auto text = read(path);
  if (!text) {
    diags_.report(DiagId::err_file_not_found, SourceLoc{}, {path});
    return false;
  }
  include_stack_.push_back(path);
  process_buffer(sm_.add_file(path, std::move(*text)));
  include_stack_.pop_back();
  return true;
}

void Preprocessor::process_buffer(int id) {
  auto toks = tokenize(sm_.buffer_text(id), sm_.buffer_start(id), diags_);
  Cursor cur{&toks, 0, id};
  contiguous_ = false;
  run(cur);
  contiguous_ = false;
  if (!out_.empty() && out_.back() != '\n') out_ += '\n';
}

int Preprocessor::finish() { return sm_.add_output(std::move(out_), std::move(segs_)); }

const Macro* Preprocessor::find_macro(const std::string& name) const {
  auto it = macros_.find(name);
  return it == macros_.end() ? nullptr : it->second.get();
}

// The file loop: directives at the start of a line, text lines expanded and emitted, inactive
// lines skipped. Conditionals left open at the end of the file are errors.
void Preprocessor::run(Cursor& cur) {
  size_t depth_at_entry = conds_.size();
  while (!cur.at_eof() && !diags_.stopped()) {
    const PPToken& t = cur.peek();
    if (t.at_line_start && t.is_punct("#")) {
      directive(cur);
    } else if (!active()) {
      ++cur.pos;
      contiguous_ = false;
    } else if (t.kind == PPKind::Newline) {
      emit_file_token(t);
      ++cur.pos;
    } else {
      expand_from_file(cur);
    }
  }
  while (conds_.size() > depth_at_entry) {
    diags_.report(DiagId::err_unterminated_conditional, conds_.back().loc);
    conds_.pop_back();
  }
}

// The rest of the current line (the newline is consumed, not returned).
std::vector<PPToken> Preprocessor::take_line(Cursor& cur) {
  std::vector<PPToken> line;
  while (cur.peek().kind != PPKind::Newline && !cur.at_eof())
    line.push_back((*cur.toks)[cur.pos++]);
  if (cur.peek().kind == PPKind::Newline) ++cur.pos;
  return line;
}

void Preprocessor::directive(Cursor& cur) {
  const PPToken hash = (*cur.toks)[cur.pos++];
  std::vector<PPToken> line = take_line(cur);
  contiguous_ = false;
  if (line.empty()) return; // the null directive
  const std::string& name = line[0].text;
  if (name == "if" || name == "ifdef" || name == "ifndef" || name == "elif" || name == "else" ||
      name == "endif") {
    conditional_directive(name, line);
    return;
  }
  if (!active()) return;
  if (name == "include")
    do_include(line, cur);
  else if (name == "define")
    do_define(line);
  else if (name == "undef")
    do_undef(line);
  else if (name == "pragma")
    do_pragma(line, false);
  else if (name == "error" || name == "warning")
    do_pragma(line, true);
  else if (name == "line" || line[0].kind == PPKind::Number)
    do_line(line, cur);
  else
    diags_.report(DiagId::err_unknown_directive,
                  SourceRange(line[0].loc, SourceLoc{line[0].end_offset()}), {name});
}

void Preprocessor::conditional_directive(const std::string& name,
                                         const std::vector<PPToken>& line) {
  SourceLoc loc = line[0].loc;
  auto extra = [&](size_t expected) {
    if (active() && line.size() > expected)
      diags_.report(DiagId::warn_extra_tokens, line[expected].loc, {name});
  };
  if (name == "if" || name == "ifdef" || name == "ifndef") {
    bool parent = active();
    bool v = false;
    if (parent && name == "if") {
      v = eval_condition(line, 1);
    } else if (parent) {
      if (line.size() < 2 || line[1].kind != PPKind::Ident)
        diags_.report(DiagId::err_macro_name_missing, loc);
      else
        v = (find_macro(line[1].text) != nullptr) == (name == "ifdef");
      extra(2);
    }
    conds_.push_back({loc, parent, parent && v, parent && v, false});
    return;
  }
  if (conds_.empty()) {
    diags_.report(name == "endif" ? DiagId::err_endif_without_if : DiagId::err_else_without_if, loc,
                  {name});
    return;
  }
  Conditional& c = conds_.back();
  if (name == "endif") {
    extra(1);
    conds_.pop_back();
  } else if (name == "else") {
    if (c.seen_else) diags_.report(DiagId::err_else_after_else, loc);
    c.seen_else = true;
    c.taking = c.parent_active && !c.taken;
    c.taken = c.taken || c.taking;
    extra(1);
  } else { // elif
    if (c.seen_else) diags_.report(DiagId::err_elif_after_else, loc);
    c.taking = false;
    if (c.parent_active && !c.taken) {
      bool v = eval_condition(line, 1);
      conds_.back().taking = v;
      conds_.back().taken = v;
    }
  }
}

// `defined X` / `defined(X)` are replaced before macro expansion; the rest is expanded and
// evaluated as a C integer expression.
bool Preprocessor::eval_condition(const std::vector<PPToken>& line, size_t from) {
  std::vector<PPToken> toks;
  for (size_t i = from; i < line.size(); ++i) {
    if (line[i].kind == PPKind::Ident && line[i].text == "defined") {
      size_t j = i + 1;
      bool paren = j < line.size() && line[j].is_punct("(");
      if (paren) ++j;
      if (j >= line.size() || line[j].kind != PPKind::Ident) {
        diags_.report(DiagId::err_macro_name_missing, line[i].loc);
        return false;
      }
      PPToken n = line[i];
      n.kind = PPKind::Number;
      n.text.assign(1, find_macro(line[j].text) ? '1' : '0');
      toks.push_back(n);
      i = j;
      if (paren) {
        if (i + 1 < line.size() && line[i + 1].is_punct(")"))
          ++i;
        else
          diags_.report(DiagId::err_pp_expr, line[i].loc, {"expected ')' after 'defined'"});
      }
    } else {
      toks.push_back(line[i]);
    }
  }
  auto r = evaluate_pp_expr(expand_list(std::move(toks)));
  if (!r.value) {
    diags_.report(DiagId::err_pp_expr, r.where.valid() ? r.where : line[0].loc, {r.error});
    return false;
  }
  return *r.value != 0;
}

// A token spelled in the current file: copy the text since the previous one (whitespace and
// comments included) when nothing intervened, so one linear segment covers long stretches.
void Preprocessor::emit_file_token(const PPToken& t) {
  // The newline the tokenizer adds at the end of a file (empty text): only whitespace and
  // comments lie before it, so nothing is copied (an unterminated comment is not lexed, and
  // reported, a second time), and the output position after it maps to the file's end, where
  // the parser reports an unexpected end of file.
  if (t.kind == PPKind::Newline && t.text.empty()) {
    if (!out_.empty() && out_.back() != '\n') out_ += '\n';
    segs_.push_back({uint32_t(out_.size()), t.loc, true, "", {}});
    contiguous_ = false;
    return;
  }
  if (contiguous_ && t.loc.offset >= last_end_) {
    const std::string& text = sm_.buffer_text(sm_.buffer_of(t.loc));
    uint32_t base = sm_.buffer_start(sm_.buffer_of(t.loc)).offset;
    out_.append(text, last_end_ - base, t.end_offset() - last_end_);
  } else {
    if (!out_.empty() && out_.back() != '\n') out_ += t.at_line_start ? '\n' : ' ';
    segs_.push_back({uint32_t(out_.size()), t.loc, true, "", {}});
    out_ += t.text;
  }
  contiguous_ = true;
  last_end_ = t.end_offset();
}

// Tokens produced by macro expansion: macro body tokens map to the invocation, argument
// tokens to where they are spelled.
void Preprocessor::emit_expanded(const std::vector<PPToken>& toks) {
  for (const auto& t : toks) {
    out_ += ' ';
    if (t.from_macro) {
      const auto* last = segs_.empty() ? nullptr : &segs_.back();
      if (!last || last->linear || last->loc != t.exp_loc || last->macro != t.from_macro->name)
        segs_.push_back(
            {uint32_t(out_.size()), t.exp_loc, false, t.from_macro->name, t.from_macro->def_loc});
    } else {
      segs_.push_back({uint32_t(out_.size()), t.loc, true, "", {}});
    }
    out_ += t.text;
  }
  contiguous_ = false;
}

} // namespace lobe::pp
