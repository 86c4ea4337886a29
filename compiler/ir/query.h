// A shader's interface as text, exactly as OSL 1.13's `oslinfo` prints it for the .oso oslc
// makes of the same source (docs/ir.md, "lobe info"). Verbose (`oslinfo -v`):
//
//   surface "plastic"
//   <tab><tab>metadata: string help = "A plastic"
//       "Kd" "float"
//   <tab><tab>Default value: 0.5
//   <tab><tab>metadata: float range[2] = 0 1
//       "Cs" "color"
//   <tab><tab>Default value: [ 1 1 1 ]
//       "Nn" "normal"
//   <tab><tab>Unknown default value
//       "st" "struct S"
//   <tab><tab>fields: {float a, color c}
//       "st.a" "float"
//   ...
//
// and plain (`oslinfo`): `float Kd  0.5`, `color Cs  [ 1 1 1 ]`, `normal Nn nodefault`,
// `string s "x" `, `struct S st fields: {float a, color c}`, no metadata. Parameters come in
// declaration order; a struct parameter is announced (with its fields) before its flattened
// fields, and so is a struct nested in it. Numbers print with %g, every array and aggregate in
// `[ ]`, strings C-escaped; closures are `pointer`. A default is unknown when it is computed
// (init ops), folded by Lobe where oslc computes it (Symbol::folded), or a closure's.
#pragma once

#include "ir/ir.h"

#include <string>

namespace lobe::ir {

struct DescribeOptions {
  bool verbose = true;
  std::string param; // only this parameter (or struct), without the shader line; "" for all
};

std::string describe(const Shader& shader, const DescribeOptions& options = {});

// The parameters as OSL's OSLQuery lists a layer's (testshade --oslquery): a line each,
// `<tab>[output ]type name` in declaration order, a struct (and a struct nested in it)
// announced as `unknown name` before its fields `type name.field`, a closure a `pointer`.
std::string oslquery_params(const Shader& shader);

// `s` in double quotes with the escapes of OIIO's Strutil::escape_chars (\\, \", \n, \t, \v,
// \b, \r, \f, \a; other bytes as they are), as oslinfo and OSL's group text print strings.
std::string c_quote(const std::string& s);

} // namespace lobe::ir
