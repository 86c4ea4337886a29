// Reader for OSL's shader-group text (see group_text.h).
#include "group_text.h"

#include <cctype>
#include <vector>

namespace lobe::scene {
namespace {

struct Token {
  std::string text;
  bool quoted = false;
  int line = 1;
};

// "where: line N" (N inside the text), or "where:L" with L the file line when the text starts
// on file line first_line > 0.
std::string located(const std::string& where, int first_line, int line) {
  return first_line > 0 ? where + ":" + std::to_string(first_line + line - 1)
                        : where + ": line " + std::to_string(line);
}

// Splits into words, quoted strings and ';' tokens.
std::vector<Token> tokenize(const std::string& s, std::string& error, const std::string& where,
                            int first_line) {
  std::vector<Token> out;
  int line = 1;
  for (size_t i = 0; i < s.size();) {
    char c = s[i];
    if (c == '\n') ++line;
    if (std::isspace(static_cast<unsigned char>(c))) {
      ++i;
    } else if (c == ';') {
      out.push_back({";", false, line});
      ++i;
    } else if (c == '"') {
      size_t end = s.find('"', i + 1);
      if (end == std::string::npos) {
        error = located(where, first_line, line) + ": unterminated string";
        return {};
      }
      out.push_back({s.substr(i + 1, end - i - 1), true, line});
      i = end + 1;
    } else {
      size_t j = i;
      while (j < s.size() && !std::isspace(static_cast<unsigned char>(s[j])) && s[j] != ';' &&
             s[j] != '"')
        ++j;
      out.push_back({s.substr(i, j - i), false, line});
      i = j;
    }
  }
  return out;
}

bool split_dot(const std::string& s, std::string& layer, std::string& param) {
  size_t dot = s.find('.');
  if (dot == std::string::npos || dot == 0 || dot + 1 == s.size()) return false;
  layer = s.substr(0, dot);
  param = s.substr(dot + 1);
  return true;
}

} // namespace

bool is_param_type(const std::string& word) {
  std::string base = word.substr(0, word.find('['));
  static const char* kTypes[] = {"int",    "float",  "color",  "point",
                                 "vector", "normal", "string", "matrix"};
  for (const char* t : kTypes)
    if (base == t) return true;
  return false;
}

std::optional<ShaderGroup> parse_group_text(const std::string& text, const std::string& where,
                                            bool allow_bare, std::string& error, int first_line) {
  error.clear();
  std::vector<Token> toks = tokenize(text, error, where, first_line);
  if (!error.empty()) return std::nullopt;
  ShaderGroup group;
  std::vector<InstanceValue> pending;
  size_t i = 0;
  auto fail = [&](int line, const std::string& msg) {
    error = located(where, first_line, line) + ": " + msg;
    return std::nullopt;
  };
  while (i < toks.size()) {
    size_t end = i;
    while (end < toks.size() && toks[end].text != ";") ++end;
    std::vector<Token> st(toks.begin() + i, toks.begin() + end);
    i = end + 1;
    if (st.empty()) continue;
    const std::string& kw = st[0].text;
    int line = st[0].line;
    if (kw == "param" || (allow_bare && is_param_type(kw))) {
      size_t t = kw == "param" ? 1 : 0;
      if (st.size() < t + 3 || !is_param_type(st[t].text))
        return fail(line, "expected `param <type> <name> <value>...;`");
      InstanceValue iv{st[t].text, st[t + 1].text, ""};
      for (size_t k = t + 2; k < st.size(); ++k) iv.value += (k > t + 2 ? " " : "") + st[k].text;
      pending.push_back(std::move(iv));
    } else if (kw == "shader") {
      if (st.size() < 2 || st.size() > 3) return fail(line, "expected `shader <name> <layer>;`");
      ShaderGroup::Layer layer;
      layer.shader = st[1].text;
      layer.name = st.size() == 3 ? st[2].text : st[1].text + std::to_string(group.layers.size());
      layer.values = std::move(pending);
      pending.clear();
      group.layers.push_back(std::move(layer));
    } else if (kw == "connect") {
      Connection c;
      if (st.size() != 3 || !split_dot(st[1].text, c.src_layer, c.src_param) ||
          !split_dot(st[2].text, c.dst_layer, c.dst_param))
        return fail(line, "expected `connect <layer>.<param> <layer>.<param>;`");
      group.connections.push_back(std::move(c));
    } else {
      return fail(line, "expected `param`, `shader` or `connect`, found `" + kw + "`");
    }
  }
  if (!pending.empty()) return fail(toks.back().line, "parameter values after the last `shader`");
  if (group.layers.empty()) {
    error = where + ": shader group has no `shader` statement";
    return std::nullopt;
  }
  return group;
}

} // namespace lobe::scene
