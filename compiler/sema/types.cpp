// Implicit conversions, overload match scores and operator operand types.
#include "sema/types.h"

namespace lobe::sema {

int conversion_cost(const Type& from, const Type& to, bool zero_literal) {
  if (from.is_error() || to.is_error()) return 0; // already reported: don't cascade
  if (from.is_array() || to.is_array()) {
    if (from.base != to.base || from.strct != to.strct) return kNoConversion;
    // An unsized array (a parameter's: its length is the instance's) goes where any length does.
    if (to.arraylen == from.arraylen || to.arraylen < 0 || from.arraylen < 0) return 0;
    return kNoConversion;
  }
  if (from == to) return 0;
  if (to.is_triple() && from.is_triple()) return 1;
  if (to.is_float() && from.is_int()) return 2;
  if ((to.is_triple() || to.is_matrix()) && from.is_float()) return 3;
  if ((to.is_triple() || to.is_matrix()) && from.is_int()) return 4;
  if (to.is_closure() && zero_literal) return 1;
  return kNoConversion;
}

namespace {
bool is_spatial(BaseType b) {
  return b == BaseType::Point || b == BaseType::Vector || b == BaseType::Normal;
}
bool is_triple_base(BaseType b) { return b == BaseType::Color || is_spatial(b); }

// Two triple kinds (or arrays of them): 32 among point/vector/normal, else `color_score`.
int triple_score(BaseType formal, BaseType actual, int color_score) {
  return is_spatial(formal) && is_spatial(actual) ? 32 : color_score;
}
} // namespace

int match_score(const Type& formal, const Type& actual) {
  if (formal == actual) return kExactMatch;
  if (!formal.is_array() && !actual.is_array()) {
    if (formal.is_float() && actual.is_int()) return 77;
    if (formal.is_triple() && actual.is_triple()) return triple_score(formal.base, actual.base, 27);
    if ((formal.is_triple() || formal.is_matrix()) && actual.is_numeric()) return 23;
    return 0;
  }
  if (!formal.is_array() || !actual.is_array()) return 0;
  if ((formal.is_unsized_array() || actual.is_unsized_array()) &&
      formal.element() == actual.element())
    return 44;
  if (!formal.is_unsized_array() && formal.arraylen != actual.arraylen) return 0;
  if (is_triple_base(formal.base) && is_triple_base(actual.base))
    return triple_score(formal.base, actual.base, 23);
  return 0;
}

int return_rank(const Type& t) {
  switch (t.base) {
  case BaseType::Float:
    return 0;
  case BaseType::Int:
    return 1;
  case BaseType::Color:
    return 2;
  case BaseType::Vector:
    return 3;
  case BaseType::Point:
    return 4;
  case BaseType::Normal:
    return 5;
  case BaseType::Matrix:
    return 6;
  case BaseType::String:
    return 7;
  case BaseType::Closure:
    return 8;
  case BaseType::Struct:
    return kStructRank;
  default:
    return 10; // void (and error)
  }
}

std::optional<Type> common_type(const Type& a, const Type& b) {
  if (a.is_array() || b.is_array()) return std::nullopt;
  if (a.is_int() && b.is_int()) return t_int();
  if (a.is_numeric() && b.is_numeric()) return t_float();
  if (a.is_triple() && b.is_triple()) return a == b ? a : t_vector();
  if (a.is_triple() && b.is_numeric()) return a;
  if (b.is_triple() && a.is_numeric()) return b;
  if (a.is_matrix() && (b.is_matrix() || b.is_numeric())) return t_matrix();
  if (b.is_matrix() && a.is_numeric()) return t_matrix();
  if (a.is_string() && b.is_string()) return t_string();
  return std::nullopt;
}

} // namespace lobe::sema
