// spline() and splineinverse(): OSL's cubic bases over a knot vector. With step s and n knots,
// there are (n - 4) / s + 1 segments; x in [0,1] (clamped) picks segment k and the four knots
// starting at k*s, weighted by the basis matrix (rows: x^3, x^2, x, 1). "linear" interpolates
// knots[k+1]..knots[k+2]; "constant" returns knots[k+1]. Unknown bases behave as catmull-rom.
#include "shadeop_decls.h"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace {

struct Basis {
  const char* name;
  int step;
  float m[4][4];
};

const Basis kBases[] = {
    {"catmull-rom",
     1,
     {{-0.5f, 1.5f, -1.5f, 0.5f}, {1, -2.5f, 2, -0.5f}, {-0.5f, 0, 0.5f, 0}, {0, 1, 0, 0}}},
    {"bezier", 3, {{-1, 3, -3, 1}, {3, -6, 3, 0}, {-3, 3, 0, 0}, {1, 0, 0, 0}}},
    {"bspline",
     1,
     {{-1 / 6.f, 3 / 6.f, -3 / 6.f, 1 / 6.f},
      {3 / 6.f, -6 / 6.f, 3 / 6.f, 0},
      {-3 / 6.f, 0, 3 / 6.f, 0},
      {1 / 6.f, 4 / 6.f, 1 / 6.f, 0}}},
    {"hermite", 2, {{2, 1, -2, 1}, {-3, -2, 3, -1}, {0, 1, 0, 0}, {1, 0, 0, 0}}},
    {"linear", 1, {{0, 0, 0, 0}, {0, 0, 0, 0}, {0, -1, 1, 0}, {0, 1, 0, 0}}},
    {"constant", 1, {{0, 0, 0, 0}, {0, 0, 0, 0}, {0, 0, 0, 0}, {0, 1, 0, 0}}},
};

const Basis& find_basis(const char* name) {
  for (const Basis& b : kBases)
    if (!std::strcmp(name, b.name)) return b;
  return kBases[0];
}

// Value and d/dx of one component of the spline.
void eval(const Basis& b, float x, const float* knots, int nknots, int comps, int c, float& v,
          float& dv) {
  v = dv = 0;
  if (nknots < 4) return;
  x = std::clamp(x, 0.0f, 1.0f);
  int nsegs = (nknots - 4) / b.step + 1;
  float xs = x * float(nsegs);
  int seg = std::min(int(std::floor(xs)), nsegs - 1);
  float t = xs - float(seg);
  const float* p = knots + size_t(seg * b.step) * size_t(comps) + c;
  if (!std::strcmp(b.name, "constant")) {
    v = p[comps];
    return;
  }
  for (int i = 0; i < 4; ++i) {
    float w = ((b.m[0][i] * t + b.m[1][i]) * t + b.m[2][i]) * t + b.m[3][i];
    float dw = (3 * b.m[0][i] * t + 2 * b.m[1][i]) * t + b.m[2][i];
    v += w * p[i * comps];
    dv += dw * float(nsegs) * p[i * comps];
  }
}

} // namespace

extern "C" {

// out[comps] = spline(basis, x, knots[nknots][comps]); dout[comps] = d out / dx (may be null).
void lobe_spline(const char* basis, float x, const float* knots, int nknots, int comps, float* out,
                 float* dout) {
  const Basis& b = find_basis(basis);
  for (int c = 0; c < comps; ++c) {
    float v, dv;
    eval(b, x, knots, nknots, comps, c, v, dv);
    out[c] = v;
    if (dout) dout[c] = (x > 0 && x < 1) ? dv : 0;
  }
}

// The x in [0,1] with spline(x) = y for a monotonic float spline (bisection).
float lobe_splineinverse(const char* basis, float y, const float* knots, int nknots) {
  const Basis& b = find_basis(basis);
  float v0, v1, d;
  eval(b, 0, knots, nknots, 1, 0, v0, d);
  eval(b, 1, knots, nknots, 1, 0, v1, d);
  bool increasing = v1 >= v0;
  if (increasing ? y <= v0 : y >= v0) return 0;
  if (increasing ? y >= v1 : y <= v1) return 1;
  float lo = 0, hi = 1;
  for (int i = 0; i < 40; ++i) {
    float mid = 0.5f * (lo + hi), v;
    eval(b, mid, knots, nknots, 1, 0, v, d);
    if ((v < y) == increasing)
      lo = mid;
    else
      hi = mid;
  }
  return 0.5f * (lo + hi);
}

} // extern "C"
