// color4.h: a colour and an alpha, with the arithmetic and standard-library overloads of
// `color` (OSL's color4.h API: same struct, same functions, same per-channel arithmetic).
// Built into Lobe: `#include "color4.h"` finds this file when no file of that name is on the
// include path. The colour part works through `color` operations, the alpha through `float`
// ones; division by a scalar multiplies by its reciprocal, as OSL's header does.

#pragma once
#define COLOR4_H

struct color4 {
  color rgb;
  float a;
};

// The helper macros below expand one overload per line; they are removed at the end.
#define LOBE_C4_SPLAT(s) color4(color(s), s)

// ---- operators: unary minus; + - * / over (color4, color4), (color4, int|float),
// (int|float, color4); == and !=
color4 __operator__neg__(color4 a) { return color4(-a.rgb, -a.a); }

#define LOBE_C4_ARITH(op, sym)                                                                  \
  color4 __operator__##op##__(color4 a, color4 b) {                                             \
    return color4(a.rgb sym b.rgb, a.a sym b.a);                                                \
  }                                                                                             \
  color4 __operator__##op##__(float a, color4 b) { return LOBE_C4_SPLAT(a) sym b; }
LOBE_C4_ARITH(add, +)
LOBE_C4_ARITH(sub, -)
LOBE_C4_ARITH(mul, *)
LOBE_C4_ARITH(div, /)
#undef LOBE_C4_ARITH

color4 __operator__add__(int a, color4 b) { return LOBE_C4_SPLAT(a) + b; }
color4 __operator__sub__(int a, color4 b) { return LOBE_C4_SPLAT(a) - b; }
color4 __operator__mul__(int a, color4 b) { return LOBE_C4_SPLAT(a) * b; }
// OSL's header spells this one `__operator_div__`, so `int / color4` takes the float overload
// (the same value); Lobe keeps OSL's names so that shaders declaring the missing overload
// themselves still compile.
color4 __operator_div__(int a, color4 b) { return LOBE_C4_SPLAT(a) / b; }

color4 __operator__add__(color4 a, int b) { return a + LOBE_C4_SPLAT(b); }
color4 __operator__add__(color4 a, float b) { return a + LOBE_C4_SPLAT(b); }
color4 __operator__sub__(color4 a, int b) { return a - LOBE_C4_SPLAT(b); }
color4 __operator__sub__(color4 a, float b) { return a - LOBE_C4_SPLAT(b); }
color4 __operator__mul__(color4 a, int b) { return a * LOBE_C4_SPLAT(b); }
color4 __operator__mul__(color4 a, float b) { return a * LOBE_C4_SPLAT(b); }
color4 __operator__div__(color4 a, int b) { return a * LOBE_C4_SPLAT(1.0 / float(b)); }
color4 __operator__div__(color4 a, float b) { return a * LOBE_C4_SPLAT(1.0 / b); }

int __operator__eq__(color4 a, color4 b) { return a.rgb == b.rgb && a.a == b.a; }
int __operator__neq__(color4 a, color4 b) { return a.rgb != b.rgb || a.a != b.a; }

// ---- standard-library functions: the colour's overload on rgb, the float one on alpha
#define LOBE_C4_MAP1(f)                                                                         \
  color4 f(color4 x) { return color4(f(x.rgb), f(x.a)); }
#define LOBE_C4_MAP2(f)                                                                         \
  color4 f(color4 x, color4 y) { return color4(f(x.rgb, y.rgb), f(x.a, y.a)); }
LOBE_C4_MAP1(abs)
LOBE_C4_MAP1(ceil)
LOBE_C4_MAP1(floor)
LOBE_C4_MAP1(sqrt)
LOBE_C4_MAP1(exp)
LOBE_C4_MAP1(log)
LOBE_C4_MAP1(log2)
LOBE_C4_MAP1(sign)
LOBE_C4_MAP1(sin)
LOBE_C4_MAP1(cos)
LOBE_C4_MAP1(tan)
LOBE_C4_MAP1(asin)
LOBE_C4_MAP1(acos)
LOBE_C4_MAP2(max)
LOBE_C4_MAP2(min)
LOBE_C4_MAP2(fmod)
LOBE_C4_MAP2(pow)
LOBE_C4_MAP2(atan2)
#undef LOBE_C4_MAP1
#undef LOBE_C4_MAP2

color4 max(color4 x, float y) { return color4(max(x.rgb, y), max(x.a, y)); }
color4 min(color4 x, float y) { return color4(min(x.rgb, y), min(x.a, y)); }
color4 fmod(color4 x, int y) { return fmod(x, LOBE_C4_SPLAT(y)); }
color4 fmod(color4 x, float y) { return fmod(x, LOBE_C4_SPLAT(y)); }
color4 pow(color4 x, float y) { return pow(x, LOBE_C4_SPLAT(y)); }
color4 atan2(color4 x, float y) { return color4(atan2(x.rgb, y), atan2(x.a, y)); }

color4 mix(color4 x, color4 y, float t) { return color4(mix(x.rgb, y.rgb, t), mix(x.a, y.a, t)); }
color4 smoothstep(color4 e0, color4 e1, color4 x) {
  return color4(smoothstep(e0.rgb, e1.rgb, x.rgb), smoothstep(e0.a, e1.a, x.a));
}
color4 smoothstep(float e0, float e1, color4 x) {
  return smoothstep(LOBE_C4_SPLAT(e0), LOBE_C4_SPLAT(e1), x);
}
color4 clamp(color4 x, color4 lo, color4 hi) {
  return color4(clamp(x.rgb, lo.rgb, hi.rgb), clamp(x.a, lo.a, hi.a));
}
color4 clamp(color4 x, float lo, float hi) {
  return clamp(x, LOBE_C4_SPLAT(lo), LOBE_C4_SPLAT(hi));
}

// Colour-space conversion of the colour part; alpha passes through.
color4 transformc(string from, string to, color4 x) {
  return color4(transformc(from, to, x.rgb), x.a);
}

#undef LOBE_C4_SPLAT
