// Implicit conversion costs and operator operand types.
#include "sema/types.h"

namespace lobe::sema {

int conversion_cost(const Type& from, const Type& to, bool zero_literal) {
  if (from.is_error() || to.is_error()) return 0; // already reported: don't cascade
  if (from.is_array() || to.is_array()) {
    if (from.base != to.base || from.strct != to.strct) return kNoConversion;
    if (to.arraylen == from.arraylen || to.arraylen < 0) return 0;
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
