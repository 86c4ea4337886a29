// Type rules shared by the type checker: which conversions are implicit and what they cost
// (overload resolution picks the cheapest), and the result types of operators.
//
// Implicit conversions, cheapest first (OSL's order: exact, then int->float and float->triple
// coercion): a triple to another triple kind (point -> vector), int -> float, float -> triple
// or matrix, int -> triple or matrix. A literal 0 converts to the null closure.
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
