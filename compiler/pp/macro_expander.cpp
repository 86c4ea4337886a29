// Macro expansion (Prosser's algorithm, simplified): a macro name is replaced by its body with
// arguments substituted (# stringizes, ## pastes, other uses get the fully expanded argument),
// then the result is rescanned together with the rest of the input. Each token carries the set
// of macros that may not expand it again, which stops self-reference. Budgets on expansion
// count and argument nesting turn pathological input into an error instead of a hang.
#include "pp/preprocessor.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <ctime>

namespace lobe::pp {

using diag::DiagId;

namespace {
constexpr long kExpansionBudget = 200000; // macro expansions per top-level token
constexpr int kMaxArgDepth = 64;          // nested macro calls inside arguments

PPToken pop(std::vector<PPToken>& stack) {
  PPToken t = std::move(stack.back());
  stack.pop_back();
  return t;
}
} // namespace

std::string date_macro(const std::tm& tm) {
  static constexpr const char* kMonths[12] = {"Jan", "Feb", "Mar", "Apr", "May", "Jun",
                                              "Jul", "Aug", "Sep", "Oct", "Nov", "Dec"};
  char buf[32];
  std::snprintf(buf, sizeof buf, "\"%s %2d %d\"", kMonths[((tm.tm_mon % 12) + 12) % 12], tm.tm_mday,
                tm.tm_year + 1900);
  return buf;
}

std::string time_macro(const std::tm& tm) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "\"%02d:%02d:%02d\"", tm.tm_hour, tm.tm_min, tm.tm_sec);
  return buf;
}

void Preprocessor::expand_from_file(Cursor& cur) {
  const PPToken& first = (*cur.toks)[cur.pos++]; // copied only when it starts an expansion
  bool ident = first.kind == PPKind::Ident;
  const Macro* m = ident && !macros_.empty() ? find_macro(first.text) : nullptr;
  bool builtin = ident && first.text.size() == 8 &&
                 (first.text == "__LINE__" || first.text == "__FILE__" ||
                  first.text == "__DATE__" || first.text == "__TIME__");
  if (!m && !builtin) {
    emit_file_token(first);
    return;
  }
  Input in;
  in.file = &cur;
  in.pending.push_back(first);
  expansion_budget_ = kExpansionBudget;
  std::vector<PPToken> out;
  expand_loop(in, out);
  emit_expanded(out);
}

std::vector<PPToken> Preprocessor::expand_list(std::vector<PPToken> toks) {
  Input in;
  std::reverse(toks.begin(), toks.end());
  in.pending = std::move(toks);
  std::vector<PPToken> out;
  if (expand_depth_ == 0) expansion_budget_ = kExpansionBudget;
  expand_loop(in, out);
  return out;
}

void Preprocessor::expand_loop(Input& in, std::vector<PPToken>& out) {
  while (!in.pending.empty()) {
    if (expansion_budget_ < 0) { // a budget was exceeded (reported): abandon this expansion
      in.pending.clear();
      break;
    }
    PPToken t = pop(in.pending);
    if (!try_expand(t, in)) out.push_back(std::move(t));
  }
}

// True if the next token of the input (newlines skipped) is '('.
bool Preprocessor::next_is_lparen(Input& in) {
  for (auto it = in.pending.rbegin(); it != in.pending.rend(); ++it)
    if (it->kind != PPKind::Newline) return it->is_punct("(");
  if (!in.file) return false;
  for (size_t i = in.file->pos;; ++i) {
    const PPToken& t = (*in.file->toks)[i];
    if (t.kind == PPKind::Eof) return false;
    if (t.kind == PPKind::Newline) continue;
    if (t.at_line_start && t.is_punct("#")) return false; // a directive, not an argument list
    return t.is_punct("(");
  }
}

bool Preprocessor::try_expand(const PPToken& t, Input& in) {
  if (t.kind != PPKind::Ident) return false;
  if (t.text == "__DATE__" || t.text == "__TIME__") {
    // When the preprocessor ran, as C's (and oslc's): "Dec  7 2026", "13:06:11", local time.
    PPToken r = t;
    r.kind = PPKind::String;
    std::time_t now = std::time(nullptr);
    std::tm tm{};
    localtime_r(&now, &tm);
    r.text = t.text == "__DATE__" ? date_macro(tm) : time_macro(tm);
    in.pending.push_back(std::move(r));
    return true;
  }
  if (t.text == "__LINE__" || t.text == "__FILE__") {
    PPToken r = t;
    diag::SourceLoc at = t.from_macro ? t.exp_loc : t.loc;
    auto p = sm_.presumed(at);
    r.kind = t.text == "__LINE__" ? PPKind::Number : PPKind::String;
    if (t.text == "__LINE__") {
      // oslc reads the main file after a line of its own (the #include of stdosl.h), so its
      // __LINE__ there is one more than the line (diagnostics still name the line itself);
      // in an included file, or after a #line directive (which numbers the lines that follow
      // as the preprocessor sees them), it is the line. Lobe's __LINE__ is oslc's.
      bool main_file = !sm_.include_loc(at).valid();
      r.text = std::to_string(p.line + (main_file && !p.renumbered ? 1 : 0));
    } else {
      r.text.assign(1, '"');
      r.text.append(p.file).push_back('"');
    }
    in.pending.push_back(std::move(r));
    return true;
  }
  const Macro* m = find_macro(t.text);
  if (!m || t.hidden(m)) return false;
  if (--expansion_budget_ < 0 || in.pending.size() > 1000000) {
    if (expansion_budget_ == -1 || in.pending.size() > 1000000)
      diags_.report(DiagId::err_macro_expansion_too_large, t.loc, {m->name});
    in.pending.clear();
    return true;
  }
  std::vector<std::vector<PPToken>> args;
  if (m->function_like) {
    if (!next_is_lparen(in)) return false;
    std::vector<PPToken> consumed;
    if (!collect_args(*m, t, in, args, consumed)) {
      // A wrong argument count keeps the call as written (the name no longer expands), so the
      // parser sees a call rather than a hole.
      PPToken name = t;
      auto hide = std::make_shared<std::vector<const Macro*>>(t.hide ? *t.hide
                                                                     : std::vector<const Macro*>{});
      hide->push_back(m);
      name.hide = hide;
      for (auto it = consumed.rbegin(); it != consumed.rend(); ++it) in.pending.push_back(*it);
      in.pending.push_back(std::move(name));
      return true;
    }
  }
  std::vector<PPToken> body = substitute(*m, t, args);
  for (auto it = body.rbegin(); it != body.rend(); ++it) in.pending.push_back(std::move(*it));
  return true;
}

// Reads `( a, b, ... )` from the input: commas split arguments at parenthesis depth 1; the
// extra arguments of a variadic macro are joined into __VA_ARGS__.
bool Preprocessor::collect_args(const Macro& m, const PPToken& name, Input& in,
                                std::vector<std::vector<PPToken>>& args,
                                std::vector<PPToken>& consumed) {
  auto next = [&](PPToken& t) {
    if (!in.pending.empty()) {
      t = pop(in.pending);
    } else {
      if (!in.file || in.file->at_eof()) return false;
      t = (*in.file->toks)[in.file->pos++];
    }
    if (t.kind != PPKind::Newline) consumed.push_back(t);
    return true;
  };
  PPToken t;
  do {
    if (!next(t)) return false;
  } while (t.kind == PPKind::Newline); // the '('
  args.emplace_back();
  int depth = 1;
  size_t named = m.params.size() - (m.variadic ? 1 : 0);
  while (true) {
    if (!next(t)) {
      diags_.report(DiagId::err_macro_unterminated_call, name.loc, {m.name});
      consumed.clear();
      return false;
    }
    if (t.kind == PPKind::Newline) continue;
    if (t.is_punct("(")) ++depth;
    if (t.is_punct(")") && --depth == 0) break;
    if (t.is_punct(",") && depth == 1 && !(m.variadic && args.size() > named)) {
      args.emplace_back();
      continue;
    }
    args.back().push_back(t);
  }
  if (args.size() == 1 && args[0].empty() && m.params.empty()) args.clear();
  if (m.variadic && args.size() == named) args.emplace_back(); // empty __VA_ARGS__
  if (args.size() != m.params.size()) {
    diags_.report(diag::DiagId::err_macro_arg_count, name.loc,
                  {m.name, std::to_string(m.params.size()), std::to_string(args.size())});
    return false;
  }
  return true;
}

namespace {

PPToken stringize(const std::vector<PPToken>& arg, const PPToken& at) {
  std::string s = "\"";
  for (char c : spell(arg)) {
    if (c == '"' || c == '\\') s += '\\';
    s += c;
  }
  PPToken r = at;
  r.kind = PPKind::String;
  r.text = s + "\"";
  return r;
}

// The kind of a pasted token, judged from its first character.
PPKind kind_of(const std::string& s) {
  if (s.empty()) return PPKind::Other;
  unsigned char c = static_cast<unsigned char>(s[0]);
  if (std::isalpha(c) || c == '_') return PPKind::Ident;
  if (std::isdigit(c) || c == '.') return PPKind::Number;
  if (c == '"') return PPKind::String;
  return PPKind::Punct;
}

} // namespace

std::vector<PPToken> Preprocessor::substitute(const Macro& m, const PPToken& name,
                                              const std::vector<std::vector<PPToken>>& args) {
  auto param_index = [&](const PPToken& t) -> int {
    if (t.kind != PPKind::Ident) return -1;
    auto it = std::find(m.params.begin(), m.params.end(), t.text);
    return it == m.params.end() ? -1 : int(it - m.params.begin());
  };
  std::vector<PPToken> out;
  const auto& body = m.body;
  for (size_t i = 0; i < body.size(); ++i) {
    const PPToken& b = body[i];
    int p = param_index(b);
    bool pasting_next = i + 1 < body.size() && body[i + 1].is_punct("##");
    if (b.is_punct("#") && m.function_like && i + 1 < body.size() &&
        param_index(body[i + 1]) >= 0) {
      out.push_back(stringize(args[size_t(param_index(body[i + 1]))], b));
      ++i;
    } else if (b.is_punct("##") && i + 1 < body.size()) {
      int q = param_index(body[i + 1]);
      std::vector<PPToken> rhs = q >= 0 ? args[size_t(q)] : std::vector<PPToken>{body[i + 1]};
      ++i;
      if (rhs.empty()) continue;
      if (out.empty()) {
        out = rhs;
        continue;
      }
      out.back().text += rhs[0].text;
      out.back().kind = kind_of(out.back().text);
      out.insert(out.end(), rhs.begin() + 1, rhs.end());
    } else if (p >= 0) {
      if (pasting_next) {
        out.insert(out.end(), args[size_t(p)].begin(), args[size_t(p)].end());
      } else {
        if (++expand_depth_ > kMaxArgDepth) {
          diags_.report(DiagId::err_macro_expansion_too_large, name.loc, {m.name});
          --expand_depth_;
          expansion_budget_ = -2; // stop the whole expansion, without a second report
          return {};
        }
        auto e = expand_list(args[size_t(p)]);
        --expand_depth_;
        if (!e.empty()) e[0].space_before = b.space_before;
        out.insert(out.end(), e.begin(), e.end());
      }
    } else {
      out.push_back(b);
      out.back().from_macro = name.from_macro ? name.from_macro : &m;
      out.back().exp_loc = name.from_macro ? name.exp_loc : name.loc;
    }
  }
  // Everything produced is hidden from m (and from whatever hid the name).
  auto hide = std::make_shared<std::vector<const Macro*>>(name.hide ? *name.hide
                                                                    : std::vector<const Macro*>{});
  hide->push_back(&m);
  for (auto& t : out) {
    if (t.hide && t.hide != name.hide) {
      auto merged = std::make_shared<std::vector<const Macro*>>(*t.hide);
      merged->insert(merged->end(), hide->begin(), hide->end());
      t.hide = merged;
    } else {
      t.hide = hide;
    }
  }
  if (!out.empty()) out[0].space_before = name.space_before;
  return out;
}

} // namespace lobe::pp
