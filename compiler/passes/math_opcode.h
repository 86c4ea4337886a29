// The math::Fn (runtime/mathlib/mathops.h) an IR opcode computes, for the constant folder and
// codegen, so both call the same function for the same op. Matched by name at compile time:
// mathops.h keeps OSL's names and knows nothing of the IR.
#pragma once

#include "ir/opcodes.h"
#include "mathops.h"

#include <array>
#include <string_view>

namespace lobe::passes {

namespace detail {
// Row i: the index in math::kFns of opcode i's `arity`-operand form, or -1.
template <int Arity> constexpr std::array<int8_t, ir::kOpcodeCount> math_fn_rows() {
  std::array<int8_t, ir::kOpcodeCount> rows{};
  for (size_t i = 0; i < ir::kOpcodeCount; ++i) {
    rows[i] = -1;
    for (size_t f = 0; f < std::size(math::kFns); ++f)
      if (math::kFns[f].arity == Arity &&
          std::string_view(math::kFns[f].name) == ir::kOpcodes[i].name)
        rows[i] = int8_t(f);
  }
  return rows;
}
inline constexpr auto kMathFn1 = math_fn_rows<1>();
inline constexpr auto kMathFn2 = math_fn_rows<2>();

// Every math::Fn is some opcode's.
constexpr bool every_fn_has_an_opcode() {
  for (size_t f = 0; f < std::size(math::kFns); ++f) {
    bool found = false;
    for (size_t i = 0; i < ir::kOpcodeCount; ++i)
      found |= size_t(math::kFns[f].arity == 1 ? kMathFn1[i] : kMathFn2[i]) == f;
    if (!found) return false;
  }
  return true;
}
static_assert(every_fn_has_an_opcode(), "a math::Fn names no IR opcode");
} // namespace detail

// The row of math::kFns that `op` with `arity` operands computes (log has a 1-operand row; its
// 2-operand form is log(x, base)), or null.
constexpr const math::FnInfo* math_fn(ir::Opcode op, int arity) {
  int8_t r = arity == 1   ? detail::kMathFn1[size_t(op)]
             : arity == 2 ? detail::kMathFn2[size_t(op)]
                          : -1;
  return r < 0 ? nullptr : &math::kFns[size_t(r)];
}

} // namespace lobe::passes
