// The noise family, following OSL's algorithms: from src/include/OSL/oslnoise.h gradient
// ("perlin", signed; "uperlin"/noise() = 0.5 * (perlin + 1)), "cell" (constant per integer
// cell), "hash" (per exact input) and their periodic variants, and from
// src/liboslnoise/simplexnoise.cpp "simplex" (signed; "usimplex" = 0.5 * (simplex + 1)); 1 to 4
// input dimensions and 1 or 3 output channels. The lattice hash is Bob Jenkins' lookup3
// (bjmix/bjfinal) as OSL's inthash and scramble; gradients, fade, interpolation order, corner
// order and scale constants are OSL's, evaluated in float in the same operation order. Gradient
// and simplex noise also return their analytic derivative (for perlin, carried through the same
// formulas as OSL's Dual2 evaluation) so that Dx(noise(P)) follows the chain rule.
// runtime/shadeops/noise_reference.py is an independent Python transcription used to derive the
// expected values in the tests.
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

// Inputs of gradient and simplex noise, made safe for ifloor: an infinite or NaN coordinate
// becomes 0, one of magnitude 2^24 or more (where every float is an integer, so the noise has
// no detail left to show) is wrapped modulo 2^24, exactly. Below 2^24 nothing changes.
inline float lattice_safe(float x) {
  if (!std::isfinite(x)) return 0.0f;
  constexpr float kWrap = 16777216.0f;
  return std::fabs(x) < kWrap ? x : std::fmod(x, kWrap);
}

// floor as a lattice key for cell noise: int64 first, so that any finite input is defined
// (the key wraps modulo 2^32, like OSL's int conversion in range); non-finite inputs give 0.
inline uint32_t cell_key(float x) {
  if (!std::isfinite(x) || std::fabs(x) >= 9.2e18f) return 0;
  return uint32_t(int64_t(std::floor(x)));
}

// OSL's wrap(): s modulo floor(period) (period at least 1), in float.
inline float wrapf(float s, float period) {
  period = std::floor(period);
  if (period < 1.0f) period = 1.0f;
  return s - period * std::floor(s / period);
}

inline int period_of(float p) {
  if (!(p >= 1.0f)) return 1;            // also NaN
  if (p >= 16777216.0f) return 16777216; // inputs wrap at 2^24 anyway (lattice_safe)
  return ifloor(p);
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

// ---- Simplex noise: OSL's simplexnoise.cpp (Stefan Gustavson's sdnoise1234) ----
//
// Each corner c of the simplex containing x contributes t^4 (g_c . d) with d = x - c (in
// unskewed space), t = r^2 - |d|^2 (0 when negative) and g_c a hashed gradient; the sum times
// an empirical scale covers about [-1, 1]. r^2 is 1 in 1-D and 0.5 above (OSL's radius: with
// Gustavson's 0.6 the 3-D and 4-D noise jumps where a corner's support is cut at the simplex
// boundary). `seed` selects an independent noise: channel j of a vector result uses seed j.
// The derivative is the sum of d/dx [t^4 (g . d)] = t^4 g - 8 t^3 (g . d) d, times the scale.

// OSL's scramble: one lookup3 final mix in place of Gustavson's permutation table.
inline uint32_t scramble(uint32_t v0, uint32_t v1 = 0, uint32_t v2 = 0) {
  return bjfinal(v0, v1, v2 ^ 0xdeadbeefu);
}

// Corner gradients, one row per hash value: 2-D, 8 directions; 3-D, the 12 cube edges, then 4
// of them again to fill 16 rows; 4-D, the 32 tesseract edges (a 0 in each position in turn, the
// other three signs counting down from +++ with the last fastest).
constexpr float kGrad2[8][2] = {{-1, -1}, {1, 0},  {-1, 0}, {1, 1},
                                {-1, 1},  {0, -1}, {0, 1},  {1, -1}};
constexpr float kGrad3[16][3] = {{1, 0, 1},  {0, 1, 1},  {-1, 0, 1},  {0, -1, 1},
                                 {1, 0, -1}, {0, 1, -1}, {-1, 0, -1}, {0, -1, -1},
                                 {1, -1, 0}, {1, 1, 0},  {-1, 1, 0},  {-1, -1, 0},
                                 {1, 0, 1},  {-1, 0, 1}, {0, 1, -1},  {0, -1, -1}};
constexpr float kGrad4[32][4] = {{0, 1, 1, 1},  {0, 1, 1, -1},  {0, 1, -1, 1},  {0, 1, -1, -1},
                                 {0, -1, 1, 1}, {0, -1, 1, -1}, {0, -1, -1, 1}, {0, -1, -1, -1},
                                 {1, 0, 1, 1},  {1, 0, 1, -1},  {1, 0, -1, 1},  {1, 0, -1, -1},
                                 {-1, 0, 1, 1}, {-1, 0, 1, -1}, {-1, 0, -1, 1}, {-1, 0, -1, -1},
                                 {1, 1, 0, 1},  {1, 1, 0, -1},  {1, -1, 0, 1},  {1, -1, 0, -1},
                                 {-1, 1, 0, 1}, {-1, 1, 0, -1}, {-1, -1, 0, 1}, {-1, -1, 0, -1},
                                 {1, 1, 1, 0},  {1, 1, -1, 0},  {1, -1, 1, 0},  {1, -1, -1, 0},
                                 {-1, 1, 1, 0}, {-1, 1, -1, 0}, {-1, -1, 1, 0}, {-1, -1, -1, 0}};

// OSL's grad2/grad3/grad4: the gradient at lattice corner c (n = 2..4 coordinates).
const float* simplex_grad(const int* c, int n, uint32_t seed) {
  auto u = [&](int k) { return uint32_t(c[k]); };
  if (n == 2) return kGrad2[scramble(u(0), u(1), seed) & 7];
  if (n == 3) return kGrad3[scramble(u(0), u(1), scramble(u(2), seed)) & 15];
  return kGrad4[scramble(u(0), u(1), scramble(u(2), u(3), seed)) & 31];
}

// OSL's simplexnoise1: corners floor(x) and floor(x) + 1, gradients +-1..8 (grad1), scale 0.36.
D simplex1(float x, uint32_t seed) {
  int i0 = ifloor(x);
  float x0 = x - float(i0), n[2], dn[2];
  for (int c = 0; c < 2; ++c) {
    float xc = c ? x0 - 1.0f : x0;
    uint32_t h = scramble(uint32_t(i0 + c), seed) & 15;
    float g = float(1 + (h & 7));
    if (h & 8) g = -g;
    float t = 1.0f - xc * xc, t2 = t * t, t4 = t2 * t2; // |xc| <= 1, so t >= 0
    n[c] = t4 * g * xc;
    dn[c] = t4 * g - 8.0f * t2 * t * g * xc * xc;
  }
  D r = dconst(0.36f * (n[0] + n[1]));
  r.d[0] = 0.36f * (dn[0] + dn[1]);
  return r;
}

// Skew factor F = (sqrt(n + 1) - 1) / n, unskew factor G = (1 - 1 / sqrt(n + 1)) / n and output
// scale of OSL's 2-, 3- and 4-D simplex noise (row n - 2), as OSL writes them.
struct SimplexDim {
  float F, G, scale;
};
constexpr SimplexDim kSimplexDim[3] = {{0.366025403f, 0.211324865f, 64.0f},
                                       {0.333333333f, 0.166666667f, 68.0f},
                                       {0.309016994f, 0.138196601f, 54.0f}};

// OSL's simplexnoise2/3/4 in its float operation order: skew x onto the integer lattice to find
// the cell, rank the offsets from the cell origin, and step from the origin along the largest
// offset first, one coordinate per corner, to the opposite cell corner.
D simplex(const float* x, int n, uint32_t seed) {
  if (n == 1) return simplex1(x[0], seed);
  const SimplexDim& k = kSimplexDim[n - 2];
  float s = x[0];
  for (int a = 1; a < n; ++a) s += x[a];
  s *= k.F;
  int cell[4], sum = 0;
  for (int a = 0; a < n; ++a) {
    cell[a] = ifloor(x[a] + s);
    sum += cell[a];
  }
  float t = float(sum) * k.G, d0[4];
  for (int a = 0; a < n; ++a) d0[a] = x[a] - (float(cell[a]) - t);
  // rank[a]: how many offsets d0[a] exceeds. Ties go as in OSL (3-D: to the earlier coordinate,
  // 2-D and 4-D: to the later), so the same one of the simplices sharing the point is used.
  int rank[4] = {0, 0, 0, 0};
  for (int a = 0; a < n; ++a)
    for (int b = a + 1; b < n; ++b) ++rank[(n == 3 ? d0[a] >= d0[b] : d0[a] > d0[b]) ? a : b];
  float nc[5] = {0, 0, 0, 0, 0}, dd[4] = {0, 0, 0, 0}, gt[4] = {0, 0, 0, 0};
  for (int c = 0; c <= n; ++c) {
    int corner[4];
    float d[4], tc = 0.5f;
    for (int a = 0; a < n; ++a) {
      int step = rank[a] >= n - c ? 1 : 0; // corner c has stepped along the c largest offsets
      corner[a] = cell[a] + step;
      d[a] = c == 0 ? d0[a] : d0[a] - float(step) + float(c) * k.G;
      tc -= d[a] * d[a];
    }
    if (tc < 0.0f) continue; // outside this corner's support
    const float* g = simplex_grad(corner, n, seed);
    float dot = g[0] * d[0];
    for (int a = 1; a < n; ++a) dot += g[a] * d[a];
    float t2 = tc * tc, t4 = t2 * t2, t3dot = t2 * tc * dot;
    nc[c] = t4 * dot;
    for (int a = 0; a < n; ++a) {
      dd[a] += t3dot * d[a];
      gt[a] += t4 * g[a];
    }
  }
  float total = nc[0];
  for (int c = 1; c <= n; ++c) total += nc[c];
  D r = dconst(k.scale * total);
  for (int a = 0; a < n; ++a) r.d[a] = k.scale * (gt[a] - 8.0f * dd[a]);
  return r;
}

} // namespace

extern "C" {

// out[nout] = noise of `kind` at x[nin] (optionally periodic); grad, if non-null, receives
// d out[j] / d x[k] at grad[j * nin + k].
void lobe_noise(int kind, const float* x, int nin, const float* period, float* out, int nout,
                float* grad) {
  using namespace lobe::shadeops;
  bool simplex_kind = kind == kSimplex || kind == kUSimplex;
  if (simplex_kind || kind == kPerlin || kind == kUPerlin) {
    float safe[4];
    for (int k = 0; k < nin && k < 4; ++k) safe[k] = lattice_safe(x[k]);
    x = safe;
    // Simplex noise has no periodic form (OSL has none; the name dispatch rejects
    // pnoise("simplex")), so `period` only applies to gradient noise.
    int per[4];
    if (period)
      for (int k = 0; k < nin; ++k) per[k] = period_of(period[k]);
    for (int j = 0; j < nout; ++j) {
      D r = simplex_kind
                ? simplex(x, nin, uint32_t(j))
                : perlin(x, nin, CornerHash{nin, period ? per : nullptr, nout == 1 ? 0 : 8 * j});
      if (kind == kUPerlin || kind == kUSimplex) r = 0.5f * (r + 1.0f);
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
    if (kind == kCell) {
      k[i] = cell_key(xi);
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

// noise(name, ...) with a name known only at run time (OSL's genericnoise / genericpnoise):
// dispatches on the name like the constant case in codegen ("gabor" is the gradient noise). An
// unknown name, or "simplex"/"usimplex" with a period, is a run-time error naming the source
// location; the result (and its gradient) is 0.
void lobe_noise_named(lobe::ShaderGlobals* sg, const char* name, const float* x, int nin,
                      const float* period, float* out, int nout, float* grad, const char* file,
                      int line) {
  std::string_view n = name ? name : "";
  int kind = n == "gabor" ? lobe::shadeops::kUPerlin
                          : lobe::shadeops::noise_kind_from_name(n, period != nullptr);
  if (kind >= 0) return lobe_noise(kind, x, nin, period, out, nout, grad);
  for (int j = 0; j < nout; ++j) out[j] = 0;
  if (grad)
    for (int k = 0; k < nout * nin; ++k) grad[k] = 0;
  if (sg && sg->context) {
    sg->context->error("Unknown noise type \"" + std::string(n) + "\": " + file + ":" +
                       std::to_string(line));
  }
}

} // extern "C"

namespace lobe::shadeops {
int noise_kind_from_name(std::string_view name, bool periodic) {
  if (name == "perlin" || name == "snoise") return kPerlin;
  if (name == "uperlin" || name == "noise") return kUPerlin;
  if (name == "simplex") return periodic ? -1 : kSimplex;
  if (name == "usimplex") return periodic ? -1 : kUSimplex;
  if (name == "cell" || name == "cellnoise") return kCell;
  if (name == "hash" || name == "hashnoise") return kHash;
  return -1;
}
} // namespace lobe::shadeops
