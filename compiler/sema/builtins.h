// The builtin function table: every standard-library function OSL provides natively (those
// OSL writes in the language itself live in compiler/stdlib/stdosl.h instead), with all
// overloads. Closures are not here: they come from the closure registry.
//
// Built once by code (builtins.cpp), read-only afterwards. Overloads of one name are listed in
// oslc's order, which counts as newest first: it decides between builtins that tie on argument
// scores and return rank, and orders the candidates a diagnostic lists (sema/overload.h).
#pragma once

#include "ast/ast.h"

#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace lobe::sema {

struct BuiltinParam {
  ast::Type type;
  bool output = false; // written by the function (sincos, getmatrix, fresnel-like)
};

struct BuiltinSig {
  std::string name;
  ast::Type ret;
  std::vector<BuiltinParam> params;
  // Extra arguments after the fixed ones: any type (printf, format, error, warning, concat
  // takes strings), `"name", value` keyword pairs of known names (texture, trace), or
  // `"name", value` pairs of any name and type (point-cloud attributes).
  enum class Extra : uint8_t { None, Any, Keywords, Pairs } extra = Extra::None;
  bool pairs_written = false; // Pairs: the values are written (pointcloud_search)
  bool any_param = false;     // the single parameter accepts any type (isconnected, isconstant)
  bool array_param = false;   // the single parameter accepts any array (arraylength)

  std::string signature() const; // "float noise(point, float)"
};

class BuiltinTable {
public:
  BuiltinTable();
  // All overloads of `name` (empty span if none).
  std::span<const BuiltinSig> lookup(std::string_view name) const;
  size_t size() const { return sigs_.size(); }
  const std::vector<BuiltinSig>& all() const { return sigs_; }

private:
  std::vector<BuiltinSig> sigs_; // grouped by name
};

// The one table (immutable after construction on first use).
const BuiltinTable& builtins();

} // namespace lobe::sema
