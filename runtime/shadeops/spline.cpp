// spline() and splineinverse(): OSL's cubic bases over a knot vector, computed as OSL 1.13
// computes them (bit for bit against testshade: tests/shade/spline_osl.osl). With step s and n
// knots there are (n - 4) / s + 1 segments; x in [0,1] (clamped) picks segment k and the four
// knots starting at k*s, whose combination by the basis matrix gives the segment's cubic.
// "constant" returns knots[k+1]. Unknown bases behave as catmull-rom.
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

// One component of the spline in OSL's arithmetic, with the derivatives (dx, dy) of the
// result for those (xdx, xdy) of x, as OSL's dual numbers carry them (null: value only). The
// segment's four knots P combine into the cubic's coefficients tk[k] = m[k] . P (summed left to
// right), then tr = ((tk0 t + tk1) t + tk2) t + tk3 with t the position in the segment, every
// product and sum rounded (OSL's spline shadeops are compiled C++ without contraction). A
// clamped x (outside [0, 1], or NaN, which reads as 0) carries no derivatives.
float eval(const Basis& b, float x, const float* knots, int nknots, int comps, int c,
           const float* xd = nullptr, float* d = nullptr) {
  if (d) d[0] = d[1] = 0;
  if (nknots < 4) return 0;
  bool clamped = !(x >= 0 && x <= 1); // NaN too: it reads as 0
  x = x > 1 ? 1.0f : x >= 0 ? x : 0.0f;
  int nsegs = (nknots - 4) / b.step + 1;
  float xs = x * float(nsegs);
  int seg = std::min(int(xs), nsegs - 1);
  const float* p = knots + size_t(seg * b.step) * size_t(comps) + c;
  if (!std::strcmp(b.name, "constant")) return p[comps];
  float t = xs - float(seg);
  float tk[4];
  for (int k = 0; k < 4; ++k) {
    float s = b.m[k][0] * p[0];
    s = s + b.m[k][1] * p[comps];
    s = s + b.m[k][2] * p[2 * comps];
    tk[k] = s + b.m[k][3] * p[3 * comps];
  }
  float v1 = tk[0] * t;
  v1 = v1 + tk[1];
  float v2 = v1 * t;
  v2 = v2 + tk[2];
  float v3 = v2 * t;
  if (d && !clamped)
    for (int k = 0; k < 2; ++k) { // dual products: a.val * b.d + a.d * b.val
      float td = xd[k] * float(nsegs);
      float d1 = tk[0] * td;
      float p2 = v1 * td, q2 = d1 * t;
      float d2 = p2 + q2;
      float p3 = v2 * td, q3 = d2 * t;
      d[k] = p3 + q3;
    }
  return v3 + tk[3];
}

// The x in [xmin, xmax] where the increasing or decreasing f(x) = y, or the interval's edge
// on y's side when [f(xmin), f(xmax)] does not bracket y (`bracketed` false): regula falsi for
// the first 3/4 of 32 iterations, then bisection, until the interval or |f(x) - y| is below
// 1e-6 (the method and constants of OpenImageIO's invert(), which OSL's splineinverse uses).
template <class F> float invert(const F& f, float y, float xmin, float xmax, bool& bracketed) {
  constexpr int kIters = 32, kFalsiIters = kIters * 3 / 4;
  constexpr float kEps = 1.0e-6f;
  float v0 = f(xmin), v1 = f(xmax);
  float x = xmin;
  bool increasing = v0 < v1;
  float lo = increasing ? v0 : v1, hi = increasing ? v1 : v0;
  bracketed = y >= lo && y <= hi;
  if (!bracketed) return ((y < lo) == increasing) ? xmin : xmax;
  if (std::fabs(v0 - v1) < kEps) return x;
  for (int i = 0; i < kIters; ++i) {
    float t = 0.5f;
    if (i < kFalsiIters) {
      t = (y - v0) / (v1 - v0);
      if (t <= 0 || t >= 1) t = 0.5f; // regula falsi failed: bisect
    }
    x = xmin * (1 - t) + xmax * t;
    float v = f(x);
    if ((v < y) == increasing) {
      xmin = x;
      v0 = v;
    } else {
      xmax = x;
      v1 = v;
    }
    if (std::fabs(xmax - xmin) < kEps || std::fabs(v - y) < kEps) return x;
  }
  return x;
}

} // namespace

extern "C" {

// out[comps] = spline(basis, x, knots[nknots][comps]); odx, ody (null: none) receive the
// result's derivatives for x's (xdx, xdy).
void lobe_spline(const char* basis, float x, float xdx, float xdy, const float* knots, int nknots,
                 int comps, float* out, float* odx, float* ody) {
  const Basis& b = find_basis(basis);
  const float xd[2] = {xdx, xdy};
  for (int c = 0; c < comps; ++c) {
    float d[2];
    out[c] = eval(b, x, knots, nknots, comps, c, xd, odx ? d : nullptr);
    if (odx) odx[c] = d[0], ody[c] = d[1];
  }
}

// The x in [0,1] with spline(x) = y, as OSL finds it: 0 or 1 when y is beyond knot 1 or knot
// n-2 on the side the knots run, else each segment in turn until one brackets y (a monotonic
// knot vector can still make a curve that is not).
float lobe_splineinverse(const char* basis, float y, const float* knots, int nknots) {
  const Basis& b = find_basis(basis);
  if (nknots < 4) return 0;
  float first = knots[1], last = knots[nknots - 2];
  bool increasing = first < last;
  if (increasing ? y <= first : y >= first) return 0;
  if (increasing ? y >= last : y <= last) return 1;
  auto f = [&](float x) { return eval(b, x, knots, nknots, 1, 0); };
  int nsegs = (nknots - 4) / b.step + 1;
  float inv = 1.0f / float(nsegs), r0 = 0, result = 0;
  for (int s = 0; s < nsegs; ++s) {
    float r1 = inv * float(s + 1);
    bool bracketed;
    result = invert(f, y, r0, r1, bracketed);
    if (bracketed) return result;
    r0 = r1;
  }
  return result;
}

} // extern "C"
