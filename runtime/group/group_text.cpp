// Group text reader (see group_text.h): a tokenizer that keeps quoted strings whole, then one
// statement at a time.
#include "group_text.h"

#include <cctype>
#include <regex>
#include <vector>

namespace lobe::group {
namespace {

struct Token {
  std::string text;
  bool quoted = false;
  int line = 1;
};

std::vector<Token> tokenize(const std::string& s) {
  std::vector<Token> out;
  int line = 1;
  for (size_t i = 0; i < s.size();) {
    char c = s[i];
    if (c == '\n') ++line;
    if (std::isspace(static_cast<unsigned char>(c))) {
      ++i;
    } else if (c == '#') { // comment to end of line
      while (i < s.size() && s[i] != '\n') ++i;
    } else if (c == ';') {
      out.push_back({";", false, line});
      ++i;
    } else if (c == '"') {
      Token t{"", true, line};
      for (++i; i < s.size() && s[i] != '"'; ++i) {
        if (s[i] == '\\' && i + 1 < s.size()) ++i;
        t.text += s[i];
      }
      ++i;
      out.push_back(t);
    } else {
      Token t{"", false, line};
      while (i < s.size() && !std::isspace(static_cast<unsigned char>(s[i])) && s[i] != ';')
        t.text += s[i++];
      out.push_back(t);
    }
  }
  return out;
}

bool is_keyword(const Token& t) {
  return !t.quoted && (t.text == "param" || t.text == "shader" || t.text == "connect");
}

Diagnostic error(const std::string& where, int line, const std::string& msg) {
  return {Diagnostic::Severity::Error, where + ":" + std::to_string(line) + ": error: " + msg};
}

bool split_endpoint(const std::string& s, std::string& layer, std::string& param) {
  size_t dot = s.find('.');
  if (dot == std::string::npos || dot == 0 || dot + 1 == s.size()) return false;
  layer = s.substr(0, dot);
  param = s.substr(dot + 1);
  return true;
}

} // namespace

std::unique_ptr<ShaderGroup> parse_group_text(const std::string& text, const std::string& where,
                                              DiagnosticList& diags) {
  auto group = std::make_unique<ShaderGroup>();
  std::vector<InstanceValue> pending;
  std::vector<Token> toks = tokenize(text);
  size_t errors = 0;
  for (size_t i = 0; i < toks.size();) {
    if (toks[i].text == ";" && !toks[i].quoted) {
      ++i;
      continue;
    }
    // One statement: the keyword and its words up to `;` or the next keyword.
    size_t j = i + 1;
    while (j < toks.size() && !(toks[j].text == ";" && !toks[j].quoted) && !is_keyword(toks[j]))
      ++j;
    std::vector<Token> st(toks.begin() + long(i), toks.begin() + long(j));
    i = j;
    const std::string& kw = st[0].text;
    int line = st[0].line;
    if (kw == "param") {
      if (st.size() < 4) {
        diags.push_back(error(where, line, "'param' needs a type, a name and a value"));
        ++errors;
        continue;
      }
      InstanceValue v{st[1].text, st[2].text, ""};
      size_t k = 3;
      for (; k < st.size() && !(!st[k].quoted && st[k].text.rfind("[[", 0) == 0); ++k) {
        if (!v.value.empty()) v.value += ' ';
        v.value += st[k].text;
      }
      // Metadata after the value: `[[ int lockgeom = 0 ]]` is kept; other items are ignored.
      std::string meta;
      for (; k < st.size(); ++k) meta += st[k].text + " ";
      static const std::regex kLockgeom(R"(\bint\s+lockgeom\s*=\s*([01])\b)");
      std::smatch m;
      if (std::regex_search(meta, m, kLockgeom)) v.lockgeom = m[1].str() == "0" ? 0 : 1;
      pending.push_back(v);
    } else if (kw == "shader") {
      if (st.size() != 3) {
        diags.push_back(error(where, line, "'shader' needs a shader name and a layer name"));
        ++errors;
        continue;
      }
      group->layers.push_back({st[1].text, st[2].text, std::move(pending)});
      pending.clear();
    } else if (kw == "connect") {
      Connection c;
      if (st.size() != 3 || !split_endpoint(st[1].text, c.src_layer, c.src_param) ||
          !split_endpoint(st[2].text, c.dst_layer, c.dst_param)) {
        diags.push_back(error(where, line, "'connect' needs two endpoints, layer.param"));
        ++errors;
        continue;
      }
      group->connections.push_back(c);
    } else {
      diags.push_back(
          error(where, line, "expected 'param', 'shader' or 'connect', found '" + kw + "'"));
      ++errors;
    }
  }
  if (!pending.empty()) {
    diags.push_back(
        error(where, toks.empty() ? 1 : toks.back().line, "'param' after the last 'shader'"));
    ++errors;
  }
  if (group->layers.empty() && !errors) {
    diags.push_back(error(where, 1, "the group has no shader"));
    ++errors;
  }
  return errors ? nullptr : std::move(group);
}

} // namespace lobe::group
