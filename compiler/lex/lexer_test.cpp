// Lexer tests: every token class, literal decoding, and bad input.
#include "lex/lexer.h"

#include <gtest/gtest.h>

using namespace lobe;
using lex::Tok;

namespace {

struct LexRun {
  diag::SourceManager sm;
  diag::DiagnosticEngine diags;
  lex::TokenStream ts;
  explicit LexRun(const std::string& text) {
    int id = sm.add_file("t.osl", text);
    ts = lex::lex_buffer(sm, diags, id);
  }
  std::vector<Tok> kinds() const {
    std::vector<Tok> k;
    for (auto& t : ts.tokens) k.push_back(t.kind);
    return k;
  }
  bool has(diag::DiagId id) const {
    for (auto& d : diags.diagnostics())
      if (d.id == id) return true;
    return false;
  }
};

} // namespace

TEST(Lexer, KeywordsIdentifiersPunctuators) {
  LexRun r("surface shader_x and or not closure color <<= >>= [[ ]] a[b[1]] ++ -- != == && || ?:");
  std::vector<Tok> want = {
      Tok::KwSurface, Tok::Ident,     Tok::KwAnd,      Tok::KwOr,     Tok::KwNot,    Tok::KwClosure,
      Tok::KwColor,   Tok::ShlAssign, Tok::ShrAssign,  Tok::MetaOpen, Tok::RBracket, Tok::RBracket,
      Tok::Ident,     Tok::LBracket,  Tok::Ident,      Tok::LBracket, Tok::IntLit,   Tok::RBracket,
      Tok::RBracket,  Tok::PlusPlus,  Tok::MinusMinus, Tok::NotEq,    Tok::EqEq,     Tok::AmpAmp,
      Tok::PipePipe,  Tok::Question,  Tok::Colon,      Tok::Eof};
  EXPECT_EQ(r.kinds(), want);
  EXPECT_FALSE(r.diags.has_errors());
}

TEST(Lexer, IntegerLiterals) {
  LexRun r("0 42 0x1F 0XfF 2147483647 0xffffffff");
  ASSERT_EQ(r.ts.tokens.size(), 7u);
  EXPECT_EQ(r.ts.tokens[1].ival, 42);
  EXPECT_EQ(r.ts.tokens[2].ival, 31);
  EXPECT_EQ(r.ts.tokens[3].ival, 255);
  EXPECT_EQ(r.ts.tokens[4].ival, 2147483647);
  EXPECT_EQ(r.ts.tokens[5].ival, -1);
  EXPECT_FALSE(r.diags.has_errors());
}

TEST(Lexer, FloatLiterals) {
  LexRun r("1.5 .25 3. 1e3 2.5E-2 7f 1.0f 6e+1");
  std::vector<float> want = {1.5f, 0.25f, 3.0f, 1000.0f, 0.025f, 7.0f, 1.0f, 60.0f};
  ASSERT_EQ(r.ts.tokens.size(), want.size() + 1);
  for (size_t i = 0; i < want.size(); ++i) {
    EXPECT_EQ(r.ts.tokens[i].kind, Tok::FloatLit) << i;
    EXPECT_FLOAT_EQ(r.ts.tokens[i].fval, want[i]) << i;
  }
}

TEST(Lexer, MemberAccessAfterNumberIsNotAFloat) {
  LexRun r("c.r a.x");
  EXPECT_EQ(r.kinds(), (std::vector<Tok>{Tok::Ident, Tok::Dot, Tok::Ident, Tok::Ident, Tok::Dot,
                                         Tok::Ident, Tok::Eof}));
}

TEST(Lexer, BadNumbers) {
  LexRun r("12abc 0x 99999999999 1.2.3");
  EXPECT_TRUE(r.has(diag::DiagId::err_bad_number));
  EXPECT_TRUE(r.has(diag::DiagId::err_int_too_large));
  EXPECT_EQ(r.diags.error_count(), 4);
}

// oslc decodes \n \t \r \a \b \f \v \\ \" and octal; other escapes stay as written (oslc
// 1.13.12 + testshade: strlen("\x41") is 4, "\e" 2, "\'" 2, "\?" 2, "\101" 1).
TEST(Lexer, StringEscapes) {
  LexRun r(R"("a\tb\n\"q\"\\ \x41\101" "x")");
  ASSERT_EQ(r.ts.tokens.size(), 3u);
  EXPECT_EQ(r.ts.strings[r.ts.tokens[0].str], "a\tb\n\"q\"\\ \\x41A");
  EXPECT_EQ(r.ts.strings[r.ts.tokens[1].str], "x");
  EXPECT_FALSE(r.diags.has_errors());
}

TEST(Lexer, OtherEscapesStayAsWritten) {
  LexRun r(R"("\q\e\'\?")");
  EXPECT_FALSE(r.diags.has_errors());
  EXPECT_EQ(r.diags.warning_count(), 0);
  EXPECT_EQ(r.ts.strings[0], "\\q\\e\\'\\?");
}

TEST(Lexer, UnterminatedStringAndComment) {
  LexRun r("\"abc\nx /* open");
  EXPECT_TRUE(r.has(diag::DiagId::err_unterminated_string));
  EXPECT_TRUE(r.has(diag::DiagId::err_unterminated_comment));
  EXPECT_EQ(r.ts.tokens.back().kind, Tok::Eof);
}

TEST(Lexer, CommentsAreSkipped) {
  LexRun r("a // b\n/* c \n d */ e");
  EXPECT_EQ(r.kinds(), (std::vector<Tok>{Tok::Ident, Tok::Ident, Tok::Eof}));
}

TEST(Lexer, InvalidCharactersAndBinary) {
  std::string s = "a @ $ b";
  s += '\0';
  s += "\x01\x02 c";
  LexRun r(s);
  EXPECT_TRUE(r.has(diag::DiagId::err_invalid_char));
  EXPECT_TRUE(r.has(diag::DiagId::err_binary_input));
  EXPECT_EQ(r.ts.tokens.back().kind, Tok::Eof);
}

TEST(Lexer, Ranges) {
  LexRun r("  foo += 1.5");
  auto b = r.sm.presumed(r.ts.tokens[1].range.begin);
  EXPECT_EQ(b.column, 7);
  EXPECT_EQ(r.ts.tokens[1].range.end.offset - r.ts.tokens[1].range.begin.offset, 2u);
  EXPECT_EQ(r.ts.tokens[0].text, "foo");
}

TEST(Lexer, RandomBytesNeverCrash) {
  uint32_t state = 12345;
  for (int round = 0; round < 50; ++round) {
    std::string s;
    for (int i = 0; i < 2000; ++i) {
      state = state * 1664525u + 1013904223u;
      s += char(state >> 24);
    }
    LexRun r(s);
    EXPECT_EQ(r.ts.tokens.back().kind, Tok::Eof);
  }
}
