// matrix33.h: a 3x3 matrix (OSL's matrix33.h API). It is held as a 4x4 `matrix` whose
// translation row and column are zero (and m[3][3] is 1), so that every 4x4 operation gives the
// 3x3 result. Built into Lobe: `#include "matrix33.h"` finds this file when no file of that
// name is on the include path.
//
// As in OSL's header, the inequality overload is named `__operator__ne__`, which `!=` does not
// look for: `a != b` on two matrix33 is an error in OSL and in Lobe alike (call
// `__operator__ne__(a, b)`, or compare `a.m != b.m`).

#pragma once
#define MATRIX33_H

struct matrix33 {
  matrix m;
};

// 1 if m44 has no translation and no projection, so a matrix33 can hold it unchanged.
int isValidAs33(matrix m44) {
  return m44[0][3] == 0 && m44[1][3] == 0 && m44[2][3] == 0 && m44[3][0] == 0 &&
         m44[3][1] == 0 && m44[3][2] == 0 && m44[3][3] == 1;
}

matrix matrix33To44(matrix33 m33) { return m33.m; }

// The upper-left 3x3 of m44 (translation and projection dropped).
matrix33 matrix44To33(matrix m44) {
  matrix33 r;
  r.m = m44;
  for (int i = 0; i < 3; ++i) {
    r.m[i][3] = 0;
    r.m[3][i] = 0;
  }
  r.m[3][3] = 1;
  return r;
}

// The helper macro wraps a 4x4 result; it is removed at the end.
#define LOBE_M33_OF(expr)                                                                       \
  {                                                                                             \
    matrix33 r;                                                                                 \
    r.m = expr;                                                                                 \
    return r;                                                                                   \
  }

// ---- operators: unary minus; * and / over (int|float, matrix33), (matrix33, int|float) and
// (matrix33, matrix33), `/` multiplying by the inverse; == (and __operator__ne__, see above)
matrix33 __operator__neg__(matrix33 a) LOBE_M33_OF(-a.m)
matrix33 __operator__mul__(int a, matrix33 b) LOBE_M33_OF(a * b.m)
matrix33 __operator__mul__(float a, matrix33 b) LOBE_M33_OF(a * b.m)
matrix33 __operator__mul__(matrix33 a, int b) LOBE_M33_OF(a.m * b)
matrix33 __operator__mul__(matrix33 a, float b) LOBE_M33_OF(a.m * b)
matrix33 __operator__mul__(matrix33 a, matrix33 b) LOBE_M33_OF(a.m * b.m)
matrix33 __operator__div__(int a, matrix33 b) LOBE_M33_OF(a / b.m)
matrix33 __operator__div__(float a, matrix33 b) LOBE_M33_OF(a / b.m)
matrix33 __operator__div__(matrix33 a, int b) LOBE_M33_OF(a.m / b)
matrix33 __operator__div__(matrix33 a, float b) LOBE_M33_OF(a.m / b)
matrix33 __operator__div__(matrix33 a, matrix33 b) LOBE_M33_OF(a.m / b.m)

int __operator__eq__(matrix33 a, matrix33 b) { return a.m == b.m; }
int __operator__ne__(matrix33 a, matrix33 b) { return a.m != b.m; }

// ---- matrix functions and transforms (the 4x4 ones applied to the held matrix)
float determinant(matrix33 a) { return determinant(a.m); }
matrix33 transpose(matrix33 a) LOBE_M33_OF(transpose(a.m))
point transform(matrix33 a, point p) { return transform(a.m, p); }
vector transform(matrix33 a, vector v) { return transform(a.m, v); }
normal transform(matrix33 a, normal n) { return transform(a.m, n); }

#undef LOBE_M33_OF
