// vector2.h: a 2-D vector with the arithmetic and standard-library overloads of `vector`
// (OSL's vector2.h API: same struct, same functions, same per-component arithmetic).
// Built into Lobe: `#include "vector2.h"` finds this file when no file of that name is on the
// include path. Division by a scalar multiplies by its reciprocal, as OSL's header does, so
// results (normalize included) agree bit for bit.

#pragma once
#define VECTOR2_H

struct vector2 {
  float x;
  float y;
};

// The helper macros below expand one overload per line; they are removed at the end.
#define LOBE_V2_SPLAT(s) vector2(s, s)

// ---- operators: unary minus; + - * / over (vector2, vector2), (vector2, int|float),
// (int|float, vector2); == and !=
vector2 __operator__neg__(vector2 a) { return vector2(-a.x, -a.y); }

#define LOBE_V2_ARITH(op, sym)                                                                  \
  vector2 __operator__##op##__(vector2 a, vector2 b) { return vector2(a.x sym b.x, a.y sym b.y); } \
  vector2 __operator__##op##__(int a, vector2 b) { return LOBE_V2_SPLAT(a) sym b; }             \
  vector2 __operator__##op##__(float a, vector2 b) { return LOBE_V2_SPLAT(a) sym b; }
LOBE_V2_ARITH(add, +)
LOBE_V2_ARITH(sub, -)
LOBE_V2_ARITH(mul, *)
LOBE_V2_ARITH(div, /)
#undef LOBE_V2_ARITH

vector2 __operator__add__(vector2 a, int b) { return a + LOBE_V2_SPLAT(b); }
vector2 __operator__add__(vector2 a, float b) { return a + LOBE_V2_SPLAT(b); }
vector2 __operator__sub__(vector2 a, int b) { return a - LOBE_V2_SPLAT(b); }
vector2 __operator__sub__(vector2 a, float b) { return a - LOBE_V2_SPLAT(b); }
vector2 __operator__mul__(vector2 a, int b) { return a * LOBE_V2_SPLAT(b); }
vector2 __operator__mul__(vector2 a, float b) { return a * LOBE_V2_SPLAT(b); }
vector2 __operator__div__(vector2 a, int b) { return a * LOBE_V2_SPLAT(1.0 / float(b)); }
vector2 __operator__div__(vector2 a, float b) { return a * LOBE_V2_SPLAT(1.0 / b); }

int __operator__eq__(vector2 a, vector2 b) { return a.x == b.x && a.y == b.y; }
int __operator__neq__(vector2 a, vector2 b) { return a.x != b.x || a.y != b.y; }

// ---- standard-library functions, component by component
#define LOBE_V2_MAP1(f)                                                                         \
  vector2 f(vector2 v) { return vector2(f(v.x), f(v.y)); }
#define LOBE_V2_MAP2(f)                                                                         \
  vector2 f(vector2 v, vector2 w) { return vector2(f(v.x, w.x), f(v.y, w.y)); }
LOBE_V2_MAP1(abs)
LOBE_V2_MAP1(ceil)
LOBE_V2_MAP1(floor)
LOBE_V2_MAP1(sqrt)
LOBE_V2_MAP1(exp)
LOBE_V2_MAP1(log)
LOBE_V2_MAP1(log2)
LOBE_V2_MAP1(sign)
LOBE_V2_MAP1(sin)
LOBE_V2_MAP1(cos)
LOBE_V2_MAP1(tan)
LOBE_V2_MAP1(asin)
LOBE_V2_MAP1(acos)
LOBE_V2_MAP2(max)
LOBE_V2_MAP2(min)
LOBE_V2_MAP2(fmod)
LOBE_V2_MAP2(pow)
LOBE_V2_MAP2(atan2)
#undef LOBE_V2_MAP1
#undef LOBE_V2_MAP2

vector2 max(vector2 v, float s) { return max(v, LOBE_V2_SPLAT(s)); }
vector2 min(vector2 v, float s) { return min(v, LOBE_V2_SPLAT(s)); }
vector2 fmod(vector2 v, float s) { return fmod(v, LOBE_V2_SPLAT(s)); }
vector2 pow(vector2 v, float s) { return pow(v, LOBE_V2_SPLAT(s)); }
vector2 atan2(vector2 v, float s) { return vector2(atan2(v.x, s), atan2(v.y, s)); }
// Floored modulo, a - b * floor(a / b), as mod() of `vector` is.
vector2 mod(vector2 a, vector2 b) { return a - b * floor(a / b); }

vector2 mix(vector2 a, vector2 b, float t) { return vector2(mix(a.x, b.x, t), mix(a.y, b.y, t)); }
vector2 smoothstep(vector2 e0, vector2 e1, vector2 v) {
  return vector2(smoothstep(e0.x, e1.x, v.x), smoothstep(e0.y, e1.y, v.y));
}
vector2 smoothstep(float e0, float e1, vector2 v) {
  return vector2(smoothstep(e0, e1, v.x), smoothstep(e0, e1, v.y));
}
vector2 clamp(vector2 v, vector2 lo, vector2 hi) {
  return vector2(clamp(v.x, lo.x, hi.x), clamp(v.y, lo.y, hi.y));
}
vector2 clamp(vector2 v, float lo, float hi) {
  return clamp(v, LOBE_V2_SPLAT(lo), LOBE_V2_SPLAT(hi));
}

// ---- geometry
float dot(vector2 a, vector2 b) { return a.x * b.x + a.y * b.y; }
float length(vector2 v) { return hypot(v.x, v.y); }
vector2 normalize(vector2 v) { return v / length(v); }

#undef LOBE_V2_SPLAT
