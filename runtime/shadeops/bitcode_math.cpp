// The math shadeops (ops_math.cpp) as C-ABI definitions by name, for the shadeop bitcode only
// (lobe_shadeops.bc, runtime/jit/shadeop_bitcode.h): ops_math.cpp registers template
// instances under names built at run time, which bitcode cannot carry, so the same one-line
// wrappers of runtime/mathlib/mathops.h are spelled out here per math::Fn. The names and
// signatures are the table's (shadeops.h, math_shadeop); the JIT links a function from the
// bitcode only where its type matches the shader's declaration.
#include "hashword.h"
#include "mathops.h"
#include "matrix44.h"

#include <cstdint>

using lobe::math::Dual;
using lobe::math::Fn;
using lobe::math::MathMode;

#define LOBE_UNARY(name, F)                                                                        \
  float lobe_math_##name(float x, int32_t mode) {                                                  \
    return lobe::math::value1(Fn::F, MathMode(mode), x);                                           \
  }                                                                                                \
  float lobe_math_##name##_slope(float x, int32_t mode) {                                          \
    return lobe::math::slope1(Fn::F, MathMode(mode), x);                                           \
  }
#define LOBE_BINARY(name, F)                                                                       \
  float lobe_math_##name(float a, float b, int32_t mode) {                                         \
    return lobe::math::value2(Fn::F, MathMode(mode), a, b);                                        \
  }                                                                                                \
  void lobe_math_##name##_dual(float* out, const float* a, const float* b, int32_t mode) {         \
    Dual r = lobe::math::dual2(Fn::F, MathMode(mode), {a[0], a[1], a[2]}, {b[0], b[1], b[2]});     \
    out[0] = r.v, out[1] = r.dx, out[2] = r.dy;                                                    \
  }

extern "C" {
// One pair of shadeops per row of runtime/registry/math_functions.h, by its arity.
#define LOBE_MATH_ROW1(name, F) LOBE_UNARY(name, F)
#define LOBE_MATH_ROW2(name, F) LOBE_BINARY(name, F)
#define LOBE_MATH_BITCODE_ROW(x, e, name, arity, max, forms, doc) LOBE_MATH_ROW##arity(name, e)
LOBE_MATH_FUNCTIONS(LOBE_MATH_BITCODE_ROW, _)
#undef LOBE_MATH_BITCODE_ROW

// hash() of numbers (ops_math.cpp's lobe_hash).
int32_t lobe_hash(const uint32_t* words, int32_t n) { return lobe::math::osl_hash(words, n); }

// The pure matrix ops (ops_matrix.cpp's, same names and signatures).
void lobe_mat_mul(float* dst, const float* a, const float* b) { lobe::math::mat_mul(dst, a, b); }
void lobe_mat_inverse(float* dst, const float* src) { lobe::math::mat_invert(dst, src); }
void lobe_mat_div(float* dst, const float* a, const float* b) { lobe::math::mat_div(dst, a, b); }
void lobe_mat_transpose(float* dst, const float* m) { lobe::math::mat_transpose(dst, m); }
float lobe_mat_det(const float* m) { return lobe::math::mat_det(m); }
void lobe_transform(float* dst, const float* m, const float* p, int32_t kind) {
  lobe::math::mat_transform(dst, m, p, kind);
}
}
