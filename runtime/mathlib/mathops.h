// The math builtins' semantics, one definition for the constant folder
// (compiler/passes/consteval.cpp) and the run-time shadeops (runtime/shadeops/ops_math.cpp).
//
// Three modes:
//   Fast     OIIO's fast-math functions (fastmath.h) with nothing fused: what OSL 1.13
//            computes for constant arguments — its optimiser (liboslexec is built for plain
//            x86-64) and LLVM's folding of its shadeops (llvm.fmuladd folds unfused) — and
//            what Lobe's folder and code generator compute for them.
//   FastJit  the same functions with every multiply-add fused: what OSL's JIT computes for
//            values known only while shading (its shadeops are clang bitcode compiled for the
//            host, which has FMA), a few ulp from Fast (hundreds near a zero of cos); Lobe's
//            shadeops compute it. As in OSL, a parameter's value is a constant when the
//            material is specialised (-O1, -O2) and a shading-time value at -O0, so math on
//            parameters can differ in the last bits between -O0 and -O2 (docs/language.md).
//   Exact    the C library's functions (libm), with the same domain rules
//            (CompileOptions::fast_math = false).
// (docs/language.md, "Math".)
// Domain rules, both modes: log/log2/log10 clamp x to [FLT_MIN, FLT_MAX] (NaN to FLT_MIN);
// asin/acos clamp to [-1, 1]; pow is OIIO's safe_pow (x^0 = 1, 0^y = 0, x^1 = x, a negative x
// needs an integer y else 0) with magnitudes at most FLT_MAX; sqrt(x < 0) = 0,
// inversesqrt(x <= 0) = 0; fmod(a, 0) = 0. Where OSL's folder and its JIT disagree, Lobe
// follows the folder: pow(-0, 1) = -0, max(-0, 0) = +0, fmod is the exact remainder.
//
// Derivatives are OSL's dual forms: a unary f has d f(x) = slope1(f, x) * dx, with the factor
// from the fused functions in Fast mode, as OSL's JIT computes it (derivatives are never
// constant-folded, so this breaks no folded/run-time agreement); atan2 and pow have their own
// partials (dual2). A value does not depend on whether derivatives are wanted, except pow's:
// with derivatives OSL computes u * u^(v-1) (pow_dual).
#pragma once

#include "fastmath.h"
#include "math_functions.h"

#include <string_view>

namespace lobe::math {

enum class MathMode : int32_t { Fast = 0, Exact = 1, FastJit = 2 };

// The builtins computed by formula, one row each in runtime/registry/math_functions.h. Run time:
// out-of-line shadeops lobe_math_<name> (value), lobe_math_<name>_slope (unary derivative
// factor), lobe_math_<name>_dual (binary partials).
enum class Fn : int32_t {
#define LOBE_MATH_FN_ENUM(x, e, name, arity, max, forms, doc) e,
  LOBE_MATH_FUNCTIONS(LOBE_MATH_FN_ENUM, _)
#undef LOBE_MATH_FN_ENUM
};

// One row per Fn, in enum order: the IR opcode it implements and its number of operands
// (compiler/passes/math_opcode.h maps opcodes to rows by this name).
struct FnInfo {
  Fn fn;
  const char* name;
  int arity;
};
inline constexpr FnInfo kFns[] = {
#define LOBE_MATH_FN_ROW(x, e, name, arity, max, forms, doc) {Fn::e, #name, arity},
    LOBE_MATH_FUNCTIONS(LOBE_MATH_FN_ROW, _)
#undef LOBE_MATH_FN_ROW
};

// ---- the two function libraries ---------------------------------------------------------------

// OIIO fast-math (kFused false: OSL's folder and Lobe's values; true: OSL's JIT).
template <bool F> struct FastLib {
  static constexpr bool kFused = F;
  static float sin(float x) { return fast_sin<F>(x); }
  static float cos(float x) { return fast_cos<F>(x); }
  static float tan(float x) { return fast_tan<F>(x); }
  static float asin(float x) { return fast_asin<F>(x); }
  static float acos(float x) { return fast_acos<F>(x); }
  static float atan(float x) { return fast_atan<F>(x); }
  static float atan2(float y, float x) { return fast_atan2<F>(y, x); }
  static float sinh(float x) { return fast_sinh<F>(x); }
  static float cosh(float x) { return fast_cosh<F>(x); }
  static float tanh(float x) { return fast_tanh<F>(x); }
  static float exp(float x) { return fast_exp<F>(x); }
  static float exp2(float x) { return fast_exp2<F>(x); }
  static float expm1(float x) { return fast_expm1<F>(x); }
  static float log(float x) { return fast_log<F>(x); }
  static float log2(float x) { return fast_log2<F>(x); }
  static float log10(float x) { return fast_log10<F>(x); }
  static float cbrt(float x) { return fast_cbrt<F>(x); }
  static float erf(float x) { return fast_erf<F>(x); }
  static float erfc(float x) { return fast_erfc<F>(x); }
  static float safe_pow(float x, float y) { return fast_safe_pow<F>(x, y); }
};

// libm with OIIO's safe_* domain rules (OSL built without fast math).
struct LibmLib {
  static constexpr bool kFused = false;
  static float sin(float x) { return std::sin(x); }
  static float cos(float x) { return std::cos(x); }
  static float tan(float x) { return std::tan(x); }
  static float asin(float x) { return x >= 1.0f ? kPi2 : x <= -1.0f ? -kPi2 : std::asin(x); }
  static float acos(float x) { return x >= 1.0f ? 0.0f : x <= -1.0f ? kPi : std::acos(x); }
  static float atan(float x) { return std::atan(x); }
  static float atan2(float y, float x) { return std::atan2(y, x); }
  static float sinh(float x) { return std::sinh(x); }
  static float cosh(float x) { return std::cosh(x); }
  static float tanh(float x) { return std::tanh(x); }
  static float exp(float x) { return std::exp(x); }
  static float exp2(float x) { return std::exp2(x); }
  static float expm1(float x) { return std::expm1(x); }
  static float log(float x) { return std::log(oiio_clamp(x, kFltMin, kFltMax)); }
  static float log2(float x) { return std::log2(oiio_clamp(x, kFltMin, kFltMax)); }
  static float log10(float x) { return std::log10(oiio_clamp(x, kFltMin, kFltMax)); }
  static float cbrt(float x) { return std::cbrt(x); }
  static float erf(float x) { return std::erf(x); }
  static float erfc(float x) { return std::erfc(x); }
  static float safe_pow(float x, float y) {
    if (y == 0) return 1.0f;
    if (x == 0) return 0.0f;
    if (y == 1.0f) return x;
    float sign = 1.0f;
    if (x < 0.0f && !integer_power_sign(y, sign)) return 0.0f;
    float p = std::pow(abs_bits(x), y);
    return sign * (p > kFltMax ? kFltMax : p);
  }
};

// ---- values -----------------------------------------------------------------------------------

// pow as OSL folds it: x^1 = x before the 0^y rule (pow(-0, 1) = -0; OSL's JIT gives +0).
template <class L> float pow(float x, float y) { return y == 1.0f ? x : L::safe_pow(x, y); }

// fmod as OSL folds it: the exact remainder (sign of a); fmod(a, 0) = 0; a NaN operand is
// returned as it is; other invalid cases (a infinite, b NaN-free) give +NaN. (OSL's JIT
// computes a - int(a/b)*b, which differs where a/b rounds to an integer or exceeds int32.)
inline float fmod(float a, float b) {
  if (b == 0.0f) return 0.0f;
  if (a != a) return a;
  if (b != b) return b;
  float r = std::fmod(a, b);
  return r != r ? std::numeric_limits<float>::quiet_NaN() : r;
}

template <class L> float apply1(Fn f, float x) {
  switch (f) {
  case Fn::Sin:
    return L::sin(x);
  case Fn::Cos:
    return L::cos(x);
  case Fn::Tan:
    return L::tan(x);
  case Fn::Asin:
    return L::asin(x);
  case Fn::Acos:
    return L::acos(x);
  case Fn::Atan:
    return L::atan(x);
  case Fn::Sinh:
    return L::sinh(x);
  case Fn::Cosh:
    return L::cosh(x);
  case Fn::Tanh:
    return L::tanh(x);
  case Fn::Exp:
    return L::exp(x);
  case Fn::Exp2:
    return L::exp2(x);
  case Fn::Expm1:
    return L::expm1(x);
  case Fn::Log:
    return L::log(x);
  case Fn::Log2:
    return L::log2(x);
  case Fn::Log10:
    return L::log10(x);
  case Fn::Logb:
    return fast_logb(x);
  case Fn::Cbrt:
    return L::cbrt(x);
  case Fn::Erf:
    return L::erf(x);
  case Fn::Erfc:
    return L::erfc(x);
  default:
    return 0.0f;
  }
}

template <class L> float apply2(Fn f, float a, float b) {
  switch (f) {
  case Fn::Atan2:
    return L::atan2(a, b);
  case Fn::Pow:
    return pow<L>(a, b);
  case Fn::Fmod:
    return fmod(a, b);
  default:
    return 0.0f;
  }
}

inline float value1(Fn f, MathMode m, float x) {
  return m == MathMode::Fast      ? apply1<FastLib<false>>(f, x)
         : m == MathMode::FastJit ? apply1<FastLib<true>>(f, x)
                                  : apply1<LibmLib>(f, x);
}
inline float value2(Fn f, MathMode m, float a, float b) {
  return m == MathMode::Fast      ? apply2<FastLib<false>>(f, a, b)
         : m == MathMode::FastJit ? apply2<FastLib<true>>(f, a, b)
                                  : apply2<LibmLib>(f, a, b);
}

// ---- derivatives ------------------------------------------------------------------------------

// d f(x)/dx as OSL's dual forms compute it (the partials are this times dx, dy).
template <class L> float slope_of(Fn f, float x) {
  constexpr bool F = L::kFused;
  switch (f) {
  case Fn::Sin:
    return L::cos(x);
  case Fn::Cos:
    return -L::sin(x);
  case Fn::Tan: {
    float c = L::cos(x);
    return 1.0f / (c * c);
  }
  case Fn::Asin:
    return abs_bits(x) < 1.0f ? 1.0f / std::sqrt(madd<F>(-x, x, 1.0f)) : 0.0f;
  case Fn::Acos:
    return abs_bits(x) < 1.0f ? -1.0f / std::sqrt(madd<F>(-x, x, 1.0f)) : 0.0f;
  case Fn::Atan:
    return 1.0f / madd<F>(x, x, 1.0f);
  case Fn::Sinh:
    return L::cosh(x);
  case Fn::Cosh:
    return L::sinh(x);
  case Fn::Tanh: {
    float c = L::cosh(x);
    return 1.0f / (c * c);
  }
  case Fn::Exp:
  case Fn::Expm1:
    return L::exp(x);
  case Fn::Exp2:
    return L::exp2(x) * kLn2;
  // 0 where the argument is clamped (x < FLT_MIN), so derivatives stay finite
  case Fn::Log:
    return x < kFltMin ? 0.0f : 1.0f / x;
  case Fn::Log2:
  case Fn::Log10: {
    float xl = x * (f == Fn::Log2 ? kLn2 : kLn10);
    return xl < kFltMin ? 0.0f : 1.0f / xl;
  }
  case Fn::Cbrt: {
    if (x == 0.0f) return 0.0f;
    float c = L::cbrt(x);
    return 1.0f / ((3.0f * c) * c);
  }
  case Fn::Erf:
    return L::exp(-x * x) * kTwoInvSqrtPi;
  case Fn::Erfc:
    return L::exp(-x * x) * -kTwoInvSqrtPi;
  default:
    return 0.0f; // logb: piecewise constant
  }
}

inline float slope1(Fn f, MathMode m, float x) {
  return m != MathMode::Exact ? slope_of<FastLib<true>>(f, x) : slope_of<LibmLib>(f, x);
}

struct Dual {
  float v = 0, dx = 0, dy = 0;
};

// x86 SSE's NaN rule, for the partials where two NaNs can meet: the first NaN operand
// (quieted) wins. (C++ may swap the operands of a commutative + or *.)
inline float quiet(float x) { return from_bits(bits_of(x) | 0x00400000u); }
inline float sse_mul(float a, float b) { return a != a ? quiet(a) : b != b ? quiet(b) : a * b; }
inline float sse_add(float a, float b) { return a != a ? quiet(a) : b != b ? quiet(b) : a + b; }

// atan2(y, x). OSL's partials are d = (-x dy + y dx) / (x^2 + y^2), the negative of the true
// derivative; reproduced as it is (0 where x = y = 0).
template <class L> Dual atan2_dual(const Dual& y, const Dual& x, float value) {
  constexpr bool F = L::kFused;
  float denom = (x.v == 0 && y.v == 0) ? 0.0f : 1.0f / madd<F>(x.v, x.v, y.v * y.v);
  float dfdy = sse_mul(denom, -x.v), dfdx = y.v * denom;
  return {value, madd<F>(dfdy, y.dx, dfdx * x.dx), madd<F>(dfdy, y.dy, dfdx * x.dy)};
}

// u^v with OSL's dual partials, evaluated without fusion even by OSL's JIT (an out-of-line
// function): d = v u^(v-1) du + u^v log(u) dv, with u^v taken as u * u^(v-1) and log(u) as 0
// for u <= 0. The value is that u * u^(v-1) as well, as OSL's: pow(-2, 0.5) with derivatives is
// -0, pow(2, 0.5) 1.41420817 where the plain pow gives 1.41421187 (testshade -O0, a lockgeom=0
// base).
template <class L> Dual pow_dual(const Dual& u, const Dual& v) {
  float p = pow<L>(u.v, v.v - 1.0f);
  float pu = u.v * p;
  float logu = u.v > 0 ? L::log(u.v) : 0.0f;
  float dfdu = v.v * p, dfdv = pu * logu;
  return {pu, sse_add(sse_mul(dfdu, u.dx), sse_mul(dfdv, v.dx)),
          sse_add(sse_mul(dfdu, u.dy), sse_mul(dfdv, v.dy))};
}

// A binary function with its partials; the value is value2's except for pow (pow_dual). fmod
// passes a's partials on.
inline Dual dual2(Fn f, MathMode m, const Dual& a, const Dual& b) {
  bool fast = m != MathMode::Exact;
  if (f == Fn::Pow) return fast ? pow_dual<FastLib<false>>(a, b) : pow_dual<LibmLib>(a, b);
  float value = value2(f, m, a.v, b.v);
  switch (f) {
  case Fn::Atan2:
    return fast ? atan2_dual<FastLib<true>>(a, b, value) : atan2_dual<LibmLib>(a, b, value);
  default:
    return {value, a.dx, a.dy};
  }
}

// ---- the simple builtins and operators (inline LLVM IR at run time, the same rules) ----------

inline float sqrt(float x) { return x >= 0.0f ? std::sqrt(x) : 0.0f; } // NaN -> 0
inline float inversesqrt(float x) { return x > 0.0f ? 1.0f / std::sqrt(x) : 0.0f; }
inline float sign(float x) { return x < 0.0f ? -1.0f : x == 0.0f ? 0.0f : 1.0f; } // NaN -> 1
inline float step(float edge, float x) { return x < edge ? 0.0f : 1.0f; }         // NaN -> 1
inline float min(float a, float b) { return b < a ? b : a; }
// OSL's folder; its JIT tests b >= a, so max(0, -0) is -0 there.
inline float max(float a, float b) { return b > a ? b : a; }
inline float smoothstep(float e0, float e1, float x) {
  if (x < e0) return 0.0f;
  if (x >= e1) return 1.0f;
  float t = (x - e0) / (e1 - e0);
  float t2 = t * t;
  return t2 * (3.0f - 2.0f * t);
}
// Float division: 0 for a zero divisor, else IEEE (OSL's folder, and its JIT for a constant
// divisor; for a varying one the JIT also gives 0 for an infinite or NaN quotient).
inline float div(float a, float b) { return b == 0.0f ? 0.0f : a / b; }
// degrees/radians multiply by constants computed in float, as stdosl.h does.
constexpr float kDegreesPerRadian = 180.0f / kPi; // 57.2957764
constexpr float kRadiansPerDegree = kPi / 180.0f; // 0.0174532924

// Comparisons, as OSL's JIT computes them: unordered, so a NaN operand makes every one true
// (also ==); triples compare all components with == and any with !=.
inline bool lt(float a, float b) { return !(a >= b); }
inline bool le(float a, float b) { return !(a > b); }
inline bool gt(float a, float b) { return !(a <= b); }
inline bool ge(float a, float b) { return !(a < b); }
inline bool eq(float a, float b) { return !(a < b || a > b); }
inline bool ne(float a, float b) { return !(a == b); }

} // namespace lobe::math
