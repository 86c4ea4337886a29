// The lexer: turns the preprocessed text into tokens. Literals are decoded here (integers
// including hex, floats with exponents and an f suffix, strings with C escapes); adjacent
// string literals stay separate tokens (the parser concatenates them). Bad input (stray or
// binary characters, unterminated strings or comments, malformed numbers) is reported and
// skipped: the lexer never fails and always ends with Eof.
#pragma once

#include "diag/diagnostics.h"
#include "diag/source_manager.h"
#include "lex/token.h"

#include <string>
#include <vector>

namespace lobe::lex {

struct TokenStream {
  std::vector<Token> tokens;        // ends with Eof
  std::vector<std::string> strings; // decoded string literal values (Token::str)
};

class Lexer {
public:
  Lexer(const diag::SourceManager& sm, diag::DiagnosticEngine& diags, int buffer_id);

  Token next();
  const std::string& string_value(const Token& t) const { return strings_[t.str]; }
  std::vector<std::string> take_strings() { return std::move(strings_); }

private:
  Token make(Tok k, size_t begin);
  Token identifier();
  Token number();
  Token string_literal();
  Token punctuator();
  bool skip_space_and_comments();
  void escape(std::string& out);
  char at(size_t i) const { return i < text_.size() ? text_[i] : '\0'; }
  diag::SourceLoc loc(size_t i) const { return base_.advanced(uint32_t(i)); }

  std::string_view text_;
  diag::SourceLoc base_;
  diag::DiagnosticEngine& diags_;
  std::vector<std::string> strings_;
  size_t pos_ = 0;
  bool reported_binary_ = false;
};

// Lexes a whole buffer.
TokenStream lex_buffer(const diag::SourceManager& sm, diag::DiagnosticEngine& diags, int buffer_id);

} // namespace lobe::lex
