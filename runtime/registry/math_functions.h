// Math functions computed by formula: each declared once, here.
//
// LOBE_MATH_FUNCTIONS(M, x) lists one M(x, Enum, name, arity, max_operands, forms, doc) per
// function: `arity` arguments of the formula (1 or 2), `max_operands` the IR op's most operands
// (the result included; log's 2-argument form makes it 3), `forms` the type checker's
// signatures — Generic: float and every triple, each argument of the result's type; Float:
// float only. From the row: math::Fn and math::kFns (runtime/mathlib/mathops.h), the opcode
// (ir::Opcode::Enum, kArith: derivatives by the chain rule), the signatures
// (compiler/sema/builtins.cpp; extra overloads such as pow(color, float) are listed there),
// the constant folder's case (compiler/passes/consteval.cpp), the code generator's row
// (runtime/codegen/ops_math.cpp) and the shadeops lobe_math_<name>[_slope|_dual], native and in
// bitcode (runtime/shadeops/ops_math.cpp, bitcode_math.cpp), and its line in docs/language.md
// (`closure_docs --update docs/language.md`, checked by a test). Adding one is its row plus its
// formulas in mathops.h: the value (apply1/apply2, per math library) and the derivative
// (slope_of, or dual2 for two arguments).
#pragma once

// clang-format off
#define LOBE_MATH_FUNCTIONS(M, x) \
  M(x, Sin,   sin,   1, 2, Generic, "a = sin b") \
  M(x, Cos,   cos,   1, 2, Generic, "a = cos b") \
  M(x, Tan,   tan,   1, 2, Generic, "a = tan b") \
  M(x, Asin,  asin,  1, 2, Generic, "a = asin b") \
  M(x, Acos,  acos,  1, 2, Generic, "a = acos b") \
  M(x, Atan,  atan,  1, 2, Generic, "a = atan b") \
  M(x, Sinh,  sinh,  1, 2, Generic, "a = sinh b") \
  M(x, Cosh,  cosh,  1, 2, Generic, "a = cosh b") \
  M(x, Tanh,  tanh,  1, 2, Generic, "a = tanh b") \
  M(x, Exp,   exp,   1, 2, Generic, "a = e^b") \
  M(x, Exp2,  exp2,  1, 2, Generic, "a = 2^b") \
  M(x, Expm1, expm1, 1, 2, Generic, "a = e^b - 1") \
  M(x, Log,   log,   1, 3, Generic, "a = ln b, or log base c") \
  M(x, Log2,  log2,  1, 2, Generic, "a = log2 b") \
  M(x, Log10, log10, 1, 2, Generic, "a = log10 b") \
  M(x, Logb,  logb,  1, 2, Generic, "a = exponent of b") \
  M(x, Cbrt,  cbrt,  1, 2, Generic, "a = cbrt b") \
  M(x, Erf,   erf,   1, 2, Float,   "a = erf b") \
  M(x, Erfc,  erfc,  1, 2, Float,   "a = erfc b") \
  M(x, Atan2, atan2, 2, 3, Generic, "a = atan2(b, c)") \
  M(x, Pow,   pow,   2, 3, Generic, "a = pow(b, c); c float or same type as b") \
  M(x, Fmod,  fmod,  2, 3, Generic, "a = fmod(b, c), 0 where c == 0")
// clang-format on
