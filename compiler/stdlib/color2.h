// color2.h: one colour channel and an alpha, with the arithmetic and standard-library overloads
// of `color` (OSL's color2.h API: same struct, same functions, same per-channel arithmetic).
// Built into Lobe: `#include "color2.h"` finds this file when no file of that name is on the
// include path. Division by a scalar multiplies by its reciprocal, as OSL's header does, so
// results agree bit for bit.

#pragma once
#define COLOR2_H

struct color2 {
  float r;
  float a;
};

// The helper macros below expand one overload per line; they are removed at the end.
#define LOBE_C2(r_, a_) color2(r_, a_)
#define LOBE_C2_SPLAT(s) color2(s, s)

// ---- operators: unary minus; + - * / over (color2, color2), (color2, int|float),
// (int|float, color2); == and !=
color2 __operator__neg__(color2 a) { return LOBE_C2(-a.r, -a.a); }

#define LOBE_C2_ARITH(op, sym)                                                                  \
  color2 __operator__##op##__(color2 a, color2 b) { return LOBE_C2(a.r sym b.r, a.a sym b.a); } \
  color2 __operator__##op##__(int a, color2 b) { return LOBE_C2_SPLAT(a) sym b; }               \
  color2 __operator__##op##__(float a, color2 b) { return LOBE_C2_SPLAT(a) sym b; }
LOBE_C2_ARITH(add, +)
LOBE_C2_ARITH(sub, -)
LOBE_C2_ARITH(mul, *)
LOBE_C2_ARITH(div, /)
#undef LOBE_C2_ARITH

color2 __operator__add__(color2 a, int b) { return a + LOBE_C2_SPLAT(b); }
color2 __operator__add__(color2 a, float b) { return a + LOBE_C2_SPLAT(b); }
color2 __operator__sub__(color2 a, int b) { return a - LOBE_C2_SPLAT(b); }
color2 __operator__sub__(color2 a, float b) { return a - LOBE_C2_SPLAT(b); }
color2 __operator__mul__(color2 a, int b) { return a * LOBE_C2_SPLAT(b); }
color2 __operator__mul__(color2 a, float b) { return a * LOBE_C2_SPLAT(b); }
color2 __operator__div__(color2 a, int b) { return a * LOBE_C2_SPLAT(1.0 / float(b)); }
color2 __operator__div__(color2 a, float b) { return a * LOBE_C2_SPLAT(1.0 / b); }

int __operator__eq__(color2 a, color2 b) { return a.r == b.r && a.a == b.a; }
int __operator__neq__(color2 a, color2 b) { return a.r != b.r || a.a != b.a; }

// ---- standard-library functions, channel by channel
#define LOBE_C2_MAP1(f)                                                                         \
  color2 f(color2 a) { return LOBE_C2(f(a.r), f(a.a)); }
#define LOBE_C2_MAP2(f)                                                                         \
  color2 f(color2 a, color2 b) { return LOBE_C2(f(a.r, b.r), f(a.a, b.a)); }
LOBE_C2_MAP1(abs)
LOBE_C2_MAP1(ceil)
LOBE_C2_MAP1(floor)
LOBE_C2_MAP1(sqrt)
LOBE_C2_MAP1(exp)
LOBE_C2_MAP1(log)
LOBE_C2_MAP1(log2)
LOBE_C2_MAP1(sign)
LOBE_C2_MAP1(sin)
LOBE_C2_MAP1(cos)
LOBE_C2_MAP1(tan)
LOBE_C2_MAP1(asin)
LOBE_C2_MAP1(acos)
LOBE_C2_MAP2(max)
LOBE_C2_MAP2(min)
LOBE_C2_MAP2(fmod)
LOBE_C2_MAP2(pow)
LOBE_C2_MAP2(atan2)
#undef LOBE_C2_MAP1
#undef LOBE_C2_MAP2

color2 max(color2 a, float b) { return LOBE_C2(max(a.r, b), max(a.a, b)); }
color2 min(color2 a, float b) { return LOBE_C2(min(a.r, b), min(a.a, b)); }
color2 fmod(color2 a, int b) { return fmod(a, LOBE_C2_SPLAT(b)); }
color2 fmod(color2 a, float b) { return fmod(a, LOBE_C2_SPLAT(b)); }
color2 pow(color2 a, float b) { return pow(a, LOBE_C2_SPLAT(b)); }
color2 atan2(color2 a, float b) { return LOBE_C2(atan2(a.r, b), atan2(a.a, b)); }

color2 mix(color2 a, color2 b, float t) { return LOBE_C2(mix(a.r, b.r, t), mix(a.a, b.a, t)); }
color2 smoothstep(color2 e0, color2 e1, color2 x) {
  return LOBE_C2(smoothstep(e0.r, e1.r, x.r), smoothstep(e0.a, e1.a, x.a));
}
color2 smoothstep(float e0, float e1, color2 x) {
  return smoothstep(LOBE_C2_SPLAT(e0), LOBE_C2_SPLAT(e1), x);
}
color2 clamp(color2 x, color2 lo, color2 hi) {
  return LOBE_C2(clamp(x.r, lo.r, hi.r), clamp(x.a, lo.a, hi.a));
}
color2 clamp(color2 x, float lo, float hi) {
  return clamp(x, LOBE_C2_SPLAT(lo), LOBE_C2_SPLAT(hi));
}

#undef LOBE_C2
#undef LOBE_C2_SPLAT
