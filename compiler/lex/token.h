// Tokens of Lobe's (OSL's) language, as the lexer produces them from preprocessed text.
#pragma once

#include "diag/source_location.h"

#include <cstdint>
#include <string_view>

namespace lobe::lex {

enum class Tok : uint8_t {
  Eof,
  Ident,
  IntLit,
  FloatLit,
  StringLit,
  // keywords
  KwAnd,
  KwBreak,
  KwClosure,
  KwColor,
  KwContinue,
  KwDo,
  KwElse,
  KwFloat,
  KwFor,
  KwIf,
  KwInt,
  KwMatrix,
  KwNormal,
  KwNot,
  KwOr,
  KwOutput,
  KwPoint,
  KwReturn,
  KwString,
  KwStruct,
  KwVector,
  KwVoid,
  KwWhile,
  KwSurface,
  KwDisplacement,
  KwVolume,
  KwShader,
  // punctuators
  LParen,
  RParen,
  LBracket,
  RBracket,
  LBrace,
  RBrace,
  MetaOpen /* [[ */,
  Comma,
  Semi,
  Colon,
  Question,
  Dot,
  Plus,
  Minus,
  Star,
  Slash,
  Percent,
  Amp,
  Pipe,
  Caret,
  Tilde,
  Bang,
  Less,
  Greater,
  Assign,
  PlusPlus,
  MinusMinus,
  PlusAssign,
  MinusAssign,
  StarAssign,
  SlashAssign,
  PercentAssign,
  AmpAssign,
  PipeAssign,
  CaretAssign,
  ShlAssign,
  ShrAssign,
  Shl,
  Shr,
  LessEq,
  GreaterEq,
  EqEq,
  NotEq,
  AmpAmp,
  PipePipe,
  Error, // an unusable character sequence (already reported)
};

// The spelling of a keyword or punctuator ("while", "+="), or a description ("identifier").
const char* tok_spelling(Tok t);

struct Token {
  Tok kind = Tok::Eof;
  diag::SourceRange range;
  std::string_view text; // the characters in the preprocessed buffer
  union {
    int32_t ival;
    float fval;
    uint32_t str; // StringLit: index into the lexer's decoded string table
  };
  Token() : ival(0) {}
  bool is(Tok k) const { return kind == k; }
};

} // namespace lobe::lex
