// The noise family, following OSL's algorithms (src/include/OSL/oslnoise.h): gradient
// ("perlin", signed; "uperlin"/noise() = 0.5 * (perlin + 1)), "cell" (constant per integer
// cell), "hash" (per exact input) and the periodic variants, for 1 to 4 input dimensions and 1
// or 3 output channels. The lattice hash is Bob Jenkins' lookup3 (bjmix/bjfinal) as OSL's
// inthash; the gradients, quintic fade, lerp/bilerp/trilerp order and scale constants are
// OSL's, evaluated in float in the same operation order. Gradient noise also returns its
// analytic derivative (carried through the same formulas as OSL's Dual2 evaluation) so that
// Dx(noise(P)) follows the chain rule. runtime/shadeops/noise_reference.py is an independent
// Python transcription used to derive the expected values in the tests.
#include "shadeops.h"

#include "lobe/context.h"
#include "lobe/shading.h"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

namespace {

// ---- Bob Jenkins lookup3 (OIIO bjhash), OSL's inthash ----

inline uint32_t rot(uint32_t x, int k) { return (x << k) | (x >> (32 - k)); }

inline void bjmix(uint32_t& a, uint32_t& b, uint32_t& c) {
  a -= c;
  a ^= rot(c, 4);
  c += b;
  b -= a;
  b ^= rot(a, 6);
  a += c;
  c -= b;
  c ^= rot(b, 8);
  b += a;
  a -= c;
  a ^= rot(c, 16);
  c += b;
  b -= a;
  b ^= rot(a, 19);
  a += c;
  c -= b;
  c ^= rot(b, 4);
  b += a;
}

inline uint32_t bjfinal(uint32_t a, uint32_t b, uint32_t c) {
  c ^= b;
  c -= rot(b, 14);
  a ^= c;
  a -= rot(c, 11);
  b ^= a;
  b -= rot(a, 25);
  c ^= b;
  c -= rot(b, 16);
  a ^= c;
  a -= rot(c, 4);
  b ^= a;
  b -= rot(a, 14);
  c ^= b;
  c -= rot(b, 24);
  return c;
}

// inthash<N>(k) for N in 1..5.
uint32_t inthash(const uint32_t* k, int n) {
  uint32_t start = 0xdeadbeefu + (uint32_t(n) << 2) + 13u;
  uint32_t a = start, b = start, c = start;
  a += k[0];
  if (n > 1) b += k[1];
  if (n > 2) c += k[2];
  if (n > 3) {
    bjmix(a, b, c);
    a += k[3];
    if (n > 4) b += k[4];
  }
  return bjfinal(a, b, c);
}

// OSL's bits_to_01: bits * (1 / UINT_MAX), in float (so the top of the range rounds to 1).
inline float bits_to_01(uint32_t bits) {
  return float(bits) * (1.0f / float(std::numeric_limits<unsigned int>::max()));
}

inline int ifloor(float x) { return int(std::floor(x)); }

// OSL's wrap(): s modulo floor(period) (period at least 1), in float.
inline float wrapf(float s, float period) {
  period = std::floor(period);
  if (period < 1.0f) period = 1.0f;
  return s - period * std::floor(s / period);
}

inline int period_of(float p) {
  int q = ifloor(p);
  return q < 1 ? 1 : q;
}

inline int imod(int a, int b) {
  a %= b;
  return a < 0 ? a + b : a;
}

// ---- A value with its partials with respect to the (up to 4) inputs: OSL's Dual2 ----

struct D {
  float v;
  float d[4];
};

inline D dconst(float v) { return D{v, {0, 0, 0, 0}}; }
inline D operator+(const D& a, const D& b) {
  D r;
  r.v = a.v + b.v;
  for (int k = 0; k < 4; ++k) r.d[k] = a.d[k] + b.d[k];
  return r;
}
inline D operator-(const D& a, const D& b) {
  D r;
  r.v = a.v - b.v;
  for (int k = 0; k < 4; ++k) r.d[k] = a.d[k] - b.d[k];
  return r;
}
inline D operator-(const D& a) {
  D r;
  r.v = -a.v;
  for (int k = 0; k < 4; ++k) r.d[k] = -a.d[k];
  return r;
}
inline D operator*(const D& a, const D& b) {
  D r;
  r.v = a.v * b.v;
  for (int k = 0; k < 4; ++k) r.d[k] = a.v * b.d[k] + a.d[k] * b.v;
  return r;
}
inline D operator*(float a, const D& b) {
  D r;
  r.v = a * b.v;
  for (int k = 0; k < 4; ++k) r.d[k] = a * b.d[k];
  return r;
}
inline D operator*(const D& a, float b) { return b * a; }
inline D operator+(const D& a, float b) {
  D r = a;
  r.v = a.v + b;
  return r;
}
inline D operator-(const D& a, float b) {
  D r = a;
  r.v = a.v - b;
  return r;
}
inline D operator-(float a, const D& b) {
  D r = -b;
  r.v = a - b.v;
  return r;
}

// t * t * t * (t * (t * 6 - 15) + 10)
inline D fade(const D& t) { return t * t * t * (t * (t * 6.0f - 15.0f) + 10.0f); }

// OIIO::lerp / bilerp / trilerp (a*(1-x) + b*x forms).
inline D lerp(const D& v0, const D& v1, const D& x) { return v0 * (1.0f - x) + v1 * x; }
inline D bilerp(const D& v0, const D& v1, const D& v2, const D& v3, const D& s, const D& t) {
  D s1 = 1.0f - s;
  return (1.0f - t) * (v0 * s1 + v1 * s) + t * (v2 * s1 + v3 * s);
}
inline D trilerp(const D* v, const D& s, const D& t, const D& r) {
  D s1 = 1.0f - s, t1 = 1.0f - t, r1 = 1.0f - r;
  return r1 * (t1 * (v[0] * s1 + v[1] * s) + t * (v[2] * s1 + v[3] * s)) +
         r * (t1 * (v[4] * s1 + v[5] * s) + t * (v[6] * s1 + v[7] * s));
}

// OSL's gradient functions.
inline D grad(uint32_t hash, const D& x) {
  int h = int(hash & 15);
  float g = float(1 + (h & 7)); // 1, 2, .., 8
  if (h & 8) g = -g;            // random sign
  return g * x;
}
inline D grad(uint32_t hash, const D& x, const D& y) {
  int h = int(hash & 7); // 8 directions (+-1,+-2) and (+-2,+-1)
  D u = h < 4 ? x : y;
  D v = 2.0f * (h < 4 ? y : x);
  return ((h & 1) ? -u : u) + ((h & 2) ? -v : v);
}
inline D grad(uint32_t hash, const D& x, const D& y, const D& z) {
  int h = int(hash & 15); // the 12 cube edges (Perlin's improved noise)
  D u = h < 8 ? x : y;
  D v = h < 4 ? y : (h == 12 || h == 14) ? x : z;
  return ((h & 1) ? -u : u) + ((h & 2) ? -v : v);
}
inline D grad(uint32_t hash, const D& x, const D& y, const D& z, const D& w) {
  int h = int(hash & 31); // the edges of the hypercube
  D u = h < 24 ? x : y;
  D v = h < 16 ? y : z;
  D s = h < 8 ? z : w;
  return ((h & 1) ? -u : u) + ((h & 2) ? -v : v) + ((h & 4) ? -s : s);
}

// OSL's HashScalar / HashVector (and the periodic variants): one inthash of the integer corner
// (wrapped by the period); output channel j of a vector noise uses h >> (8 * j).
struct CornerHash {
  int n;
  const int* period; // null: not periodic
  int shift;
  uint32_t operator()(const int* c) const {
    uint32_t k[5] = {0, 0, 0, 0, 0};
    for (int i = 0; i < n; ++i) k[i] = uint32_t(period ? imod(c[i], period[i]) : c[i]);
    return inthash(k, n) >> shift;
  }
};

// OSL's perlin(): signed gradient noise; x[k] carries d/dx_k = 1.
D perlin(const float* xin, int n, const CornerHash& hash) {
  int X[4];
  D f[4], u[4];
  for (int k = 0; k < n; ++k) {
    X[k] = ifloor(xin[k]); // floorfrac: the fraction carries the input's derivative
    f[k] = dconst(xin[k] - float(X[k]));
    f[k].d[k] = 1;
    u[k] = fade(f[k]);
  }
  auto corner = [&](int bits) {
    int c[4];
    D r[4];
    for (int k = 0; k < n; ++k) {
      int b = (bits >> k) & 1;
      c[k] = X[k] + b;
      r[k] = b ? f[k] - 1.0f : f[k];
    }
    uint32_t h = hash(c);
    switch (n) {
    case 1:
      return grad(h, r[0]);
    case 2:
      return grad(h, r[0], r[1]);
    case 3:
      return grad(h, r[0], r[1], r[2]);
    default:
      return grad(h, r[0], r[1], r[2], r[3]);
    }
  };
  if (n == 1) return 0.2500f * lerp(corner(0), corner(1), u[0]);
  if (n == 2) return 0.6616f * bilerp(corner(0), corner(1), corner(2), corner(3), u[0], u[1]);
  D v[16];
  for (int i = 0; i < (1 << n); ++i) v[i] = corner(i);
  if (n == 3) return 0.9820f * trilerp(v, u[0], u[1], u[2]);
  return 0.8344f * lerp(trilerp(v, u[0], u[1], u[2]), trilerp(v + 8, u[0], u[1], u[2]), u[3]);
}

} // namespace

extern "C" {

// out[nout] = noise of `kind` at x[nin] (optionally periodic); grad, if non-null, receives
// d out[j] / d x[k] at grad[j * nin + k].
void lobe_noise(int kind, const float* x, int nin, const float* period, float* out, int nout,
                float* grad) {
  if (kind == lobe::shadeops::kPerlin || kind == lobe::shadeops::kUPerlin) {
    int per[4];
    if (period)
      for (int k = 0; k < nin; ++k) per[k] = period_of(period[k]);
    for (int j = 0; j < nout; ++j) {
      CornerHash h{nin, period ? per : nullptr, nout == 1 ? 0 : 8 * j};
      D r = perlin(x, nin, h);
      if (kind == lobe::shadeops::kUPerlin) r = 0.5f * (r + 1.0f);
      out[j] = r.v;
      if (grad)
        for (int k = 0; k < nin; ++k) grad[j * nin + k] = r.d[k];
    }
    return;
  }
  // cell / hash: inthash of the keys; a vector result appends the channel index as one more
  // key (OSL's hash3<N+1>). Periodic forms wrap the input first (OSL's wrap()).
  uint32_t k[5];
  for (int i = 0; i < nin; ++i) {
    float xi = period ? wrapf(x[i], period[i]) : x[i];
    if (kind == lobe::shadeops::kCell) {
      k[i] = uint32_t(ifloor(xi));
    } else {
      std::memcpy(&k[i], &xi, 4);
    }
  }
  for (int j = 0; j < nout; ++j) {
    if (nout == 1) {
      out[j] = bits_to_01(inthash(k, nin));
    } else {
      k[nin] = uint32_t(j);
      out[j] = bits_to_01(inthash(k, nin + 1));
    }
    if (grad)
      for (int i = 0; i < nin; ++i) grad[j * nin + i] = 0;
  }
}

// noise(name, ...) with a name known only at run time (OSL's genericnoise): dispatches on the
// name like the constant case in codegen ("gabor" is the gradient noise). An unknown name is a
// run-time error naming the source location; the result (and its gradient) is 0.
void lobe_noise_named(lobe::ShaderGlobals* sg, const char* name, const float* x, int nin,
                      const float* period, float* out, int nout, float* grad, const char* file,
                      int line) {
  std::string_view n = name ? name : "";
  int kind = n == "gabor" ? lobe::shadeops::kUPerlin : lobe::shadeops::noise_kind_from_name(n);
  if (kind >= 0) return lobe_noise(kind, x, nin, period, out, nout, grad);
  for (int j = 0; j < nout; ++j) out[j] = 0;
  if (grad)
    for (int k = 0; k < nout * nin; ++k) grad[k] = 0;
  if (sg && sg->context) {
    sg->context->errors++;
    sg->context->message("ERROR: Unknown noise type \"" + std::string(n) + "\": " + file + ":" +
                         std::to_string(line) + "\n");
  }
}

} // extern "C"

namespace lobe::shadeops {
int noise_kind_from_name(std::string_view name) {
  if (name == "perlin" || name == "snoise" || name == "simplex") return kPerlin;
  if (name == "uperlin" || name == "noise" || name == "usimplex") return kUPerlin;
  if (name == "cell" || name == "cellnoise") return kCell;
  if (name == "hash" || name == "hashnoise") return kHash;
  return -1;
}
} // namespace lobe::shadeops
