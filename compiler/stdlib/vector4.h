// vector4.h: a 4-D (homogeneous) vector with the arithmetic and standard-library overloads of
// `vector`, plus transforms by a matrix (OSL's vector4.h API: same struct, same functions, same
// per-component arithmetic). Built into Lobe: `#include "vector4.h"` finds this file when no
// file of that name is on the include path. Division by a scalar multiplies by its
// reciprocal, as OSL's header does, so results (normalize included) agree bit for bit.

#pragma once
#define VECTOR4_H

struct vector4 {
  float x;
  float y;
  float z;
  float w;
};

// The helper macros below expand one overload per line; they are removed at the end.
#define LOBE_V4_SPLAT(s) vector4(s, s, s, s)

// ---- operators: unary minus; + - * / over (vector4, vector4), (vector4, int|float),
// (int|float, vector4); == and !=
vector4 __operator__neg__(vector4 a) { return vector4(-a.x, -a.y, -a.z, -a.w); }

#define LOBE_V4_ARITH(op, sym)                                                                  \
  vector4 __operator__##op##__(vector4 a, vector4 b) {                                          \
    return vector4(a.x sym b.x, a.y sym b.y, a.z sym b.z, a.w sym b.w);                         \
  }                                                                                             \
  vector4 __operator__##op##__(int a, vector4 b) { return LOBE_V4_SPLAT(a) sym b; }             \
  vector4 __operator__##op##__(float a, vector4 b) { return LOBE_V4_SPLAT(a) sym b; }
LOBE_V4_ARITH(add, +)
LOBE_V4_ARITH(sub, -)
LOBE_V4_ARITH(mul, *)
LOBE_V4_ARITH(div, /)
#undef LOBE_V4_ARITH

vector4 __operator__add__(vector4 a, int b) { return a + LOBE_V4_SPLAT(b); }
vector4 __operator__add__(vector4 a, float b) { return a + LOBE_V4_SPLAT(b); }
vector4 __operator__sub__(vector4 a, int b) { return a - LOBE_V4_SPLAT(b); }
vector4 __operator__sub__(vector4 a, float b) { return a - LOBE_V4_SPLAT(b); }
vector4 __operator__mul__(vector4 a, int b) { return a * LOBE_V4_SPLAT(b); }
vector4 __operator__mul__(vector4 a, float b) { return a * LOBE_V4_SPLAT(b); }
vector4 __operator__div__(vector4 a, int b) { return a * LOBE_V4_SPLAT(1.0 / float(b)); }
vector4 __operator__div__(vector4 a, float b) { return a * LOBE_V4_SPLAT(1.0 / b); }

int __operator__eq__(vector4 a, vector4 b) {
  return a.x == b.x && a.y == b.y && a.z == b.z && a.w == b.w;
}
int __operator__neq__(vector4 a, vector4 b) {
  return a.x != b.x || a.y != b.y || a.z != b.z || a.w != b.w;
}

// ---- standard-library functions, component by component
#define LOBE_V4_MAP1(f)                                                                         \
  vector4 f(vector4 v) { return vector4(f(v.x), f(v.y), f(v.z), f(v.w)); }
#define LOBE_V4_MAP2(f)                                                                         \
  vector4 f(vector4 v, vector4 u) {                                                             \
    return vector4(f(v.x, u.x), f(v.y, u.y), f(v.z, u.z), f(v.w, u.w));                         \
  }
#define LOBE_V4_MAP2F(f)                                                                        \
  vector4 f(vector4 v, float s) { return vector4(f(v.x, s), f(v.y, s), f(v.z, s), f(v.w, s)); }
LOBE_V4_MAP1(abs)
LOBE_V4_MAP1(ceil)
LOBE_V4_MAP1(floor)
LOBE_V4_MAP1(sqrt)
LOBE_V4_MAP1(exp)
LOBE_V4_MAP1(log)
LOBE_V4_MAP1(log2)
LOBE_V4_MAP1(sign)
LOBE_V4_MAP1(sin)
LOBE_V4_MAP1(cos)
LOBE_V4_MAP1(tan)
LOBE_V4_MAP1(asin)
LOBE_V4_MAP1(acos)
LOBE_V4_MAP2(max)
LOBE_V4_MAP2(min)
LOBE_V4_MAP2(fmod)
LOBE_V4_MAP2(pow)
LOBE_V4_MAP2(atan2)
LOBE_V4_MAP2F(max)
LOBE_V4_MAP2F(min)
LOBE_V4_MAP2F(fmod)
LOBE_V4_MAP2F(pow)
LOBE_V4_MAP2F(atan2)
#undef LOBE_V4_MAP1
#undef LOBE_V4_MAP2
#undef LOBE_V4_MAP2F

vector4 mix(vector4 a, vector4 b, float t) {
  return vector4(mix(a.x, b.x, t), mix(a.y, b.y, t), mix(a.z, b.z, t), mix(a.w, b.w, t));
}
vector4 smoothstep(vector4 e0, vector4 e1, vector4 v) {
  return vector4(smoothstep(e0.x, e1.x, v.x), smoothstep(e0.y, e1.y, v.y),
                 smoothstep(e0.z, e1.z, v.z), smoothstep(e0.w, e1.w, v.w));
}
vector4 smoothstep(float e0, float e1, vector4 v) {
  return vector4(smoothstep(e0, e1, v.x), smoothstep(e0, e1, v.y), smoothstep(e0, e1, v.z),
                 smoothstep(e0, e1, v.w));
}
vector4 clamp(vector4 v, vector4 lo, vector4 hi) {
  return vector4(clamp(v.x, lo.x, hi.x), clamp(v.y, lo.y, hi.y), clamp(v.z, lo.z, hi.z),
                 clamp(v.w, lo.w, hi.w));
}
vector4 clamp(vector4 v, float lo, float hi) {
  return vector4(clamp(v.x, lo, hi), clamp(v.y, lo, hi), clamp(v.z, lo, hi), clamp(v.w, lo, hi));
}

// ---- geometry
float dot(vector4 a, vector4 b) { return a.x * b.x + a.y * b.y + a.z * b.z + a.w * b.w; }
float length(vector4 v) { return sqrt(v.x * v.x + v.y * v.y + v.z * v.z + v.w * v.w); }
vector4 normalize(vector4 v) { return v / length(v); }

// The 3-D point a homogeneous vector stands for: (x, y, z) / w.
vector vec4ToVec3(vector4 v) { return vector(v.x, v.y, v.z) / v.w; }

// v as a row vector times M (OSL's convention: points transform as p * M).
vector4 transform(matrix M, vector4 v) {
  return vector4(M[0][0] * v.x + M[1][0] * v.y + M[2][0] * v.z + M[3][0] * v.w,
                 M[0][1] * v.x + M[1][1] * v.y + M[2][1] * v.z + M[3][1] * v.w,
                 M[0][2] * v.x + M[1][2] * v.y + M[2][2] * v.z + M[3][2] * v.w,
                 M[0][3] * v.x + M[1][3] * v.y + M[2][3] * v.z + M[3][3] * v.w);
}
vector4 transform(string from, string to, vector4 v) { return transform(matrix(from, to), v); }

#undef LOBE_V4_SPLAT
