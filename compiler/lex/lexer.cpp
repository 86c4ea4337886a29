// The lexer.
#include "lex/lexer.h"

#include <cctype>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <unordered_map>

namespace lobe::lex {

using diag::DiagId;
using diag::SourceRange;

namespace {

struct Spelling {
  Tok tok;
  const char* text;
};

const Spelling kKeywords[] = {
    {Tok::KwAnd, "and"},
    {Tok::KwBreak, "break"},
    {Tok::KwClosure, "closure"},
    {Tok::KwColor, "color"},
    {Tok::KwContinue, "continue"},
    {Tok::KwDo, "do"},
    {Tok::KwElse, "else"},
    {Tok::KwFloat, "float"},
    {Tok::KwFor, "for"},
    {Tok::KwIf, "if"},
    {Tok::KwInt, "int"},
    {Tok::KwMatrix, "matrix"},
    {Tok::KwNormal, "normal"},
    {Tok::KwNot, "not"},
    {Tok::KwOr, "or"},
    {Tok::KwOutput, "output"},
    {Tok::KwPoint, "point"},
    {Tok::KwReturn, "return"},
    {Tok::KwString, "string"},
    {Tok::KwStruct, "struct"},
    {Tok::KwVector, "vector"},
    {Tok::KwVoid, "void"},
    {Tok::KwWhile, "while"},
    {Tok::KwSurface, "surface"},
    {Tok::KwDisplacement, "displacement"},
    {Tok::KwVolume, "volume"},
    {Tok::KwShader, "shader"},
};

// Longest first, so that "<<=" wins over "<<" and "<".
const Spelling kPuncts[] = {
    {Tok::ShlAssign, "<<="},    {Tok::ShrAssign, ">>="}, {Tok::MetaOpen, "[["},
    {Tok::PlusPlus, "++"},      {Tok::MinusMinus, "--"}, {Tok::PlusAssign, "+="},
    {Tok::MinusAssign, "-="},   {Tok::StarAssign, "*="}, {Tok::SlashAssign, "/="},
    {Tok::PercentAssign, "%="}, {Tok::AmpAssign, "&="},  {Tok::PipeAssign, "|="},
    {Tok::CaretAssign, "^="},   {Tok::Shl, "<<"},        {Tok::Shr, ">>"},
    {Tok::LessEq, "<="},        {Tok::GreaterEq, ">="},  {Tok::EqEq, "=="},
    {Tok::NotEq, "!="},         {Tok::AmpAmp, "&&"},     {Tok::PipePipe, "||"},
    {Tok::LParen, "("},         {Tok::RParen, ")"},      {Tok::LBracket, "["},
    {Tok::RBracket, "]"},       {Tok::LBrace, "{"},      {Tok::RBrace, "}"},
    {Tok::Comma, ","},          {Tok::Semi, ";"},        {Tok::Colon, ":"},
    {Tok::Question, "?"},       {Tok::Dot, "."},         {Tok::Plus, "+"},
    {Tok::Minus, "-"},          {Tok::Star, "*"},        {Tok::Slash, "/"},
    {Tok::Percent, "%"},        {Tok::Amp, "&"},         {Tok::Pipe, "|"},
    {Tok::Caret, "^"},          {Tok::Tilde, "~"},       {Tok::Bang, "!"},
    {Tok::Less, "<"},           {Tok::Greater, ">"},     {Tok::Assign, "="},
};

bool ident_start(char c) { return std::isalpha(static_cast<unsigned char>(c)) || c == '_'; }
bool ident_char(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }
bool digit(char c) { return c >= '0' && c <= '9'; }

} // namespace

const char* tok_spelling(Tok t) {
  switch (t) {
  case Tok::Eof:
    return "end of file";
  case Tok::Ident:
    return "identifier";
  case Tok::IntLit:
    return "integer literal";
  case Tok::FloatLit:
    return "float literal";
  case Tok::StringLit:
    return "string literal";
  case Tok::Error:
    return "invalid token";
  default:
    break;
  }
  for (const auto& k : kKeywords)
    if (k.tok == t) return k.text;
  for (const auto& p : kPuncts)
    if (p.tok == t) return p.text;
  return "?";
}

Lexer::Lexer(const diag::SourceManager& sm, diag::DiagnosticEngine& diags, int buffer_id)
    : text_(sm.buffer_text(buffer_id)), base_(sm.buffer_start(buffer_id)), diags_(diags) {}

Token Lexer::make(Tok k, size_t begin) {
  Token t;
  t.kind = k;
  t.range = SourceRange(loc(begin), loc(pos_));
  t.text = text_.substr(begin, pos_ - begin);
  return t;
}

// Skips whitespace and comments; false once the input is exhausted.
bool Lexer::skip_space_and_comments() {
  while (pos_ < text_.size()) {
    char c = text_[pos_];
    if (c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f' || c == '\v') {
      ++pos_;
    } else if (c == '/' && at(pos_ + 1) == '/') {
      while (pos_ < text_.size() && text_[pos_] != '\n') ++pos_;
    } else if (c == '/' && at(pos_ + 1) == '*') {
      size_t end = text_.find("*/", pos_ + 2);
      if (end == std::string_view::npos) {
        diags_.report(DiagId::err_unterminated_comment, SourceRange(loc(pos_), loc(pos_ + 2)));
        pos_ = text_.size();
      } else {
        pos_ = end + 2;
      }
    } else {
      return true;
    }
  }
  return false;
}

Token Lexer::next() {
  while (true) {
    if (diags_.stopped() || !skip_space_and_comments()) {
      pos_ = text_.size();
      return make(Tok::Eof, pos_);
    }
    char c = text_[pos_];
    if (ident_start(c)) return identifier();
    if (digit(c) || (c == '.' && digit(at(pos_ + 1)))) return number();
    if (c == '"') return string_literal();
    if (Token t = punctuator(); t.kind != Tok::Eof) return t;
    // Anything else is reported once per run of bad bytes and becomes one Error token.
    size_t b = pos_;
    while (pos_ < text_.size() && !ident_start(text_[pos_]) &&
           !std::isspace(static_cast<unsigned char>(text_[pos_])) &&
           !std::ispunct(static_cast<unsigned char>(text_[pos_])))
      ++pos_;
    if (pos_ == b) ++pos_;
    bool nul = std::memchr(text_.data() + b, '\0', pos_ - b) != nullptr;
    if (nul && !reported_binary_) {
      reported_binary_ = true;
      diags_.report(DiagId::err_binary_input, loc(b));
    } else if (!nul) {
      unsigned char u = static_cast<unsigned char>(text_[b]);
      std::string shown = std::isprint(u) ? std::string(1, char(u))
                                          : "\\x" + std::string(1, "0123456789abcdef"[u >> 4]) +
                                                "0123456789abcdef"[u & 15];
      diags_.report(DiagId::err_invalid_char, SourceRange(loc(b), loc(b + 1)), {shown});
    }
    return make(Tok::Error, b); // the parser stays silent about it: already reported
  }
}

Token Lexer::identifier() {
  size_t b = pos_;
  while (pos_ < text_.size() && ident_char(text_[pos_])) ++pos_;
  Token t = make(Tok::Ident, b);
  static const std::unordered_map<std::string_view, Tok> kKeywordMap = [] {
    std::unordered_map<std::string_view, Tok> m;
    for (const auto& k : kKeywords) m.emplace(k.text, k.tok);
    return m;
  }();
  if (auto it = kKeywordMap.find(t.text); it != kKeywordMap.end()) t.kind = it->second;
  return t;
}

// int: decimal or 0x hex; float: digits with '.', exponent, optional f/F suffix.
Token Lexer::number() {
  size_t b = pos_;
  bool is_float = false, hex = false;
  if (text_[pos_] == '0' && (at(pos_ + 1) == 'x' || at(pos_ + 1) == 'X')) {
    hex = true;
    pos_ += 2;
    while (std::isxdigit(static_cast<unsigned char>(at(pos_)))) ++pos_;
  } else {
    while (digit(at(pos_))) ++pos_;
    if (at(pos_) == '.') {
      is_float = true;
      ++pos_;
      while (digit(at(pos_))) ++pos_;
    }
    if ((at(pos_) == 'e' || at(pos_) == 'E') &&
        (digit(at(pos_ + 1)) ||
         ((at(pos_ + 1) == '+' || at(pos_ + 1) == '-') && digit(at(pos_ + 2))))) {
      is_float = true;
      pos_ += 2;
      while (digit(at(pos_))) ++pos_;
    }
    if (at(pos_) == 'f' || at(pos_) == 'F') {
      is_float = true;
      ++pos_;
    }
  }
  size_t digits_end = pos_;
  bool bad = (hex && digits_end == b + 2) || ident_char(at(pos_)) || at(pos_) == '.';
  while (ident_char(at(pos_)) || at(pos_) == '.') ++pos_;
  Token t = make(is_float ? Tok::FloatLit : Tok::IntLit, b);
  if (bad) {
    diags_.report(DiagId::err_bad_number, t.range, {std::string(t.text)});
    t.kind = Tok::Error;
    return t;
  }
  std::string s(text_.substr(b, digits_end - b));
  if (is_float) {
    t.fval = std::strtof(s.c_str(), nullptr); // overflow gives inf, as in C
  } else {
    errno = 0;
    unsigned long long v = std::strtoull(s.c_str(), nullptr, hex ? 16 : 10);
    // Hex literals may fill all 32 bits (0xffffffff is -1); decimals must fit a signed int.
    if (errno == ERANGE || v > (hex ? 0xffffffffull : 2147483648ull)) {
      diags_.report(DiagId::err_int_too_large, t.range, {s});
      v = 0;
    }
    t.ival = int32_t(uint32_t(v)); // 2147483648 is allowed for `-2147483648`
  }
  return t;
}

// The escapes oslc decodes (OpenImageIO's unescape_chars): \n \t \r \a \b \f \v \\ \" and
// octal \0-\377. Any other (\' \? \xHH \e ...) stays as written, backslash included, without
// a warning, as in oslc: "\x41" is four characters.
void Lexer::escape(std::string& out) {
  char c = at(pos_++);
  switch (c) {
  case 'n':
    out += '\n';
    return;
  case 't':
    out += '\t';
    return;
  case 'r':
    out += '\r';
    return;
  case 'a':
    out += '\a';
    return;
  case 'b':
    out += '\b';
    return;
  case 'f':
    out += '\f';
    return;
  case 'v':
    out += '\v';
    return;
  case '\\':
  case '"':
    out += c;
    return;
  default:
    break;
  }
  if (c >= '0' && c <= '7') {
    int v = c - '0';
    for (int n = 1; n < 3 && at(pos_) >= '0' && at(pos_) <= '7'; ++n)
      v = v * 8 + (at(pos_++) - '0');
    out += char(v & 0xff);
    return;
  }
  out += '\\';
  out += c;
}

Token Lexer::string_literal() {
  size_t b = pos_++;
  std::string value;
  while (pos_ < text_.size() && text_[pos_] != '"' && text_[pos_] != '\n') {
    char c = text_[pos_++];
    if (c == '\\' && pos_ < text_.size() && text_[pos_] != '\n')
      escape(value);
    else
      value += c;
  }
  if (at(pos_) != '"') {
    diags_.report(DiagId::err_unterminated_string, SourceRange(loc(b), loc(b + 1)));
  } else {
    ++pos_;
  }
  // OSL's strings are C strings: a literal ends at an escaped NUL ("a\0bc" is "a"; OSL 1.13.12
  // prints 1 for strlen("a\0bc")).
  if (size_t nul = value.find('\0'); nul != std::string::npos) value.resize(nul);
  Token t = make(Tok::StringLit, b);
  t.str = uint32_t(strings_.size());
  strings_.push_back(std::move(value));
  return t;
}

// A punctuator, or Eof if none matches here. `]]` is two `]` tokens: `a[b[1]]` must index.
Token Lexer::punctuator() {
  char c = text_[pos_];
  for (const auto& p : kPuncts) {
    if (p.text[0] != c) continue;
    size_t n = p.text[1] == '\0' ? 1 : (p.text[2] == '\0' ? 2 : 3);
    if (text_.compare(pos_, n, p.text) == 0) {
      size_t b = pos_;
      pos_ += n;
      return make(p.tok, b);
    }
  }
  return Token{};
}

TokenStream lex_buffer(const diag::SourceManager& sm, diag::DiagnosticEngine& diags,
                       int buffer_id) {
  Lexer lx(sm, diags, buffer_id);
  TokenStream ts;
  ts.tokens.reserve(sm.buffer_text(buffer_id).size() / 4 + 16);
  while (true) {
    ts.tokens.push_back(lx.next());
    if (ts.tokens.back().kind == Tok::Eof) break;
  }
  ts.strings = lx.take_strings();
  return ts;
}

} // namespace lobe::lex
