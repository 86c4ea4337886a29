// spline() and splineinverse(): OSL's cubic bases over a knot vector, computed as OSL 1.13
// computes them (bit for bit against testshade: tests/shade/spline_osl.osl and
// spline_derivs_osl.osl, derivatives included). With step s and n
// knots there are (n - 4) / s + 1 segments; x in [0,1] (clamped) picks segment k and the four
// knots starting at k*s, whose combination by the basis matrix gives the segment's cubic.
// "constant" returns knots[k+1]. Unknown bases behave as linear (as OSL 1.13.12's do).
#include "shadeop_decls.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <type_traits>

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
  return kBases[4]; // linear
}

// A value with optional derivatives, combined as OSL's dual numbers combine a Dual2 with a
// float or another Dual2 (OSL's spline shadeops are templates over which of x and the knots
// carry derivatives): a product of two duals is a.val * b.d + a.d * b.val, of a dual and a
// float the dual's derivatives times the float; a sum adds the derivatives present. Every
// product and sum is rounded (the shadeops are compiled C++ without contraction).
struct Md {
  float v = 0, dx = 0, dy = 0;
  bool d = false; // carries derivatives
};

Md operator*(const Md& a, const Md& b) {
  Md r{a.v * b.v, 0, 0, a.d || b.d};
  if (a.d && b.d) {
    float px = a.v * b.dx, qx = a.dx * b.v, py = a.v * b.dy, qy = a.dy * b.v;
    r.dx = px + qx, r.dy = py + qy;
  } else if (a.d) {
    r.dx = a.dx * b.v, r.dy = a.dy * b.v;
  } else if (b.d) {
    r.dx = a.v * b.dx, r.dy = a.v * b.dy;
  }
  return r;
}
Md operator+(const Md& a, const Md& b) {
  Md r{a.v + b.v, 0, 0, a.d || b.d};
  if (a.d && b.d)
    r.dx = a.dx + b.dx, r.dy = a.dy + b.dy;
  else if (a.d)
    r.dx = a.dx, r.dy = a.dy;
  else if (b.d)
    r.dx = b.dx, r.dy = b.dy;
  return r;
}
Md operator-(const Md& a, const Md& b) {
  Md r{a.v - b.v, 0, 0, a.d || b.d};
  if (a.d && b.d)
    r.dx = a.dx - b.dx, r.dy = a.dy - b.dy;
  else if (a.d)
    r.dx = a.dx, r.dy = a.dy;
  else if (b.d)
    r.dx = -b.dx, r.dy = -b.dy;
  return r;
}
// Dual division (both operands duals, as inside splineinverse's search): q = a / b, q' = (1 / b)
// * (a' - q b'), the reciprocal and the quotient each rounded.
Md operator/(const Md& a, const Md& b) {
  float inv = 1.0f / b.v, q = a.v / b.v;
  float px = q * b.dx, py = q * b.dy;
  float sx = a.dx - px, sy = a.dy - py;
  return {q, inv * sx, inv * sy, true};
}
Md scaled(float f, const Md& a) { return {f * a.v, f * a.dx, f * a.dy, a.d}; }
Md fabs_md(const Md& a) { return a.v < 0 ? Md{-a.v, -a.dx, -a.dy, a.d} : a; }

// The knots: `comps` floats each, component `c` read; with derivatives when `kdx` is set (the
// knot array's derivative planes, laid out as its values).
struct Knots {
  const float* v;
  const float* kdx;
  const float* kdy;
  int n, comps, c;
  // Knot i; 0 outside [0, n) (where OSL, given fewer than four knots, reads past the array).
  Md at(int i) const {
    if (i < 0 || i >= n) return Md{0, 0, 0, kdx != nullptr};
    size_t k = size_t(i) * size_t(comps) + size_t(c);
    return kdx ? Md{v[k], kdx[k], kdy[k], true} : Md{v[k], 0, 0, false};
  }
};

// One component of the spline in OSL's arithmetic. The segment's four knots P combine into the
// cubic's coefficients tk[k] = m[k] . P (summed left to right), then ((tk0 t + tk1) t + tk2) t
// + tk3 with t the position in the segment, as duals where x or the knots carry derivatives.
// A clamped x (outside [0, 1], or NaN, which reads as 0) carries no derivatives of its own;
// "constant" returns knots[k+1] without derivatives.
// Fewer than four knots leave OSL's segment count (n - 4) / step + 1 at zero or below and its
// segment index negative: its degenerate segment is evaluated the same way here, the knots it
// would read before the first (or past the last) as 0 (OSL reads whatever memory is there; at
// the ends of such a segment those weigh nothing: spline("linear", 0.25, {5, 7, 9}) is 7 in
// OSL 1.13.12, as "catmull-rom" and "bspline" are).
Md eval(const Basis& b, Md x, const Knots& kn) {
  if (kn.n < 1) return Md{0, 0, 0, x.d || kn.kdx};
  bool clamped = !(x.v >= 0 && x.v <= 1); // NaN too: it reads as 0
  if (clamped) x = Md{x.v > 1 ? 1.0f : 0.0f, 0, 0, false};
  int nsegs = (kn.n - 4) / b.step + 1; // C's division: toward zero
  Md xs = scaled(float(nsegs), x);
  int seg = std::min(int(xs.v), nsegs - 1);
  int first = seg * b.step;
  if (!std::strcmp(b.name, "constant")) return Md{kn.at(first + 1).v, 0, 0, x.d || kn.kdx};
  Md t = xs;
  t.v = xs.v - float(seg);
  Md p[4] = {kn.at(first), kn.at(first + 1), kn.at(first + 2), kn.at(first + 3)};
  Md tk[4];
  for (int k = 0; k < 4; ++k) {
    Md s = scaled(b.m[k][0], p[0]);
    s = s + scaled(b.m[k][1], p[1]);
    s = s + scaled(b.m[k][2], p[2]);
    tk[k] = s + scaled(b.m[k][3], p[3]);
  }
  Md r = tk[0] * t + tk[1];
  r = r * t + tk[2];
  return r * t + tk[3];
}

// invert() over plain floats or over duals (Md with derivatives), as OpenImageIO's template
// is instantiated for both.
float val(float a) { return a; }
float val(const Md& a) { return a.v; }
float absolute(float a) { return std::fabs(a); }
Md absolute(const Md& a) { return fabs_md(a); }
template <class T> T constant(float c);
template <> float constant<float>(float c) { return c; }
template <> Md constant<Md>(float c) { return Md{c, 0, 0, true}; }

// The x in [xmin, xmax] where the increasing or decreasing f(x) = y, or the interval's edge
// on y's side when [f(xmin), f(xmax)] does not bracket y (`bracketed` false): regula falsi for
// the first 3/4 of 32 iterations, then bisection, until the interval or |f(x) - y| is below
// 1e-6 (the method and constants of OpenImageIO's invert(), which OSL's splineinverse uses).
template <class T, class F>
T invert(const F& f, const T& y, const T& xmin_, const T& xmax_, bool& bracketed) {
  constexpr int kIters = 32, kFalsiIters = kIters * 3 / 4;
  constexpr float kEps = 1.0e-6f;
  T xmin = xmin_, xmax = xmax_;
  T v0 = f(xmin), v1 = f(xmax);
  T x = xmin;
  bool increasing = val(v0) < val(v1);
  float lo = increasing ? val(v0) : val(v1), hi = increasing ? val(v1) : val(v0);
  bracketed = val(y) >= lo && val(y) <= hi;
  if (!bracketed) return ((val(y) < lo) == increasing) ? xmin : xmax;
  if (val(absolute(v0 - v1)) < kEps) return x;
  for (int i = 0; i < kIters; ++i) {
    T t = constant<T>(0.5f);
    if (i < kFalsiIters) {
      t = (y - v0) / (v1 - v0);
      if (val(t) <= 0 || val(t) >= 1) t = constant<T>(0.5f); // regula falsi failed: bisect
    }
    x = xmin * (constant<T>(1) - t) + xmax * t;
    T v = f(x);
    if ((val(v) < val(y)) == increasing) {
      xmin = x;
      v0 = v;
    } else {
      xmax = x;
      v1 = v;
    }
    if (val(absolute(xmax - xmin)) < kEps || val(absolute(v - y)) < kEps) return x;
  }
  return x;
}

// splineinverse over floats or duals: 0 or 1 when y is beyond the curve's first or last knot
// on the side the knots run, else each segment in turn until one brackets y (a monotonic knot
// vector can still make a curve that is not).
template <class T> T spline_inverse(const Basis& b, const T& y, const Knots& kn) {
  if (kn.n < 4) return constant<T>(0);
  // The curve's ends: knots 1 and n-2 for the bases that step by one knot, the first and last
  // knot for bezier and hermite (whose curves pass through them), as OSL reads them.
  int low = b.step == 1 ? 1 : 0, high = b.step == 1 ? kn.n - 2 : kn.n - 1;
  float first = kn.v[low], last = kn.v[high];
  bool increasing = kn.v[1] < kn.v[kn.n - 2]; // the direction from knots 1 and n-2 always
  if (increasing ? val(y) <= first : val(y) >= first) return constant<T>(0);
  if (increasing ? val(y) >= last : val(y) <= last) return constant<T>(1);
  auto f = [&](const T& x) -> T {
    if constexpr (std::is_same_v<T, float>)
      return eval(b, Md{x, 0, 0, false}, kn).v;
    else
      return eval(b, x, kn);
  };
  int nsegs = (kn.n - 4) / b.step + 1;
  float inv = 1.0f / float(nsegs), r0 = 0;
  T result = constant<T>(0);
  for (int s = 0; s < nsegs; ++s) {
    float r1 = inv * float(s + 1);
    bool bracketed;
    result = invert(f, y, constant<T>(r0), constant<T>(r1), bracketed);
    if (bracketed) return result;
    r0 = r1;
  }
  return result;
}
} // namespace

extern "C" {

// out[comps] = spline(basis, x, knots[nknots][comps]). x carries derivatives (xdx, xdy) when
// `x_derivs`; the knots when `kdx`/`kdy` are set (their derivative planes, laid out as
// `knots`). odx, ody (null: none) receive the result's derivatives.
void lobe_spline(const char* basis, float x, float xdx, float xdy, int x_derivs, const float* knots,
                 const float* kdx, const float* kdy, int nknots, int comps, float* out, float* odx,
                 float* ody) {
  const Basis& b = find_basis(basis);
  Md xm{x, xdx, xdy, x_derivs != 0};
  for (int c = 0; c < comps; ++c) {
    Md r = eval(b, xm, Knots{knots, kdx, kdy, nknots, comps, c});
    out[c] = r.v;
    if (odx) odx[c] = r.d ? r.dx : 0.0f, ody[c] = r.d ? r.dy : 0.0f;
  }
}

// The x in [0,1] with spline(x) = y, as OSL finds it (spline_inverse above).
float lobe_splineinverse(const char* basis, float y, const float* knots, int nknots) {
  return spline_inverse(find_basis(basis), y, Knots{knots, nullptr, nullptr, nknots, 1, 0});
}

// The same with derivatives: the search runs on duals, y with (ydx, ydy), as OSL's
// splineinverse does when its result carries derivatives (the knots' values only: OSL's search
// does not read their derivatives); out[3] receives the value and its derivatives.
void lobe_splineinverse_d(const char* basis, float y, float ydx, float ydy, const float* knots,
                          int nknots, float* out) {
  Md r = spline_inverse(find_basis(basis), Md{y, ydx, ydy, true},
                        Knots{knots, nullptr, nullptr, nknots, 1, 0});
  out[0] = r.v, out[1] = r.dx, out[2] = r.dy;
}

} // extern "C"
