// Group text reader (see group_text.h): a tokenizer that keeps quoted strings whole, then one
// statement at a time.
#include "group_text.h"

#include "public_diag.h"

#include <cctype>
#include <regex>
#include <vector>

namespace lobe::group {
namespace {

struct Token {
  std::string text;
  bool quoted = false;
  int line = 1;
  bool end() const { return !quoted && (text == ";" || text == ","); }
};

// Words, quoted strings (with C escapes) and the statement ends ';' and ','. False on an
// unterminated string (`line` says where it starts).
bool tokenize(const std::string& s, std::vector<Token>& out, int& line) {
  line = 1;
  bool hints = false; // inside [[ ... ]], where ',' separates hints and ends no statement
  for (size_t i = 0; i < s.size();) {
    char c = s[i];
    if (c == '\n') ++line;
    if (std::isspace(static_cast<unsigned char>(c))) {
      ++i;
    } else if (c == '#') {
      while (i < s.size() && s[i] != '\n') ++i;
    } else if (c == ',' && hints) {
      out.push_back({",", true, line}); // a word of the hints, not an end
      ++i;
    } else if (c == ';' || c == ',') {
      out.push_back({std::string(1, c), false, line});
      ++i;
    } else if (c == '"') {
      Token t{"", true, line};
      for (++i; i < s.size() && s[i] != '"'; ++i) {
        if (s[i] == '\n') ++line;
        if (s[i] == '\\' && i + 1 < s.size()) {
          char e = s[++i];
          t.text += e == 'n' ? '\n' : e == 't' ? '\t' : e;
        } else {
          t.text += s[i];
        }
      }
      if (i >= s.size()) {
        line = t.line;
        return false;
      }
      ++i;
      out.push_back(t);
    } else {
      Token t{"", false, line};
      while (i < s.size() && !std::isspace(static_cast<unsigned char>(s[i])) && s[i] != ';' &&
             s[i] != ',' && s[i] != '"')
        t.text += s[i++];
      if (t.text.find("[[") != std::string::npos) hints = true;
      if (t.text.find("]]") != std::string::npos) hints = false;
      out.push_back(t);
    }
  }
  return true;
}

bool is_keyword(const Token& t) {
  return !t.quoted && (t.text == "param" || t.text == "shader" || t.text == "connect");
}

bool split_endpoint(const std::string& s, std::string& layer, std::string& param) {
  size_t dot = s.find('.');
  if (dot == std::string::npos || dot == 0 || dot + 1 == s.size()) return false;
  layer = s.substr(0, dot);
  param = s.substr(dot + 1);
  return true;
}

} // namespace

bool is_param_type(const std::string& word) {
  size_t br = word.find('[');
  std::string base = word.substr(0, br);
  if (br != std::string::npos && word.back() != ']') return false;
  static const char* kTypes[] = {"int",    "float",  "color",  "point",
                                 "vector", "normal", "string", "matrix"};
  for (const char* t : kTypes)
    if (base == t) return true;
  return false;
}

std::unique_ptr<ShaderGroup> parse_group_text(const std::string& text, const std::string& where,
                                              DiagnosticList& diags,
                                              const GroupTextOptions& options) {
  auto line_of = [&](int line) {
    return options.first_line > 0 ? options.first_line + line - 1 : line;
  };
  size_t errors = 0;
  auto error = [&](int line, const std::string& msg) {
    diags.push_back(
        runtime_diag(diag::DiagId::group_syntax, msg, std::nullopt, where, line_of(line)));
    ++errors;
  };
  std::vector<Token> toks;
  int bad_line = 1;
  if (!tokenize(text, toks, bad_line)) {
    error(bad_line, "unterminated string");
    return nullptr;
  }
  auto group = std::make_unique<ShaderGroup>();
  std::vector<InstanceValue> pending;
  for (size_t i = 0; i < toks.size();) {
    if (toks[i].end()) {
      ++i;
      continue;
    }
    // One statement: its words up to ';' or ',' or the next keyword (a bare param, which
    // starts with a type name, must end with ';' or ',').
    size_t j = i + 1;
    while (j < toks.size() && !toks[j].end() && !is_keyword(toks[j])) ++j;
    std::vector<Token> st(toks.begin() + long(i), toks.begin() + long(j));
    i = j;
    const std::string& kw = st[0].text;
    int line = st[0].line;
    bool bare = kw != "param" && options.allow_bare_params && is_param_type(kw) && !st[0].quoted;
    if (kw == "param" || bare) {
      size_t t = bare ? 0 : 1;
      if (st.size() < t + 3 || !is_param_type(st[t].text)) {
        error(line, "expected `param <type> <name> <value>...;`");
        continue;
      }
      InstanceValue v{st[t].text, st[t + 1].text, ""};
      v.osl_rules = true;
      size_t k = t + 2;
      for (; k < st.size() && !(!st[k].quoted && st[k].text.rfind("[[", 0) == 0); ++k) {
        if (!v.value.empty()) v.value += ' ';
        v.value += st[k].text;
        v.words.push_back(st[k].text);
      }
      // The hints, as testshade takes them: `int lockgeom = 0`, `int interpolated = 1` (the
      // same), `int interactive = 1`, separated by commas in the first [[ ]] (OSL 1.13.12 reads
      // no further).
      std::string meta;
      for (; k < st.size(); ++k) {
        meta += st[k].text + " ";
        if (!st[k].quoted && st[k].text.find("]]") != std::string::npos) break;
      }
      // Each hint: absent, zero or nonzero (any length of digits).
      enum class Hint { Absent, Zero, Nonzero };
      static const std::regex kHint(R"(\bint\s+(lockgeom|interpolated|interactive)\s*=\s*-?(\d+))");
      Hint lockgeom = Hint::Absent, interpolated = Hint::Absent, interactive = Hint::Absent;
      for (auto it = std::sregex_iterator(meta.begin(), meta.end(), kHint);
           it != std::sregex_iterator(); ++it) {
        Hint h =
            (*it)[2].str().find_first_not_of('0') == std::string::npos ? Hint::Zero : Hint::Nonzero;
        const std::string name = (*it)[1].str();
        (name == "lockgeom" ? lockgeom : name == "interpolated" ? interpolated : interactive) = h;
      }
      // `lockgeom = 0` or `interpolated = 1` lets user data bind the value; `lockgeom = 1`
      // locks nothing (OSL 1.13.12 still binds a parameter its shader declares lockgeom = 0).
      if (lockgeom == Hint::Zero || interpolated == Hint::Nonzero) v.lockgeom = 0;
      v.interpolated = interpolated == Hint::Nonzero;
      v.interactive = interactive == Hint::Nonzero;
      pending.push_back(std::move(v));
    } else if (kw == "shader") {
      if (st.size() < 2 || st.size() > 3) {
        error(line, "expected `shader <name> [<layer>];`");
        continue;
      }
      std::string name =
          st.size() == 3 ? st[2].text : st[1].text + "_" + std::to_string(group->layers.size());
      group->layers.push_back({st[1].text, name, std::move(pending)});
      pending.clear();
    } else if (kw == "connect") {
      Connection c;
      if (st.size() != 3 || !split_endpoint(st[1].text, c.src_layer, c.src_param) ||
          !split_endpoint(st[2].text, c.dst_layer, c.dst_param)) {
        error(line, "expected `connect <layer>.<param> <layer>.<param>;`");
        continue;
      }
      group->connections.push_back(c);
    } else {
      error(line, "expected `param`, `shader` or `connect`, found `" + kw + "`");
    }
  }
  if (!pending.empty() && !errors)
    error(toks.back().line, "parameter values after the last `shader`");
  if (group->layers.empty() && !errors) {
    diags.push_back(runtime_diag(diag::DiagId::group_no_shader, "", std::nullopt, where));
    ++errors;
  }
  return errors ? nullptr : std::move(group);
}

} // namespace lobe::group
