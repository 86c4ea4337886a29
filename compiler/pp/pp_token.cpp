// The preprocessing tokenizer.
#include "pp/pp_token.h"

#include <algorithm>
#include <cctype>

namespace lobe::pp {

bool PPToken::hidden(const Macro* m) const {
  return hide && std::find(hide->begin(), hide->end(), m) != hide->end();
}

namespace {

bool ident_start(char c) { return std::isalpha(static_cast<unsigned char>(c)) || c == '_'; }
bool ident_char(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }

// Longest punctuators first, so "<<=" wins over "<<" and "<".
const char* const kPuncts[] = {"<<=", ">>=", "##", "<<", ">>", "<=", ">=", "==", "!=", "&&", "||",
                               "++",  "--",  "+=", "-=", "*=", "/=", "%=", "&=", "|=", "^=", "[["};

class Tokenizer {
public:
  Tokenizer(std::string_view t, diag::SourceLoc base, diag::DiagnosticEngine& d)
      : text_(t), base_(base), diags_(d) {}

  std::vector<PPToken> run() {
    out_.reserve(text_.size() / 3 + 8);
    while (pos_ < text_.size()) step();
    push(PPKind::Newline, pos_, 0);
    push(PPKind::Eof, pos_, 0);
    return std::move(out_);
  }

private:
  char at(size_t i) const { return i < text_.size() ? text_[i] : '\0'; }

  // A backslash followed by a newline (optionally \r\n) continues the line.
  size_t continuation(size_t i) const {
    if (at(i) != '\\') return 0;
    if (at(i + 1) == '\n') return 2;
    if (at(i + 1) == '\r' && at(i + 2) == '\n') return 3;
    return 0;
  }

  void push(PPKind k, size_t begin, size_t len) {
    PPToken t;
    t.kind = k;
    t.text = std::string(text_.substr(begin, len));
    t.loc = base_.advanced(uint32_t(begin));
    t.space_before = space_;
    t.at_line_start = line_start_;
    out_.push_back(std::move(t));
    space_ = false;
    line_start_ = (k == PPKind::Newline);
  }

  void step() {
    char c = text_[pos_];
    if (size_t n = continuation(pos_)) {
      pos_ += n;
      space_ = true;
      return;
    }
    if (c == '\n') {
      push(PPKind::Newline, pos_, 1);
      ++pos_;
      return;
    }
    if (c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v') {
      ++pos_;
      space_ = true;
      return;
    }
    if (c == '/' && at(pos_ + 1) == '/') {
      line_comment();
      return;
    }
    if (c == '/' && at(pos_ + 1) == '*') {
      block_comment();
      return;
    }
    if (ident_start(c)) {
      run_while(PPKind::Ident, ident_char);
      return;
    }
    if (std::isdigit(static_cast<unsigned char>(c)) ||
        (c == '.' && std::isdigit(static_cast<unsigned char>(at(pos_ + 1))))) {
      number();
      return;
    }
    if (c == '"') {
      string_lit();
      return;
    }
    for (const char* p : kPuncts) {
      if (p[0] != c) continue;
      size_t n = p[1] == '\0' ? 1 : (p[2] == '\0' ? 2 : 3);
      if (text_.compare(pos_, n, p) == 0) {
        push(PPKind::Punct, pos_, n);
        pos_ += n;
        return;
      }
    }
    bool punct = std::ispunct(static_cast<unsigned char>(c)) && c != '\\' && c != '`' && c != '$' &&
                 c != '@' && c != '\'';
    push(punct ? PPKind::Punct : PPKind::Other, pos_, 1);
    ++pos_;
  }

  template <class Pred> void run_while(PPKind k, Pred p) {
    size_t b = pos_;
    while (pos_ < text_.size() && p(text_[pos_])) ++pos_;
    push(k, b, pos_ - b);
  }

  // pp-number: digits, letters, '.', '_' and a sign after an exponent letter.
  void number() {
    size_t b = pos_;
    while (pos_ < text_.size()) {
      char c = text_[pos_];
      if ((c == '+' || c == '-') && pos_ > b &&
          (text_[pos_ - 1] == 'e' || text_[pos_ - 1] == 'E') &&
          !(text_[b] == '0' && (at(b + 1) == 'x' || at(b + 1) == 'X'))) {
        ++pos_;
      } else if (ident_char(c) || c == '.') {
        ++pos_;
      } else {
        break;
      }
    }
    push(PPKind::Number, b, pos_ - b);
  }

  // A string literal up to the closing quote or the end of the line (the lexer reports it).
  void string_lit() {
    size_t b = pos_++;
    while (pos_ < text_.size() && text_[pos_] != '"' && text_[pos_] != '\n') {
      if (text_[pos_] == '\\' && pos_ + 1 < text_.size() && text_[pos_ + 1] != '\n') ++pos_;
      ++pos_;
    }
    if (at(pos_) == '"') ++pos_;
    push(PPKind::String, b, pos_ - b);
  }

  void line_comment() {
    while (pos_ < text_.size() && text_[pos_] != '\n') {
      if (size_t n = continuation(pos_))
        pos_ += n;
      else
        ++pos_;
    }
    space_ = true;
  }

  void block_comment() {
    size_t b = pos_;
    size_t end = text_.find("*/", pos_ + 2);
    if (end == std::string_view::npos) {
      diags_.report(
          diag::DiagId::err_unterminated_comment,
          diag::SourceRange(base_.advanced(uint32_t(b)), base_.advanced(uint32_t(b + 2))));
      pos_ = text_.size();
    } else {
      pos_ = end + 2;
    }
    space_ = true;
  }

  std::string_view text_;
  diag::SourceLoc base_;
  diag::DiagnosticEngine& diags_;
  std::vector<PPToken> out_;
  size_t pos_ = 0;
  bool space_ = false;
  bool line_start_ = true;
};

} // namespace

std::vector<PPToken> tokenize(std::string_view text, diag::SourceLoc base,
                              diag::DiagnosticEngine& diags) {
  return Tokenizer(text, base, diags).run();
}

std::string spell(const std::vector<PPToken>& toks) {
  std::string s;
  for (const auto& t : toks) {
    if (t.kind == PPKind::Newline || t.kind == PPKind::Eof) continue;
    if (t.space_before && !s.empty()) s += ' ';
    s += t.text;
  }
  return s;
}

} // namespace lobe::pp
