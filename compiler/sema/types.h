// Type rules shared by the type checker: which conversions are implicit (assignment,
// initialisation, return), how well an argument matches a parameter (overload resolution), and
// the result types of operators.
//
// Implicit conversions: a triple to another triple kind (point -> vector), int -> float, float or
// int -> triple or matrix. A literal 0 converts to the null closure (not as a call argument).
#pragma once

#include "ast/ast.h"

#include <optional>

namespace lobe::sema {

using ast::BaseType;
using ast::Type;

inline constexpr int kNoConversion = -1;

// Cost of converting a value of type `from` to `to` implicitly (0: identical), or
// kNoConversion. `zero_literal`: the value is the literal 0 (converts to a closure).
int conversion_cost(const Type& from, const Type& to, bool zero_literal = false);
inline bool assignable(const Type& to, const Type& from, bool zero_literal = false) {
  return conversion_cost(from, to, zero_literal) != kNoConversion;
}

// The operand type both sides of an arithmetic or comparison operator are converted to
// (int+float -> float, float*color -> color, point-vector -> vector, ...), or nullopt if the
// operator does not apply. Closures and structs are handled by the caller.
std::optional<Type> common_type(const Type& a, const Type& b);

// How well an argument of type `actual` matches a parameter (or a return type matches the
// type the context expects) of type `formal`: oslc 1.13's scores, measured by experiment
// (docs/language.md, "Calls and overload resolution"). A call's candidates are ranked by the
// sum over their arguments.
//   100 identical type (same struct; arrays of the same element type and length)
//    77 int -> float
//    44 T[N] -> T[]
//    32 point/vector/normal -> another of the three (also their arrays)
//    27 color <-> point/vector/normal
//    23 int or float -> triple or matrix; color[] <-> point/vector/normal[]
//     0 no match (float -> int, int[] -> float[], anything <-> string, closure or struct, ...)
inline constexpr int kExactMatch = 100;
int match_score(const Type& formal, const Type& actual);

// Order of preference between return types when argument scores and the expected type leave a
// tie (oslc's): float < int < color < vector < point < normal < matrix < string < closure
// < struct < void.
int return_rank(const Type& t);
inline constexpr int kStructRank = 9;

inline Type t_int() { return Type(BaseType::Int); }
inline Type t_float() { return Type(BaseType::Float); }
inline Type t_color() { return Type(BaseType::Color); }
inline Type t_point() { return Type(BaseType::Point); }
inline Type t_vector() { return Type(BaseType::Vector); }
inline Type t_normal() { return Type(BaseType::Normal); }
inline Type t_matrix() { return Type(BaseType::Matrix); }
inline Type t_string() { return Type(BaseType::String); }
inline Type t_void() { return Type(BaseType::Void); }
inline Type t_closure() { return Type(BaseType::Closure); }
inline Type t_error() { return Type(BaseType::Error); }

} // namespace lobe::sema
