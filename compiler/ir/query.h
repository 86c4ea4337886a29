// A shader's interface as text, in the style of `oslinfo -v` (OSL_FACTS.md "Query output"):
//
//   surface "plastic"
//       "Kd" "float"
//   <tab><tab>Default value: 0.5
//   <tab><tab>metadata: float min = 0
//       "Cs" "color"
//   <tab><tab>Default value: [ 1 1 1 ]
//       "Nn" "normal"
//   <tab><tab>Default value: (computed at run time)
//
// Parameters in declaration order (struct fields flattened as "s.a"); shader metadata after
// the first line. Printed by `lobe info`.
#pragma once

#include "ir/ir.h"

#include <string>

namespace lobe::ir {

std::string describe(const Shader& shader);

} // namespace lobe::ir
