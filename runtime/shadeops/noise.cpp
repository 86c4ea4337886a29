// The noise family, following OSL's algorithms: from src/include/OSL/oslnoise.h gradient
// ("perlin", signed; "uperlin"/noise() = 0.5 * (perlin + 1)), "cell" (constant per integer
// cell), "hash" (per exact input) and their periodic variants, and from
// src/liboslnoise/simplexnoise.cpp "simplex" (signed; "usimplex" = 0.5 * (simplex + 1)); 1 to 4
// input dimensions and 1 or 3 output channels. The lattice hash is Bob Jenkins' lookup3
// (runtime/mathlib/hashword.h) as OSL's inthash and scramble; gradients, fade, interpolation order,
// corner order and scale constants are OSL's, evaluated in float in the same operation order.
// Gradient and simplex noise also return their analytic derivative (for perlin, carried through the
// same formulas as OSL's Dual2 evaluation) so that Dx(noise(P)) follows the chain rule.
// runtime/shadeops/noise_reference.py is an independent Python transcription used to derive the
// expected values in the tests.
#include "hashword.h"
#include "shadeop_decls.h"
#include "shadeops.h"

#include "lobe/context.h"
#include "lobe/shading.h"

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <type_traits>
#include <utility>

#if defined(__x86_64__) || defined(__i386__)
#include <xmmintrin.h>
#endif

// Bitcode builds (lobe_shadeops.bc) keep each noise variant a function of its own, so that
// lobe_noise_d stays a small dispatcher the JIT inlines into a shader, where the call's constants
// select one variant (runtime/jit/shadeop_bitcode.h; the JIT lets its inliner take the variant
// too). Native builds leave the choice to the compiler.
#ifdef LOBE_BITCODE
#define LOBE_VARIANT __attribute__((noinline))
#define LOBE_BATCHABLE __attribute__((noinline))
#else
#define LOBE_VARIANT
#define LOBE_BATCHABLE
#endif

namespace {

// ---- OSL's inthash: Bob Jenkins' lookup3 hashword with initval 13 (runtime/mathlib) ----

// Lanes of 32-bit words (GCC/Clang vector extension): the corners of a noise cell, hashed at
// once. The operations wrap lane by lane as uint32_t does, so each lane is the scalar hash.
template <int L> struct Lanes { typedef uint32_t type __attribute__((vector_size(4 * L))); };

// u = {0, 1, .., L - 1}.
template <class U, uint32_t... I>
inline void lane_indices(U& u, std::integer_sequence<uint32_t, I...>) {
  u = U{I...};
}

// inthash<N> of the 2^N corners of the cell at X (one lane per corner, bit k of the lane index
// for axis k: key X[k] or X1[k]), N in 1..4 known at compile time. The same words as
// math::hashword(key, N, 13) corner by corner.
template <int N> inline void corner_hashes(const uint32_t* X, const uint32_t* X1, uint32_t* h) {
  constexpr int kCorners = 1 << N;
  using U = typename Lanes<kCorners>::type;
  U lane, key[N];
  lane_indices(lane, std::make_integer_sequence<uint32_t, kCorners>());
  for (int k = 0; k < N; ++k) {
    U x0 = U{} + X[k], x1 = U{} + X1[k], on = U{} - ((lane >> k) & 1u); // ~0 where bit k is set
    key[k] = x0 ^ ((x0 ^ x1) & on);
  }
  constexpr uint32_t start = 0xdeadbeefu + (uint32_t(N) << 2) + 13u;
  U a = U{} + start, b = a, c = a;
  a += key[0];
  if constexpr (N > 1) b += key[1];
  if constexpr (N > 2) c += key[2];
  if constexpr (N > 3) {
    lobe::math::lookup3_mix(a, b, c);
    a += key[3];
  }
  lobe::math::lookup3_final_in_place(a, b, c);
  for (int i = 0; i < kCorners; ++i) h[i] = c[i];
}

// inthash<N>(k) for N in 1..5.
inline uint32_t inthash(const uint32_t* k, int n) { return lobe::math::hashword(k, n, 13); }

// OSL's bits_to_01: bits * (1 / UINT_MAX), in float (so the top of the range rounds to 1).
inline float bits_to_01(uint32_t bits) {
  return float(bits) * (1.0f / float(std::numeric_limits<unsigned int>::max()));
}

// OSL's float -> int conversions, with the result x86 gives (and OSL, built for x86, returns)
// where C++ leaves it undefined: a NaN, or a value outside the int range, converts to INT_MIN.
// On x86 that is what cvttss2si does, so the range test is the instruction's own.
inline int to_int(float f) {
#if defined(__x86_64__) || defined(__i386__)
  return _mm_cvtt_ss2si(_mm_set_ss(f));
#else
  return f >= -2147483648.0f && f < 2147483648.0f ? int(f) : std::numeric_limits<int>::min();
#endif
}
// OIIO::ifloor: int(floor(x)).
inline int ifloor(float x) { return to_int(std::floor(x)); }

// Cell noise key: OSL's ifloor, as unsigned.
inline uint32_t cell_key(float x) { return uint32_t(ifloor(x)); }

// OSL's wrap(): s modulo floor(period) (period at least 1), in float.
inline float wrapf(float s, float period) {
  period = std::floor(period);
  if (period < 1.0f) period = 1.0f;
  return s - period * std::floor(s / period);
}

// OSL's HashScalarPeriodic period: ifloor(p), at least 1 (NaN and huge periods give 1, as
// ifloor gives INT_MIN for them).
inline int period_of(float p) {
  int i = ifloor(p);
  return i < 1 ? 1 : i;
}

inline int imod(int a, int b) {
  a %= b;
  return a < 0 ? a + b : a;
}

// ---- OSL's Dual2<float>: a value with its derivatives along screen x and y ----
//
// Gradient noise with derivatives is evaluated on these, seeded with the inputs' own Dx/Dy, as
// OSL does (not as partials with respect to the inputs combined by the chain rule afterwards):
// the same operations in the same order round the same way, so Dx(noise(P)) is OSL's to the
// bit. The operators are OSL's dual.h ones: a constant operand of a Dual2 expression (fade's
// 6, 15, 10 and lerp's 1) is itself a Dual2 with zero derivatives.

struct D2 {
  float v, dx, dy;
};

inline D2 operator+(const D2& a, const D2& b) { return {a.v + b.v, a.dx + b.dx, a.dy + b.dy}; }
inline D2 operator-(const D2& a, const D2& b) { return {a.v - b.v, a.dx - b.dx, a.dy - b.dy}; }
inline D2 operator-(const D2& a) { return {-a.v, -a.dx, -a.dy}; }
inline D2 operator-(const D2& a, float b) { return {a.v - b, a.dx, a.dy}; }
inline D2 operator+(const D2& a, float b) { return {a.v + b, a.dx, a.dy}; }
inline D2 operator*(const D2& a, const D2& b) {
  return {a.v * b.v, a.v * b.dx + a.dx * b.v, a.v * b.dy + a.dy * b.v};
}
inline D2 operator*(float s, const D2& a) { return {a.v * s, a.dx * s, a.dy * s}; }

// A constant of the evaluation type (a Dual2 constant has zero derivatives).
template <class T> inline T cst(float c);
template <> inline float cst<float>(float c) { return c; }
template <> inline D2 cst<D2>(float c) { return {c, 0.0f, 0.0f}; }

inline float val(float x) { return x; }
inline float val(const D2& x) { return x.v; }

// t * t * t * (t * (t * 6 - 15) + 10)
template <class T> inline T fade(const T& t) {
  return t * t * t * (t * (t * cst<T>(6.0f) - cst<T>(15.0f)) + cst<T>(10.0f));
}

// OIIO::lerp: v0 * (1 - x) + v1 * x.
template <class T> inline T lerp(const T& v0, const T& v1, const T& x) {
  return v0 * (cst<T>(1.0f) - x) + v1 * x;
}

// OSL's gradient functions (negate_if / select forms).
template <class T> inline T neg_if(const T& x, bool c) { return c ? -x : x; }
template <class T> inline T grad(uint32_t hash, const T& x) {
  int h = int(hash & 15);
  float g = float(1 + (h & 7)); // 1, 2, .., 8
  if (h & 8) g = -g;            // random sign
  return g * x;
}
template <class T> inline T grad(uint32_t hash, const T& x, const T& y) {
  int h = int(hash & 7); // 8 directions (+-1,+-2) and (+-2,+-1)
  T u = h < 4 ? x : y;
  T v = 2.0f * (h < 4 ? y : x);
  return neg_if(u, h & 1) + neg_if(v, h & 2);
}
template <class T> inline T grad(uint32_t hash, const T& x, const T& y, const T& z) {
  int h = int(hash & 15); // the 12 cube edges (Perlin's improved noise)
  T u = h < 8 ? x : y;
  T v = h < 4 ? y : (h == 12 || h == 14) ? x : z;
  return neg_if(u, h & 1) + neg_if(v, h & 2);
}
template <class T> inline T grad(uint32_t hash, const T& x, const T& y, const T& z, const T& w) {
  int h = int(hash & 31); // the edges of the hypercube
  T u = h < 24 ? x : y;
  T v = h < 16 ? y : z;
  T s = h < 8 ? z : w;
  return neg_if(u, h & 1) + neg_if(v, h & 2) + neg_if(s, h & 4);
}

// Vector lanes for perlin_cell's value-only 3-D and 4-D cases (GCC/Clang vector extension).
typedef float F8 __attribute__((vector_size(32)));
typedef float F4 __attribute__((vector_size(16)));
typedef float F2 __attribute__((vector_size(8)));
using U8 = Lanes<8>::type;

// Lane b's offset along x, y and z from corner b of a cell's eight (bit k of b for axis k):
// f[k] - 1 where the bit is set, else f[k].
inline void corner_offsets(const float* f, F8* r) {
  U8 lane;
  lane_indices(lane, std::make_integer_sequence<uint32_t, 8>());
  for (int k = 0; k < 3; ++k) {
    F8 f0 = F8{} + f[k], f1 = F8{} + (f[k] - 1.0f);
    r[k] = ((lane >> k) & 1u) != 0u ? f1 : f0;
  }
}

// perlin_cell's interpolation of eight corner values: along z (g[i], g[i + 4]), then x, then y.
inline float lerp_zxy(const F8& g, const float* u) {
  F4 lo, hi;
  std::memcpy(&lo, &g, sizeof lo);
  std::memcpy(&hi, reinterpret_cast<const char*>(&g) + sizeof lo, sizeof hi);
  F4 m = lo * (F4{} + (1.0f - u[2])) + hi * (F4{} + u[2]);
  F2 a = {m[0], m[2]}, b = {m[1], m[3]};
  F2 xy = a * (F2{} + (1.0f - u[0])) + b * (F2{} + u[0]); // both y rows at once
  return xy[0] * (1.0f - u[1]) + xy[1] * u[1];
}

// The value-only 3-D case of perlin_cell below with one vector lane per corner: the same
// operations as the scalar code, lane by lane (grad's selects, then the z, x and y lerps), so
// the bits are the same. Left to the compiler, the scalar form was vectorised with partial
// vectors shuffled through the stack, one reload spanning two stores (perf: the costliest
// instructions of marble's noise).
inline void perlin3_lanes(const uint32_t* hashes, const float* f, const float* u, int nout,
                          float* out) {
  U8 hv;
  std::memcpy(&hv, hashes, sizeof hv);
  F8 r[3];
  corner_offsets(f, r);
  for (int j = 0; j < nout; ++j) {
    U8 hj = (hv >> (nout == 1 ? 0u : 8u * uint32_t(j))) & 15u;
    F8 gu = hj < 8u ? r[0] : r[1];
    F8 gv = hj < 4u ? r[1] : ((hj == 12u) | (hj == 14u)) ? r[0] : r[2];
    F8 g = ((hj & 1u) != 0u ? -gu : gu) + ((hj & 2u) != 0u ? -gv : gv);
    out[j] = 0.9820f * lerp_zxy(g, u);
  }
}

// The same for 4-D: two vectors of eight corners (w = 0, then w = 1), OSL's 4-D gradient
// selects, then on each w face z, x and y, then w (the value-only order).
inline void perlin4_lanes(const uint32_t* hashes, const float* f, const float* u, int nout,
                          float* out) {
  U8 hv[2];
  std::memcpy(&hv, hashes, sizeof hv);
  F8 r[3];
  corner_offsets(f, r);
  const float w[2] = {f[3], f[3] - 1.0f};
  for (int j = 0; j < nout; ++j) {
    float faces[2];
    for (int side = 0; side < 2; ++side) {
      U8 hj = (hv[side] >> (nout == 1 ? 0u : 8u * uint32_t(j))) & 31u;
      F8 rw = F8{} + w[side];
      F8 gu = hj < 24u ? r[0] : r[1];
      F8 gv = hj < 16u ? r[1] : r[2];
      F8 gs = hj < 8u ? r[2] : rw;
      F8 g = ((hj & 1u) != 0u ? -gu : gu) + ((hj & 2u) != 0u ? -gv : gv);
      g = g + ((hj & 4u) != 0u ? -gs : gs);
      faces[side] = lerp_zxy(g, u);
    }
    out[j] = 0.8344f * (faces[0] * (1.0f - u[3]) + faces[1] * u[3]);
  }
}

// OSL's perlin(): signed gradient noise, T = float (no derivatives) or D2, in N dimensions, for
// nout = 1 or 3 channels. The corner hash is OSL's HashScalar / HashVector (and the periodic
// variants): one inthash of the integer corner (wrapped by the period); channel j of a vector
// noise uses h >> (8 * j), so the hash of each corner is computed once for all channels.
// The interpolation order is that of OSL's SIMD (OIIO_SIMD) code, which is what OSL runs on
// x86: 1-D lerp; 2-D x then y; 3-D z, then x, then y; 4-D without derivatives: (z, x, y) on
// each w face, then w; 4-D with derivatives: w, then z, x, y. The corners are numbered with bit
// k for axis k. Every channel goes through the same operations in the same order as a scalar
// evaluation would, so the results are bit for bit those of one call per channel.
template <class T, int N>
inline __attribute__((always_inline)) void perlin_cell(const T* xin, const int* period, int nout,
                                                       T* out) {
  int X[N];
  T f[N], u[N];
  for (int k = 0; k < N; ++k) {
    X[k] = ifloor(val(xin[k])); // floorfrac: x - float(ifloor(x)); derivatives pass through
    f[k] = xin[k];
    if constexpr (std::is_same_v<T, D2>)
      f[k].v = xin[k].v - float(X[k]);
    else
      f[k] = xin[k] - float(X[k]);
    u[k] = fade(f[k]);
  }
  // The corner keys per axis: X and X + 1, or with a period p imod(X, p) and imod(X + 1, p),
  // one modulo per axis rather than per corner (X + 1 never overflows: lobe_noise_d passes
  // |x| < 2^31, so X is at most 2^31 - 128).
  uint32_t K0[N], K1[N];
  for (int k = 0; k < N; ++k) {
    if (period) {
      int w = imod(X[k], period[k]);
      K0[k] = uint32_t(w);
      K1[k] = uint32_t(w + 1 == period[k] ? 0 : w + 1);
    } else {
      K0[k] = uint32_t(X[k]);
      K1[k] = uint32_t(X[k]) + 1u;
    }
  }
  constexpr int kCorners = 1 << N;
  uint32_t h[kCorners];
  corner_hashes<N>(K0, K1, h);
  if constexpr (std::is_same_v<T, float> && N == 3) return perlin3_lanes(h, f, u, nout, out);
  if constexpr (std::is_same_v<T, float> && N == 4) return perlin4_lanes(h, f, u, nout, out);
  for (int j = 0; j < nout; ++j) {
    const int shift = nout == 1 ? 0 : 8 * j;
    T g[kCorners];
    for (int bits = 0; bits < kCorners; ++bits) {
      T r[N];
      for (int k = 0; k < N; ++k) r[k] = ((bits >> k) & 1) ? f[k] - 1.0f : f[k];
      uint32_t hj = h[bits] >> shift;
      if constexpr (N == 1)
        g[bits] = grad(hj, r[0]);
      else if constexpr (N == 2)
        g[bits] = grad(hj, r[0], r[1]);
      else if constexpr (N == 3)
        g[bits] = grad(hj, r[0], r[1], r[2]);
      else
        g[bits] = grad(hj, r[0], r[1], r[2], r[3]);
    }
    // x then y over the four (x, y) corners at v[0..3] (index = x + 2 y).
    auto xy = [&](const T* v) {
      return lerp(lerp(v[0], v[1], u[0]), lerp(v[2], v[3], u[0]), u[N > 1 ? 1 : 0]);
    };
    if constexpr (N == 1) {
      out[j] = 0.2500f * lerp(g[0], g[1], u[0]);
    } else if constexpr (N == 2) {
      out[j] = 0.6616f * xy(g);
    } else if constexpr (N == 3) {
      T m[4];
      for (int i = 0; i < 4; ++i) m[i] = lerp(g[i], g[i + 4], u[2]);
      out[j] = 0.9820f * xy(m);
    } else if constexpr (std::is_same_v<T, D2>) {
      T m[4];
      for (int i = 0; i < 4; ++i)
        m[i] = lerp(lerp(g[i], g[i + 8], u[3]), lerp(g[i + 4], g[i + 12], u[3]), u[2]);
      out[j] = 0.8344f * xy(m);
    } else {
      T m[4], m1[4];
      for (int i = 0; i < 4; ++i) {
        m[i] = lerp(g[i], g[i + 4], u[2]);
        m1[i] = lerp(g[i + 8], g[i + 12], u[2]);
      }
      out[j] = 0.8344f * lerp(xy(m), xy(m1), u[3]);
    }
  }
}

// Up to four noise inputs, passed by value. A variant that read its inputs through a pointer
// loaded neighbouring floats in one instruction, which the shader had stored one by one: a
// failed store-to-load forward, measured at about 20 ns of a 3-D simplex call's 67 (the same
// code fed by one vector store: 47 ns). By value they arrive in registers.
struct Inputs {
  float v[4];
};
inline Inputs inputs(const float* x, int n) {
  Inputs in{{0, 0, 0, 0}};
  for (int k = 0; k < n; ++k) in.v[k] = x[k];
  return in;
}

// The variants: value only (inputs by value) and with derivatives.
template <int N> LOBE_VARIANT void perlin_value(Inputs x, const int* period, int nout, float* out) {
  perlin_cell<float, N>(x.v, period, nout, out);
}
template <int N> LOBE_VARIANT void perlin_dual(const D2* x, const int* period, int nout, D2* out) {
  perlin_cell<D2, N>(x, period, nout, out);
}

template <int N> void perlin_n(const float* x, const int* period, int nout, float* out) {
  perlin_value<N>(inputs(x, N), period, nout, out);
}
template <int N> void perlin_n(const D2* x, const int* period, int nout, D2* out) {
  perlin_dual<N>(x, period, nout, out);
}
template <class T> void perlin(const T* xin, int n, const int* period, int nout, T* out) {
  switch (n) {
  case 1:
    return perlin_n<1>(xin, period, nout, out);
  case 2:
    return perlin_n<2>(xin, period, nout, out);
  case 3:
    return perlin_n<3>(xin, period, nout, out);
  default:
    return perlin_n<4>(xin, period, nout, out);
  }
}

// ---- Partials with respect to the (up to 4) inputs, for simplex noise ----

struct D {
  float v;
  float d[4];
};

inline D dconst(float v) { return D{v, {0, 0, 0, 0}}; }

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
  return lobe::math::lookup3_final(v0, v1, v2 ^ 0xdeadbeefu);
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
// The derivative is summed in OSL's (Gustavson's sdnoise1) order: -8 * (t0^3 g0 x0^2 + t1^3 g1
// x1^2) + (t0^4 g0 + t1^4 g1), times the scale; only when kPartials (the value is the same).
template <bool kPartials> LOBE_VARIANT D simplex1(float x, uint32_t seed) {
  int i0 = ifloor(x);
  float x0 = x - float(i0), x1 = x0 - 1.0f;
  float g[2], t[2], t2[2], t4[2], xx[2], n[2];
  for (int c = 0; c < 2; ++c) {
    float xc = c ? x1 : x0;
    uint32_t h = scramble(uint32_t(i0) + uint32_t(c), seed) & 15;
    // 1 + (h & 7), negated when h & 8: the sign bit set without a branch (a taken-or-not branch
    // on a hash bit is mispredicted half the time).
    g[c] = std::bit_cast<float>(std::bit_cast<uint32_t>(float(1 + (h & 7))) | (h & 8) << 28);
    xx[c] = xc * xc;
    t[c] = 1.0f - xx[c]; // |xc| <= 1, so t >= 0
    t2[c] = t[c] * t[c];
    t4[c] = t2[c] * t2[c];
    n[c] = t4[c] * g[c] * xc;
  }
  D r = dconst(0.36f * (n[0] + n[1]));
  if constexpr (kPartials) {
    float dn = t2[0] * t[0] * g[0] * xx[0];
    dn += t2[1] * t[1] * g[1] * xx[1];
    dn *= -8.0f;
    dn += t4[0] * g[0] + t4[1] * g[1];
    r.d[0] = dn * 0.36f;
  }
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
// N = 2..4, known at compile time (the loops over coordinates and corners unroll); the partials
// only when kPartials (the value is the same either way).
template <int N, bool kPartials> LOBE_VARIANT D simplex_n(Inputs in, uint32_t seed) {
  constexpr int n = N;
  const float* x = in.v;
  const SimplexDim& k = kSimplexDim[n - 2];
  float s = x[0];
  for (int a = 1; a < n; ++a) s += x[a];
  s *= k.F;
  int cell[4];
  uint32_t sum = 0; // wraps as x86 adds (a cell past the int range is INT_MIN)
  for (int a = 0; a < n; ++a) {
    cell[a] = ifloor(x[a] + s);
    sum += uint32_t(cell[a]);
  }
  float t = float(int32_t(sum)) * k.G, d0[4];
  for (int a = 0; a < n; ++a) d0[a] = x[a] - (float(cell[a]) - t);
  // rank[a]: how many offsets d0[a] exceeds. Ties go as in OSL (3-D: to the earlier coordinate,
  // 2-D and 4-D: to the later), so the same one of the simplices sharing the point is used.
  // Counted with constant indices (the loops unroll), so the ranks stay in registers: an
  // increment at a computed index kept them in memory, a chain of stores and reloads.
  int rank[4] = {0, 0, 0, 0};
  for (int a = 0; a < n; ++a)
    for (int b = a + 1; b < n; ++b) {
      int first = (n == 3 ? d0[a] >= d0[b] : d0[a] > d0[b]) ? 1 : 0;
      rank[a] += first;
      rank[b] += 1 - first;
    }
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
    // Outside this corner's support (or NaN): no value, and zero gradient and t^2, t^4 -- but
    // tc itself is kept in the derivative's t^2 * tc * (g . d) term, as in OSL, so that a
    // non-finite offset (a huge or NaN input) gives a NaN derivative there as OSL's does.
    static constexpr float kZero[4] = {0, 0, 0, 0};
    bool inside = tc >= 0.0f;
    const float* g = inside ? simplex_grad(corner, n, seed) : kZero;
    float dot = g[0] * d[0];
    for (int a = 1; a < n; ++a) dot += g[a] * d[a];
    float t2 = inside ? tc * tc : 0.0f, t4 = t2 * t2, t3dot = t2 * tc * dot;
    nc[c] = inside ? t4 * dot : 0.0f;
    if constexpr (kPartials)
      for (int a = 0; a < n; ++a) {
        dd[a] += t3dot * d[a];
        gt[a] += t4 * g[a];
      }
  }
  float total = nc[0];
  for (int c = 1; c <= n; ++c) total += nc[c];
  D r = dconst(k.scale * total);
  if constexpr (kPartials)
    for (int a = 0; a < n; ++a) r.d[a] = k.scale * (gt[a] - 8.0f * dd[a]);
  return r;
}

// With partials (the value-only forms are lobe_simplex_v1..v4, below).
D simplex_partials(const float* x, int n, uint32_t seed) {
  switch (n) {
  case 1:
    return simplex1<true>(x[0], seed);
  case 2:
    return simplex_n<2, true>(inputs(x, 2), seed);
  case 3:
    return simplex_n<3, true>(inputs(x, 3), seed);
  default:
    return simplex_n<4, true>(inputs(x, 4), seed);
  }
}

// ---- Simplex noise for W points at once (W = 4 or 8), value only ----
//
// simplex1<false> and simplex_n<N, false> lane by lane: the same operations in the same order on
// each lane (vector arithmetic rounds as scalar arithmetic does, and nothing is contracted), so
// each lane's bits are the scalar function's. Comparisons give lane masks (all ones or zero);
// the scalar code's selects are masks applied to the bits. The gradients are read per lane from
// the same tables.

// The helpers below pass vectors by value; they are inline and internal, never called across an
// ABI boundary, so the compilers' warning that AVX-sized vector arguments change the ABI when
// compiled without AVX does not apply.
#if defined(__clang__)
#pragma clang diagnostic ignored "-Wpsabi"
#elif defined(__GNUC__)
#pragma GCC diagnostic ignored "-Wpsabi"
#endif

// lookup3's final mix of lanes of words (a vector of uint32_t), lane by lane; returns c.
template <class U> inline U lookup3_final_lanes(U a, U b, U c) {
  lobe::math::lookup3_final_in_place(a, b, c);
  return c;
}

// The lane functions' loops (over corners and coordinates) unroll in full: rolled, their selects
// on the corner index became branches and their arrays stayed in memory (seen in the JIT's
// code for lobe_perlin_v3_x8).
#define LOBE_UNROLL _Pragma("GCC unroll 16")

// W lanes of floats, ints and words (the words are corner_hashes' Lanes).
template <int W> struct Wide {
  typedef float F __attribute__((vector_size(4 * W)));
  typedef int32_t I __attribute__((vector_size(4 * W)));
  typedef typename Lanes<W>::type U;
};

// to_int lane by lane: a NaN or a value outside the int range gives INT_MIN, as on x86 (the
// lane is zeroed before the conversion, which is then defined, and replaced after).
template <class F, class I> inline I to_int_lanes(F f) {
  I in = (f >= (F{} - 2147483648.0f)) & (f < (F{} + 2147483648.0f));
  I v = __builtin_convertvector((F)((I)f & in), I);
  return (v & in) | ((I{} + std::numeric_limits<int>::min()) & ~in);
}
template <class F, class I> inline I ifloor_lanes(F f) {
  for (int l = 0; l < int(sizeof(F) / 4); ++l) f[l] = std::floor(f[l]); // one rounding each
  return to_int_lanes<F, I>(f);
}

template <int W> inline void simplex1_lanes(const float* px, const uint32_t* pseed, float* out) {
  using F = typename Wide<W>::F;
  using I = typename Wide<W>::I;
  using U = typename Wide<W>::U;
  F x;
  U seed;
  std::memcpy(&x, px, sizeof x);
  std::memcpy(&seed, pseed, sizeof seed);
  I i0 = ifloor_lanes<F, I>(x);
  F x0 = x - __builtin_convertvector(i0, F), x1 = x0 - 1.0f;
  F n[2];
  LOBE_UNROLL
  for (int c = 0; c < 2; ++c) {
    F xc = c ? x1 : x0;
    U h = lookup3_final_lanes((U)i0 + uint32_t(c), seed, U{} + 0xdeadbeefu) & 15u;
    F g = (F)((U) __builtin_convertvector(1u + (h & 7u), F) | (h & 8u) << 28);
    F xx = xc * xc;
    F t = 1.0f - xx;
    F t2 = t * t;
    F t4 = t2 * t2;
    n[c] = t4 * g * xc;
  }
  F r = 0.36f * (n[0] + n[1]);
  std::memcpy(out, &r, sizeof r);
}

template <int N, int W>
inline void simplex_lanes(const float* px, const uint32_t* pseed, float* out) {
  using F = typename Wide<W>::F;
  using I = typename Wide<W>::I;
  using U = typename Wide<W>::U;
  constexpr int n = N;
  const SimplexDim& k = kSimplexDim[n - 2];
  F x[4];
  U seed;
  LOBE_UNROLL
  for (int a = 0; a < n; ++a) std::memcpy(&x[a], px + a * W, sizeof(F));
  std::memcpy(&seed, pseed, sizeof seed);
  F s = x[0];
  LOBE_UNROLL
  for (int a = 1; a < n; ++a) s += x[a];
  s *= k.F;
  I cell[4];
  U sum = U{}; // wraps, as the one-point sum
  LOBE_UNROLL
  for (int a = 0; a < n; ++a) {
    cell[a] = ifloor_lanes<F, I>(x[a] + s);
    sum += (U)cell[a];
  }
  F t = __builtin_convertvector((I)sum, F) * k.G, d0[4];
  LOBE_UNROLL
  for (int a = 0; a < n; ++a) d0[a] = x[a] - (__builtin_convertvector(cell[a], F) - t);
  I rank[4] = {I{}, I{}, I{}, I{}};
  LOBE_UNROLL
  for (int a = 0; a < n; ++a) {
    LOBE_UNROLL
    for (int b = a + 1; b < n; ++b) {
      I first = (n == 3 ? d0[a] >= d0[b] : d0[a] > d0[b]) & 1;
      rank[a] += first;
      rank[b] += 1 - first;
    }
  }
  F total = F{};
  LOBE_UNROLL
  for (int c = 0; c <= n; ++c) {
    U corner[4];
    F d[4], tc = F{} + 0.5f;
    LOBE_UNROLL
    for (int a = 0; a < n; ++a) {
      I step = (rank[a] >= n - c) & 1;
      corner[a] = (U)(cell[a] + step);
      d[a] = c == 0 ? d0[a] : d0[a] - __builtin_convertvector(step, F) + float(c) * k.G;
      tc -= d[a] * d[a];
    }
    I inside = tc >= 0.0f;
    U row;
    if constexpr (n == 2) {
      row = lookup3_final_lanes(corner[0], corner[1], seed ^ 0xdeadbeefu) & 7u;
    } else if constexpr (n == 3) {
      U inner = lookup3_final_lanes(corner[2], seed, U{} + 0xdeadbeefu);
      row = lookup3_final_lanes(corner[0], corner[1], inner ^ 0xdeadbeefu) & 15u;
    } else {
      U inner = lookup3_final_lanes(corner[2], corner[3], seed ^ 0xdeadbeefu);
      row = lookup3_final_lanes(corner[0], corner[1], inner ^ 0xdeadbeefu) & 31u;
    }
    float gl[4][W];
    LOBE_UNROLL
    for (int l = 0; l < W; ++l) {
      LOBE_UNROLL
      for (int a = 0; a < n; ++a)
        gl[a][l] = n == 2 ? kGrad2[row[l]][a] : n == 3 ? kGrad3[row[l]][a] : kGrad4[row[l]][a];
    }
    F g[4];
    LOBE_UNROLL
    for (int a = 0; a < n; ++a) std::memcpy(&g[a], gl[a], sizeof(F));
    F dot = g[0] * d[0];
    LOBE_UNROLL
    for (int a = 1; a < n; ++a) dot += g[a] * d[a];
    F t2 = tc * tc, t4 = t2 * t2;
    F nc = (F)((I)(t4 * dot) & inside); // +0 outside the corner's support, as the scalar code
    total = c == 0 ? nc : total + nc;
  }
  F r = k.scale * total;
  std::memcpy(out, &r, sizeof r);
}

// Gradient noise's lattice for W points: per coordinate k, the offset f from the cell's lower
// corner (x - floor(x)), f - 1, fade(f) and the lower corner's key, as perlin_cell computes them.
template <int N, int W>
inline void lattice_lanes(const float* px, typename Wide<W>::F* f, typename Wide<W>::F* f1,
                          typename Wide<W>::F* u, typename Wide<W>::U* k0) {
  using F = typename Wide<W>::F;
  using I = typename Wide<W>::I;
  using U = typename Wide<W>::U;
  LOBE_UNROLL
  for (int k = 0; k < N; ++k) {
    F x;
    std::memcpy(&x, px + k * W, sizeof x);
    I cell = ifloor_lanes<F, I>(x);
    f[k] = x - __builtin_convertvector(cell, F);
    f1[k] = f[k] - 1.0f;
    u[k] = f[k] * f[k] * f[k] * (f[k] * (f[k] * 6.0f - 15.0f) + 10.0f); // fade
    k0[k] = (U)cell;
  }
}

// perlin_cell<float, N> for N = 3 or 4 and C = 1 or 3 channels (perlin3_lanes' and
// perlin4_lanes' operations) for W points at once: x[k * W + l] is coordinate k of point l,
// out[j * W + l] channel j of point l. The 2^N corners are taken one after another, each
// across the W points; a corner's hash serves every channel (channel j of a vector noise reads
// it shifted by 8 j, as the one-point code).
template <int N, int C, int W> inline void perlin_points(const float* px, float* out) {
  using F = typename Wide<W>::F;
  using U = typename Wide<W>::U;
  F f[N], u[N], f1[N];
  U k0[N];
  lattice_lanes<N, W>(px, f, f1, u, k0);
  // The one-point code broadcasts the offsets and u[0], u[2] as 0 + value, which reads -0 as
  // +0: the same here (u[1] and u[3] enter its last lerps as they are).
  F f0[N], us[3] = {F{} + u[0], F{}, F{} + u[2]};
  LOBE_UNROLL
  for (int k = 0; k < N; ++k) f0[k] = F{} + f[k];
  constexpr int kCorners = 1 << N;
  constexpr uint32_t start = 0xdeadbeefu + (uint32_t(N) << 2) + 13u; // inthash of N words
  U h[kCorners];
  LOBE_UNROLL
  for (int c = 0; c < kCorners; ++c) {
    U key[N];
    LOBE_UNROLL
    for (int k = 0; k < N; ++k) key[k] = (c >> k) & 1 ? k0[k] + 1u : k0[k];
    U a = start + key[0], b = start + key[1], cc = start + key[2];
    if constexpr (N == 4) {
      lobe::math::lookup3_mix(a, b, cc);
      a += key[3];
    }
    h[c] = lookup3_final_lanes(a, b, cc);
  }
  // lerp_zxy on eight corner values: along z, then x (both y rows), then y.
  auto lerp_zxy = [&](const F* g, F& result) { // (a vector out, not returned: see -Wpsabi)
    F m[4];
    LOBE_UNROLL
    for (int i = 0; i < 4; ++i) m[i] = g[i] * (1.0f - u[2]) + g[i + 4] * us[2];
    F y0 = m[0] * (1.0f - u[0]) + m[1] * us[0], y1 = m[2] * (1.0f - u[0]) + m[3] * us[0];
    result = y0 * (1.0f - u[1]) + y1 * u[1];
  };
  LOBE_UNROLL
  for (int j = 0; j < C; ++j) {
    const uint32_t shift = C == 1 ? 0u : 8u * uint32_t(j);
    F face[2];
    LOBE_UNROLL
    for (int side = 0; side < (N == 4 ? 2 : 1); ++side) {
      F g[8];
      LOBE_UNROLL
      for (int c = 0; c < 8; ++c) {
        F r[3];
        LOBE_UNROLL
        for (int k = 0; k < 3; ++k) r[k] = (c >> k) & 1 ? f1[k] : f0[k];
        if constexpr (N == 3) {
          U hj = (h[c] >> shift) & 15u;
          F gu = hj < 8u ? r[0] : r[1];
          F gv = hj < 4u ? r[1] : ((hj == 12u) | (hj == 14u)) ? r[0] : r[2];
          g[c] = ((hj & 1u) != 0u ? -gu : gu) + ((hj & 2u) != 0u ? -gv : gv);
        } else {
          U hj = (h[c + 8 * side] >> shift) & 31u;
          F rw = side ? f1[3] : f0[3];
          F gu = hj < 24u ? r[0] : r[1];
          F gv = hj < 16u ? r[1] : r[2];
          F gs = hj < 8u ? r[2] : rw;
          g[c] = ((hj & 1u) != 0u ? -gu : gu) + ((hj & 2u) != 0u ? -gv : gv);
          g[c] = g[c] + ((hj & 4u) != 0u ? -gs : gs);
        }
      }
      lerp_zxy(g, face[side]);
    }
    F r;
    if constexpr (N == 3)
      r = 0.9820f * face[0];
    else
      r = 0.8344f * (face[0] * (1.0f - u[3]) + face[1] * u[3]);
    std::memcpy(out + j * W, &r, sizeof r);
  }
}

// perlin_cell<float, 2> with C = 1 or 3 channels (its generic path: x then y) for W points at
// once, in the layout of perlin_points.
template <int C, int W> inline void perlin2_points(const float* px, float* out) {
  using F = typename Wide<W>::F;
  using U = typename Wide<W>::U;
  F f[2], f1[2], u[2];
  U k0[2];
  lattice_lanes<2, W>(px, f, f1, u, k0);
  constexpr uint32_t start = 0xdeadbeefu + (2u << 2) + 13u; // inthash of two words
  U h[4];
  LOBE_UNROLL
  for (int c = 0; c < 4; ++c) {
    U a = start + (c & 1 ? k0[0] + 1u : k0[0]), b = start + (c & 2 ? k0[1] + 1u : k0[1]);
    h[c] = lookup3_final_lanes(a, b, U{} + start);
  }
  LOBE_UNROLL
  for (int j = 0; j < C; ++j) {
    const uint32_t shift = C == 1 ? 0u : 8u * uint32_t(j);
    F g[4];
    LOBE_UNROLL
    for (int c = 0; c < 4; ++c) {
      U hj = (h[c] >> shift) & 7u;
      F r0 = c & 1 ? f1[0] : f[0], r1 = c & 2 ? f1[1] : f[1];
      F gu = hj < 4u ? r0 : r1;
      F gv = 2.0f * (hj < 4u ? r1 : r0);
      g[c] = ((hj & 1u) != 0u ? -gu : gu) + ((hj & 2u) != 0u ? -gv : gv);
    }
    F y0 = g[0] * (1.0f - u[0]) + g[1] * u[0], y1 = g[2] * (1.0f - u[0]) + g[3] * u[0];
    F r = 0.6616f * (y0 * (1.0f - u[1]) + y1 * u[1]);
    std::memcpy(out + j * W, &r, sizeof r);
  }
}

// One form for the W-point functions of each family: N coordinates, C channels, W lanes.
template <int N, int C, int W>
inline void perlin_form(const float* x, const uint32_t* /*seed*/, float* out) {
  if constexpr (N == 2)
    perlin2_points<C, W>(x, out);
  else
    perlin_points<N, C, W>(x, out);
}
template <int N, int W> inline void simplex_form(const float* x, const uint32_t* seed, float* out) {
  if constexpr (N == 1)
    simplex1_lanes<W>(x, seed, out);
  else
    simplex_lanes<N, W>(x, seed, out);
}

// Gradient noise at one point, one channel or three (lane 3 zero).
template <int N> inline float perlin_one(Inputs in) {
  float r;
  perlin_value<N>(in, nullptr, 1, &r);
  return r;
}
template <int N> inline lobe_float4 perlin_one3(Inputs in) {
  float r[3];
  perlin_value<N>(in, nullptr, 3, r);
  return lobe_float4{r[0], r[1], r[2], 0.0f};
}

} // namespace

extern "C" {

// Simplex noise, value only, at one point (1 to 4 coordinates) and for W = 4 or 8 points at
// once (x[a * W + l]: coordinate a of point l; seed[l]: point l's channel; out[l]), each lane
// the one-point function's bits. In bitcode builds the one-point functions stay calls through
// the JIT's -O2 pipeline, which then gathers independent calls into the W-point ones
// (runtime/jit/noise_batch.h) and inlines what is left.
LOBE_BATCHABLE float lobe_simplex_v1(float x, uint32_t seed) { return simplex1<false>(x, seed).v; }
LOBE_BATCHABLE float lobe_simplex_v2(float x, float y, uint32_t seed) {
  return simplex_n<2, false>(Inputs{{x, y, 0, 0}}, seed).v;
}
LOBE_BATCHABLE float lobe_simplex_v3(float x, float y, float z, uint32_t seed) {
  return simplex_n<3, false>(Inputs{{x, y, z, 0}}, seed).v;
}
LOBE_BATCHABLE float lobe_simplex_v4(float x, float y, float z, float w, uint32_t seed) {
  return simplex_n<4, false>(Inputs{{x, y, z, w}}, seed).v;
}
// Signed gradient noise of two to four coordinates, value only, not periodic, one channel
// (v2, v3, v4) or three (v2c, v3c, v4c: channels in lanes 0-2, lane 3 zero): one point
// (perlin_cell) and W points (`seed` is unused: the W-point functions share one form;
// out[j * W + l]).
LOBE_BATCHABLE float lobe_perlin_v2(float x, float y) { return perlin_one<2>({{x, y, 0, 0}}); }
LOBE_BATCHABLE lobe_float4 lobe_perlin_v2c(float x, float y) {
  return perlin_one3<2>({{x, y, 0, 0}});
}
LOBE_BATCHABLE float lobe_perlin_v3(float x, float y, float z) {
  return perlin_one<3>({{x, y, z, 0}});
}
LOBE_BATCHABLE lobe_float4 lobe_perlin_v3c(float x, float y, float z) {
  return perlin_one3<3>({{x, y, z, 0}});
}
LOBE_BATCHABLE float lobe_perlin_v4(float x, float y, float z, float w) {
  return perlin_one<4>({{x, y, z, w}});
}
LOBE_BATCHABLE lobe_float4 lobe_perlin_v4c(float x, float y, float z, float w) {
  return perlin_one3<4>({{x, y, z, w}});
}

// The W-point forms, name_x4 and name_x8.
#define LOBE_WIDE_FORMS(name, form, ...)                                                           \
  void name##_x4(const float* x, const uint32_t* seed, float* out) {                               \
    form<__VA_ARGS__, 4>(x, seed, out);                                                            \
  }                                                                                                \
  void name##_x8(const float* x, const uint32_t* seed, float* out) {                               \
    form<__VA_ARGS__, 8>(x, seed, out);                                                            \
  }
LOBE_WIDE_FORMS(lobe_perlin_v2, perlin_form, 2, 1)
LOBE_WIDE_FORMS(lobe_perlin_v2c, perlin_form, 2, 3)
LOBE_WIDE_FORMS(lobe_perlin_v3, perlin_form, 3, 1)
LOBE_WIDE_FORMS(lobe_perlin_v3c, perlin_form, 3, 3)
LOBE_WIDE_FORMS(lobe_perlin_v4, perlin_form, 4, 1)
LOBE_WIDE_FORMS(lobe_perlin_v4c, perlin_form, 4, 3)
LOBE_WIDE_FORMS(lobe_simplex_v1, simplex_form, 1)
LOBE_WIDE_FORMS(lobe_simplex_v2, simplex_form, 2)
LOBE_WIDE_FORMS(lobe_simplex_v3, simplex_form, 3)
LOBE_WIDE_FORMS(lobe_simplex_v4, simplex_form, 4)
#undef LOBE_WIDE_FORMS

} // extern "C"

namespace {
// Value-only simplex noise of n = 1..4 coordinates.
float simplex_value(const float* x, int n, uint32_t seed) {
  switch (n) {
  case 1:
    return lobe_simplex_v1(x[0], seed);
  case 2:
    return lobe_simplex_v2(x[0], x[1], seed);
  case 3:
    return lobe_simplex_v3(x[0], x[1], x[2], seed);
  default:
    return lobe_simplex_v4(x[0], x[1], x[2], x[3], seed);
  }
}
} // namespace

extern "C" {

// out[nout] = noise of `kind` at x[nin] (optionally periodic), evaluated as OSL does. With dx
// null, OSL's value-only code path; otherwise dx[nin] and dy[nin] are the inputs' screen
// derivatives (zeros where an input has none) and odx[nout] / ody[nout] receive the result's,
// computed as OSL's Dual2 code path (whose value can differ from the value-only one in the last
// bits: 4-D perlin interpolates in another order). Call with derivatives exactly when the result
// needs them, as OSL does.
void lobe_noise_d(int kind, const float* x, const float* dx, const float* dy, int nin,
                  const float* period, float* out, float* odx, float* ody, int nout) {
  using namespace lobe::shadeops;
  bool simplex_kind = kind == kSimplex || kind == kUSimplex;
  bool unsigned_kind = kind == kUPerlin || kind == kUSimplex;
  // Lobe keeps gradient and simplex noise finite and in range for every input, where OSL's is
  // inf or garbage beyond the int range and for inf/NaN: such a coordinate reads as 0, with no
  // derivative (a deliberate difference, docs/language.md). Everything smaller matches OSL.
  // The inputs are taken as values (Inputs): choosing between the caller's array and a safe
  // copy by pointer kept them in memory, stored one by one and reloaded two at a time (a failed
  // store-to-load forward on every call).
  // Selects, not branches: a shader's noise calls then stay in one basic block, where the JIT
  // can gather independent ones (runtime/jit/noise_batch.h).
  Inputs xin = inputs(x, nin);
  x = xin.v;
  float sdx[4], sdy[4];
  if (kind != kCell && kind != kHash) {
    for (int k = 0; k < nin; ++k) {
      bool ok = std::fabs(xin.v[k]) < 2147483648.0f;
      xin.v[k] = ok ? xin.v[k] : 0.0f;
      if (dx) {
        sdx[k] = ok ? dx[k] : 0.0f;
        sdy[k] = ok && dy ? dy[k] : 0.0f;
      }
    }
    if (dx) dx = sdx, dy = sdy;
  }
  if (kind == kPerlin || kind == kUPerlin) {
    // Simplex noise has no periodic form (OSL has none; the name dispatch rejects
    // pnoise("simplex")), so `period` only applies to gradient and cell/hash noise.
    int per[4];
    if (period)
      for (int k = 0; k < nin; ++k) per[k] = period_of(period[k]);
    if (dx) {
      D2 in[4], r[3];
      for (int k = 0; k < nin; ++k) in[k] = D2{x[k], dx[k], dy[k]};
      perlin(in, nin, period ? per : nullptr, nout, r);
      for (int j = 0; j < nout; ++j) {
        if (unsigned_kind) r[j] = 0.5f * (r[j] + 1.0f);
        out[j] = r[j].v;
        odx[j] = r[j].dx;
        ody[j] = r[j].dy;
      }
    } else {
      float r[3];
      if (period || nin < 2) {
        perlin(x, nin, period ? per : nullptr, nout, r);
      } else if (nout == 1) {
        r[0] = nin == 2   ? lobe_perlin_v2(x[0], x[1])
               : nin == 3 ? lobe_perlin_v3(x[0], x[1], x[2])
                          : lobe_perlin_v4(x[0], x[1], x[2], x[3]);
      } else {
        lobe_float4 v = nin == 2   ? lobe_perlin_v2c(x[0], x[1])
                        : nin == 3 ? lobe_perlin_v3c(x[0], x[1], x[2])
                                   : lobe_perlin_v4c(x[0], x[1], x[2], x[3]);
        r[0] = v[0], r[1] = v[1], r[2] = v[2];
      }
      for (int j = 0; j < nout; ++j) out[j] = unsigned_kind ? 0.5f * (r[j] + 1.0f) : r[j];
    }
    return;
  }
  if (simplex_kind) {
    for (int j = 0; j < nout; ++j) {
      if (!dx) {
        float v = simplex_value(x, nin, uint32_t(j));
        out[j] = unsigned_kind ? 0.5f * (v + 1.0f) : v; // OSL's usimplex: 0.5 * (n + 1)
        continue;
      }
      D r = simplex_partials(x, nin, uint32_t(j));
      if (unsigned_kind) { // OSL's usimplex: 0.5 * (n + 1), partials times 0.5
        r.v = 0.5f * (r.v + 1.0f);
        for (int k = 0; k < nin; ++k) r.d[k] *= 0.5f;
      }
      out[j] = r.v;
      if (dx) { // OSL's chain rule: dn/dx0 * x0' + dn/dx1 * x1' + ...
        float sx = r.d[0] * dx[0], sy = r.d[0] * dy[0];
        for (int k = 1; k < nin; ++k) {
          sx = sx + r.d[k] * dx[k];
          sy = sy + r.d[k] * dy[k];
        }
        odx[j] = sx;
        ody[j] = sy;
      }
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
    if (dx) odx[j] = ody[j] = 0;
  }
}

// The partials form: grad, if non-null, receives d out[j] / d x[k] at grad[j * nin + k]
// (the Dual2 path seeded with unit derivatives, two inputs at a time).
void lobe_noise(int kind, const float* x, int nin, const float* period, float* out, int nout,
                float* grad) {
  if (!grad)
    return lobe_noise_d(kind, x, nullptr, nullptr, nin, period, out, nullptr, nullptr, nout);
  float ox[3], oy[3];
  for (int k0 = 0; k0 < nin; k0 += 2) {
    float sx[4] = {0, 0, 0, 0}, sy[4] = {0, 0, 0, 0};
    sx[k0] = 1;
    if (k0 + 1 < nin) sy[k0 + 1] = 1;
    lobe_noise_d(kind, x, sx, sy, nin, period, out, ox, oy, nout);
    for (int j = 0; j < nout; ++j) {
      grad[j * nin + k0] = ox[j];
      if (k0 + 1 < nin) grad[j * nin + k0 + 1] = oy[j];
    }
  }
}

// noise(name, ...) with a name known only at run time (OSL's genericnoise / genericpnoise):
// dispatches on the name like the constant case in codegen. An unknown name, or
// "simplex"/"usimplex" with a period, is a run-time error, as OSL words it: `[periodic ]noise
// type "x" is unknown, called from (file:line)` for a name that is a constant,
// `Unknown noise type "x"` (file null) for one known only while shading; the result (and its
// derivatives) is 0. "gabor" goes to lobe_gabor (gabor.cpp) with the call's
// keyword options (null: the defaults).
void lobe_noise_named_d(lobe::ShaderGlobals* sg, const char* name, const float* x, const float* dx,
                        const float* dy, int nin, const float* period, const void* gabor_opts,
                        float* out, float* odx, float* ody, int nout, const char* file, int line) {
  std::string_view n = name ? name : "";
  if (n == "gabor")
    return lobe_gabor(x, dx, dy, nin, period,
                      static_cast<const lobe::shadeops::GaborOptions*>(gabor_opts), out, odx, ody,
                      nout);
  int kind = lobe::shadeops::noise_kind_from_name(n, period != nullptr);
  if (kind >= 0) return lobe_noise_d(kind, x, dx, dy, nin, period, out, odx, ody, nout);
  for (int j = 0; j < nout; ++j) {
    out[j] = 0;
    if (dx) odx[j] = ody[j] = 0;
  }
  if (sg && sg->context) { // OSL's words: a constant name's error has the place
    if (file)
      sg->context->error(std::string(period ? "periodic " : "") + "noise type \"" + std::string(n) +
                         "\" is unknown, called from (" + file + ":" + std::to_string(line) + ")");
    else
      sg->context->error("Unknown noise type \"" + std::string(n) + "\"");
  }
}

// The partials form of lobe_noise_named.
void lobe_noise_named(lobe::ShaderGlobals* sg, const char* name, const float* x, int nin,
                      const float* period, float* out, int nout, float* grad, const char* file,
                      int line) {
  std::string_view n = name ? name : "";
  int kind = lobe::shadeops::noise_kind_from_name(n, period != nullptr);
  if (kind >= 0) return lobe_noise(kind, x, nin, period, out, nout, grad);
  lobe_noise_named_d(sg, name, x, nullptr, nullptr, nin, period, nullptr, out, nullptr, nullptr,
                     nout, file, line);
  if (grad)
    for (int k = 0; k < nout * nin; ++k) grad[k] = 0;
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
