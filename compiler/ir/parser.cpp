// The IR text parser: line-oriented. Each line is split into tokens (bare words, quoted
// strings, commas); the line's first token says what it is (header, section keyword, symbol
// kind, label, opcode). Symbols are declared before ops, so op operands resolve by name at once;
// labels may be used before they are defined and are resolved at the end.
#include "ir/parser.h"
#include "ir/opcodes.h"

#include <charconv>
#include <map>
#include <unordered_map>

namespace lobe::ir {

std::string ParseError::to_string() const {
  return std::to_string(line) + ":" + std::to_string(column) + ": " + message;
}

namespace {

struct Token {
  std::string text;
  bool quoted = false;
  int col = 0; // 1-based
};

// A failure while parsing one line; carries the column.
struct Fail {
  int col;
  std::string message;
};

// Splits a line into tokens. Quoted strings decode \" \\ \n \t \xNN; a comma is its own token.
bool tokenize(std::string_view line, std::vector<Token>& out, Fail& fail) {
  size_t i = 0;
  while (i < line.size()) {
    char c = line[i];
    if (c == ' ' || c == '\t' || c == '\r') {
      ++i;
    } else if (c == ',') {
      out.push_back({",", false, int(i) + 1});
      ++i;
    } else if (c == '"' || (c == '@' && i + 1 < line.size() && line[i + 1] == '"')) {
      // "string", or @"file with spaces":line:col (the location keeps its @ and tail).
      Token t{"", true, int(i) + 1};
      if (c == '@') {
        t.text = "@";
        t.quoted = false;
        ++i;
      }
      std::string s;
      ++i;
      bool closed = false;
      while (i < line.size()) {
        char d = line[i++];
        if (d == '"') {
          closed = true;
          break;
        }
        if (d != '\\') {
          s.push_back(d);
          continue;
        }
        if (i >= line.size()) break;
        char e = line[i++];
        if (e == 'n')
          s.push_back('\n');
        else if (e == 't')
          s.push_back('\t');
        else if (e == 'x' && i + 2 <= line.size()) {
          int v = 0;
          std::from_chars(line.data() + i, line.data() + i + 2, v, 16);
          s.push_back(char(v));
          i += 2;
        } else
          s.push_back(e);
      }
      if (!closed) {
        fail = {t.col, "unterminated string"};
        return false;
      }
      if (t.text == "@") {
        size_t e = i;
        while (e < line.size() && line[e] != ' ' && line[e] != '\t') ++e;
        t.text = "@\x01" + s + std::string(line.substr(i, e - i)); // \x01 marks "quoted file"
        i = e;
      } else {
        t.text = s;
      }
      out.push_back(t);
    } else {
      size_t b = i;
      while (i < line.size() && line[i] != ' ' && line[i] != '\t' && line[i] != ',' &&
             line[i] != '\r')
        ++i;
      out.push_back({std::string(line.substr(b, i - b)), false, int(b) + 1});
    }
  }
  return true;
}

bool is_value_token(const Token& t) {
  if (t.quoted) return true;
  if (t.text.empty()) return false;
  char c = t.text[0];
  return (c >= '0' && c <= '9') || c == '-' || c == '+' || c == '.' || t.text == "inf" ||
         t.text == "nan";
}

// Parses state for one text; one method per line kind.
class Parser {
public:
  ParseResult run(std::string_view text);

private:
  enum class Section { Header, Shader, Symbols, Init, Main, End };

  void line(std::vector<Token>& toks);
  void shader_line(std::vector<Token>& toks);
  void struct_line(std::vector<Token>& toks);
  void symbol_line(std::vector<Token>& toks);
  void op_line(std::vector<Token>& toks);
  size_t values(const std::vector<Token>& toks, size_t i, const Type& t,
                std::vector<ConstValue>& out);
  size_t metadata(const std::vector<Token>& toks, size_t i, std::vector<Metadata>& out);
  Type type(const Token& t);
  // "float[3]" -> "float" and 3; "S[]" -> "S" and -1; "int" -> "int" and 0.
  std::string split_array(const Token& t, int& arraylen);
  SourceLoc loc(const Token& t);
  int integer(const Token& t, std::string_view what);
  const Token& at(const std::vector<Token>& toks, size_t i, std::string_view what);

  Shader sh_;
  Section section_ = Section::Header;
  std::unordered_map<std::string, int> syms_;
  std::map<std::string, int> labels_;
  struct PendingJump {
    int op, slot, line, col;
    std::string label;
  };
  std::vector<PendingJump> pending_;
  int line_no_ = 0;
  int last_col_ = 1;
};

const Token& Parser::at(const std::vector<Token>& toks, size_t i, std::string_view what) {
  if (i >= toks.size()) throw Fail{last_col_, "expected " + std::string(what)};
  return toks[i];
}

int Parser::integer(const Token& t, std::string_view what) {
  int v = 0;
  auto r = std::from_chars(t.text.data(), t.text.data() + t.text.size(), v);
  if (t.quoted || r.ec != std::errc() || r.ptr != t.text.data() + t.text.size())
    throw Fail{t.col, "expected " + std::string(what) + ", found '" + t.text + "'"};
  return v;
}

std::string Parser::split_array(const Token& t, int& arraylen) {
  const std::string& s = t.text;
  arraylen = 0;
  size_t lb = s.find('[');
  if (lb == std::string::npos) return s;
  if (s.back() != ']') throw Fail{t.col, "malformed array type '" + s + "'"};
  std::string len = s.substr(lb + 1, s.size() - lb - 2);
  arraylen = len.empty() ? -1 : integer(Token{len, false, t.col}, "array length");
  if (arraylen == 0) throw Fail{t.col, "array length must not be 0"};
  return s.substr(0, lb);
}

Type Parser::type(const Token& t) {
  Type ty;
  auto b = base_type_from_string(split_array(t, ty.arraylen));
  if (!b || t.quoted) throw Fail{t.col, "unknown type '" + t.text + "'"};
  ty.base = *b;
  return ty;
}

SourceLoc Parser::loc(const Token& t) {
  // @file:line:col, or @\x01<decoded file>:line:col for a quoted file name.
  std::string s = t.text.substr(1);
  bool quoted = !s.empty() && s[0] == '\x01';
  size_t c2 = s.rfind(':');
  size_t c1 = c2 == std::string::npos || c2 == 0 ? std::string::npos : s.rfind(':', c2 - 1);
  if (c1 == std::string::npos) throw Fail{t.col, "malformed location '" + t.text + "'"};
  SourceLoc l;
  l.file = s.substr(quoted ? 1 : 0, c1 - (quoted ? 1 : 0));
  l.line = integer(Token{s.substr(c1 + 1, c2 - c1 - 1), false, t.col}, "line number");
  l.column = integer(Token{s.substr(c2 + 1), false, t.col}, "column number");
  return l;
}

// Reads value tokens from toks[i..]; for fixed types exactly the component count is expected.
size_t Parser::values(const std::vector<Token>& toks, size_t i, const Type& t,
                      std::vector<ConstValue>& out) {
  size_t want = t.arraylen < 0 ? 0 : size_t(t.components()) * size_t(std::max(t.arraylen, 1));
  while (i < toks.size() && is_value_token(toks[i]) && (want == 0 || out.size() < want)) {
    const Token& v = toks[i++];
    ConstValue c;
    if (t.base == BaseType::String) {
      if (!v.quoted) throw Fail{v.col, "expected a string value, found '" + v.text + "'"};
      c.s = v.text;
    } else if (v.quoted) {
      throw Fail{v.col, "expected a number, found a string"};
    } else if (t.base == BaseType::Int) {
      c.i = integer(v, "an integer");
    } else {
      const char* b = v.text.data() + (v.text[0] == '+' ? 1 : 0);
      auto r = std::from_chars(b, v.text.data() + v.text.size(), c.f);
      if (r.ec != std::errc() || r.ptr != v.text.data() + v.text.size())
        throw Fail{v.col, "expected a number, found '" + v.text + "'"};
    }
    out.push_back(c);
  }
  if (out.empty() || (want && out.size() != want))
    throw Fail{i < toks.size() ? toks[i].col : last_col_,
               "expected " + (want ? std::to_string(want) : std::string("some")) +
                   " value(s) for type " + to_string(t)};
  return i;
}

// [[ type name = values, ... ]] starting at toks[i] == "[["; returns the index after "]]".
size_t Parser::metadata(const std::vector<Token>& toks, size_t i, std::vector<Metadata>& out) {
  ++i;
  while (true) {
    Metadata m;
    m.type = type(at(toks, i++, "metadata type"));
    const Token& name = at(toks, i++, "metadata name");
    m.name = name.text;
    if (at(toks, i, "'='").text != "=") throw Fail{toks[i].col, "expected '='"};
    i = values(toks, i + 1, m.type, m.value);
    out.push_back(std::move(m));
    const Token& sep = at(toks, i++, "',' or ']]'");
    if (sep.text == "]]" && !sep.quoted) return i;
    if (sep.text != ",") throw Fail{sep.col, "expected ',' or ']]', found '" + sep.text + "'"};
  }
}

void Parser::shader_line(std::vector<Token>& toks) {
  static constexpr ShaderType kTypes[] = {ShaderType::Surface, ShaderType::Displacement,
                                          ShaderType::Volume, ShaderType::Shader};
  bool found = false;
  for (ShaderType t : kTypes)
    if (toks[0].text == to_string(t)) {
      sh_.type = t;
      found = true;
    }
  if (!found) throw Fail{toks[0].col, "expected a shader type, found '" + toks[0].text + "'"};
  sh_.name = at(toks, 1, "shader name").text;
  size_t i = 2;
  if (i < toks.size() && toks[i].text == "[[") i = metadata(toks, i, sh_.metadata);
  if (i < toks.size()) throw Fail{toks[i].col, "unexpected '" + toks[i].text + "'"};
  section_ = Section::Shader;
}

// struct NAME { TYPE name, ... }: a field's TYPE is a base type or a struct declared above,
// with an optional array suffix.
void Parser::struct_line(std::vector<Token>& toks) {
  StructType st;
  const Token& name = at(toks, 1, "struct name");
  st.name = name.text;
  if (sh_.find_struct(st.name)) throw Fail{name.col, "duplicate struct '" + st.name + "'"};
  if (at(toks, 2, "'{'").text != "{") throw Fail{toks[2].col, "expected '{'"};
  size_t i = 3;
  while (at(toks, i, "a field or '}'").text != "}" || toks[i].quoted) {
    const Token& t = toks[i++];
    StructField f;
    std::string base = split_array(t, f.type.arraylen);
    if (!t.quoted && sh_.find_struct(base))
      f.struct_name = base;
    else
      f.type = type(t);
    f.name = at(toks, i++, "field name").text;
    st.fields.push_back(std::move(f));
    const Token& sep = at(toks, i, "',' or '}'");
    if (sep.text == "," && !sep.quoted)
      ++i;
    else if (sep.text != "}")
      throw Fail{sep.col, "expected ',' or '}'"};
  }
  if (i + 1 < toks.size()) throw Fail{toks[i + 1].col, "unexpected '" + toks[i + 1].text + "'"};
  sh_.structs.push_back(std::move(st));
}

void Parser::symbol_line(std::vector<Token>& toks) {
  static constexpr SymKind kKinds[] = {SymKind::Param, SymKind::OutputParam, SymKind::Global,
                                       SymKind::Local, SymKind::Temp,        SymKind::Const};
  Symbol s;
  bool found = false;
  for (SymKind k : kKinds)
    if (toks[0].text == to_string(k) && !toks[0].quoted) {
      s.kind = k;
      found = true;
    }
  if (!found) throw Fail{toks[0].col, "expected a symbol kind, found '" + toks[0].text + "'"};
  s.type = type(at(toks, 1, "symbol type"));
  const Token& name = at(toks, 2, "symbol name");
  s.name = name.text;
  if (syms_.count(s.name)) throw Fail{name.col, "duplicate symbol '" + s.name + "'"};
  size_t i = 3;
  if (i < toks.size() && toks[i].text == "=" && !toks[i].quoted)
    i = values(toks, i + 1, s.type, s.init);
  for (; i < toks.size(); ++i) {
    const Token& t = toks[i];
    if (t.text == "derivs")
      s.derivs = true;
    else if (t.text == "folded")
      s.folded = true;
    else if (t.text.rfind("init=", 0) == 0) {
      size_t colon = t.text.find(':');
      if (colon == std::string::npos) throw Fail{t.col, "expected init=BEGIN:END"};
      s.init_begin = integer(Token{t.text.substr(5, colon - 5), false, t.col}, "init begin");
      s.init_end = integer(Token{t.text.substr(colon + 1), false, t.col}, "init end");
    } else if (t.text.rfind("len=", 0) == 0) {
      s.default_len = integer(Token{t.text.substr(4), false, t.col}, "default length");
    } else if (t.text.rfind("struct=", 0) == 0) {
      s.struct_name = t.text.substr(7);
      if (s.struct_name.empty() && i + 1 < toks.size() && toks[i + 1].quoted)
        s.struct_name = toks[++i].text;
    } else if (t.text == "[[") {
      i = metadata(toks, i, s.metadata) - 1;
    } else if (!t.quoted && t.text[0] == '@') {
      s.loc = loc(t);
    } else {
      throw Fail{t.col, "unexpected '" + t.text + "' in symbol declaration"};
    }
  }
  syms_[s.name] = int(sh_.symbols.size());
  sh_.symbols.push_back(std::move(s));
}

void Parser::op_line(std::vector<Token>& toks) {
  Op op;
  std::optional<Opcode> code = opcode_from_name(toks[0].text);
  if (!code) throw Fail{toks[0].col, "unknown opcode '" + toks[0].text + "'"};
  op.opcode = *code;
  op.written_mask = info(op.opcode).written;
  size_t i = 1;
  for (; i < toks.size(); ++i) {
    const Token& t = toks[i];
    if (!t.quoted &&
        (t.text == "->" || t.text[0] == '@' || t.text[0] == '%' || t.text.rfind("wmask=", 0) == 0))
      break;
    auto it = syms_.find(t.text);
    if (it == syms_.end()) throw Fail{t.col, "unknown symbol '" + t.text + "'"};
    op.args.push_back(it->second);
  }
  if (i < toks.size() && toks[i].text == "->") {
    for (++i; i < toks.size() && !toks[i].quoted && toks[i].text[0] != '@' &&
              toks[i].text[0] != '%' && toks[i].text.rfind("wmask=", 0) != 0;
         ++i) {
      pending_.push_back(
          {int(sh_.ops.size()), int(op.jumps.size()), line_no_, toks[i].col, toks[i].text});
      op.jumps.push_back(-1);
    }
  }
  if (i < toks.size() && toks[i].text.rfind("wmask=", 0) == 0) {
    const Token& t = toks[i++];
    op.written_mask = uint32_t(integer(Token{t.text.substr(6), false, t.col}, "written mask"));
  }
  if (i < toks.size() && !toks[i].quoted && toks[i].text == "%infn") op.in_function = true, ++i;
  if (i < toks.size() && !toks[i].quoted && toks[i].text[0] == '@') op.loc = loc(toks[i++]);
  if (i < toks.size()) throw Fail{toks[i].col, "unexpected '" + toks[i].text + "'"};
  if (op.opcode == Opcode::UseParam) sh_.useparams = true;
  sh_.ops.push_back(std::move(op));
}

void Parser::line(std::vector<Token>& toks) {
  const Token& first = toks[0];
  const std::string& w = first.text;
  if (section_ == Section::Header) {
    if (w != "lobe-ir" || at(toks, 1, "version").text != "1" || toks.size() != 2)
      throw Fail{first.col, "expected 'lobe-ir 1'"};
    section_ = Section::Shader;
    return;
  }
  if (section_ == Section::End) throw Fail{first.col, "text after 'end'"};
  if (!first.quoted && toks.size() == 1) {
    if (w == "symbols" && section_ == Section::Shader) {
      section_ = Section::Symbols;
      return;
    }
    if (w == "init" && section_ == Section::Symbols) {
      section_ = Section::Init;
      return;
    }
    if (w == "main" && (section_ == Section::Symbols || section_ == Section::Init)) {
      section_ = Section::Main;
      sh_.main_begin = int(sh_.ops.size());
      return;
    }
    if (w == "end" && section_ == Section::Main) {
      section_ = Section::End;
      return;
    }
    if (w.size() > 1 && w.back() == ':' && section_ >= Section::Init) {
      std::string label = w.substr(0, w.size() - 1);
      if (!labels_.emplace(label, int(sh_.ops.size())).second)
        throw Fail{first.col, "duplicate label '" + label + "'"};
      return;
    }
  }
  if (section_ == Section::Shader && w == "struct" && !first.quoted) return struct_line(toks);
  if (section_ == Section::Symbols) return symbol_line(toks);
  if (section_ == Section::Init || section_ == Section::Main) return op_line(toks);
  throw Fail{first.col, "unexpected '" + w + "'"};
}

ParseResult Parser::run(std::string_view text) {
  ParseResult res;
  size_t pos = 0;
  bool named = false;
  try {
    while (pos <= text.size()) {
      size_t nl = text.find('\n', pos);
      if (nl == std::string_view::npos) nl = text.size();
      std::string_view ln = text.substr(pos, nl - pos);
      pos = nl + 1;
      ++line_no_;
      std::vector<Token> toks;
      Fail f{0, ""};
      if (!tokenize(ln, toks, f)) throw f;
      if (toks.empty() || (!toks[0].quoted && toks[0].text[0] == '#')) continue;
      last_col_ = int(ln.size()) + 1;
      if (section_ == Section::Shader && !named) {
        shader_line(toks);
        named = true;
        continue;
      }
      line(toks);
    }
    if (section_ != Section::End) throw Fail{1, "missing 'end'"};
    for (const PendingJump& p : pending_) {
      auto it = labels_.find(p.label);
      if (it == labels_.end()) {
        line_no_ = p.line;
        throw Fail{p.col, "undefined label '" + p.label + "'"};
      }
      sh_.ops[p.op].jumps[p.slot] = it->second;
    }
  } catch (const Fail& f) {
    res.error = ParseError{line_no_, f.col, f.message};
    return res;
  }
  res.shader = std::move(sh_);
  return res;
}

} // namespace

ParseResult parse(std::string_view text) { return Parser().run(text); }

} // namespace lobe::ir
