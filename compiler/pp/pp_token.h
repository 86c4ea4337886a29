// Preprocessing tokens: the preprocessor's view of the text (identifiers, pp-numbers, string
// literals, punctuators, newlines), produced from one file buffer. Comments and whitespace are
// not tokens; they set `space_before`. Backslash-newline joins lines.
#pragma once

#include "diag/diagnostics.h"
#include "diag/source_location.h"

#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace lobe::pp {

struct Macro;

enum class PPKind : uint8_t { Ident, Number, String, Punct, Other, Newline, Eof };

struct PPToken {
  PPKind kind = PPKind::Eof;
  std::string text;
  diag::SourceLoc loc; // where it is spelled (file location)
  bool space_before = false;
  bool at_line_start = false;
  // Macro expansion bookkeeping: the outermost macro whose body produced this token (null if
  // spelled in a file or in a macro argument), and that macro's invocation location.
  const Macro* from_macro = nullptr;
  diag::SourceLoc exp_loc;
  // Macros that must not expand this token again (the "hide set" of Prosser's algorithm).
  std::shared_ptr<const std::vector<const Macro*>> hide;

  bool is(PPKind k, std::string_view t) const { return kind == k && text == t; }
  bool is_punct(std::string_view t) const { return is(PPKind::Punct, t); }
  bool hidden(const Macro* m) const;
  uint32_t end_offset() const { return loc.offset + uint32_t(text.size()); }
};

// Tokenizes `text` (whose first byte is at `base`). Reports unterminated block comments.
// The result always ends with a Newline token and an Eof token.
std::vector<PPToken> tokenize(std::string_view text, diag::SourceLoc base,
                              diag::DiagnosticEngine& diags);

// Spells tokens back as text, one space where a token had whitespace before it.
std::string spell(const std::vector<PPToken>& toks);

} // namespace lobe::pp
