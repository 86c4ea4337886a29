// A closure call in OSL syntax, parsed into a parameter block for `lobe brdf`:
//   conductor_bsdf(N, U, 0.2, 0.2, color(0.2, 0.9, 1.1), color(3.9, 2.4, 2.2), "ggx")
//   dielectric_bsdf(N, U, 1, 1, 0.1, 0.1, 1.5, "ggx", "energy_compensation", 0)
// Arguments: numbers, N (the local normal +z), U / T (the tangent +x), color(...) / vector(...)
// / normal(...) / point(...) with one or three numbers, "strings", then keyword pairs
// `"name", value`. Overloads are resolved by argument count and types; microfacet's 5-argument
// form and reflection(N) forward to the registry's forms as stdosl.h defines them. Errors are
// values carrying the byte offset they refer to (for a caret).
#pragma once

#include "closures.h"

#include <deque>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

namespace lobe::verify {

struct ParsedClosure {
  std::string key;
  closures::Params params;
  double eta_below = 1.0; // the float `ior`/`eta` of a transmissive closure, else 1
  std::shared_ptr<std::deque<std::string>> strings; // storage the block's strings point into
};

struct ExprError {
  size_t pos = 0;
  std::string message;
};

struct ExprResult {
  std::optional<ParsedClosure> closure;
  ExprError error; // meaningful when !closure
};

ExprResult parse_closure_expr(std::string_view text);

} // namespace lobe::verify
