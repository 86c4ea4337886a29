// Random numbers and warps for the path tracer.
//
// Paths draw Owen-scrambled Sobol numbers (Sampler); tests and set-up draw independent
// uniforms (RandomStream). Both are pure functions of their indices and seed, so nothing
// depends on which thread ran a pixel: images are bit-identical across thread counts.
#pragma once

#include "lobe/vec.h"
#include "lobe/warp.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace lobe::render {

inline constexpr float kPi = 3.14159265358979323846f;
inline constexpr float kInvPi = 0.31830988618379067154f;

inline uint64_t mix64(uint64_t z) {
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}

// A counter-based stream of independent uniforms: the n-th number of stream (index, sub, seed).
// For tests and set-up work that wants plain random numbers; paths use Sampler below.
class RandomStream {
public:
  RandomStream(uint64_t index, uint64_t sub, uint64_t seed)
      : key_(mix64(mix64(index * 0x9e3779b97f4a7c15ull + seed) ^ (sub * 0xd1b54a32d192ed03ull))) {}
  // Uniform in [0, 1): 24 random bits, so 1 is never returned.
  float next() {
    uint64_t h = mix64(key_ + (counter_++) * 0x9e3779b97f4a7c15ull);
    return float(h >> 40) * 0x1p-24f;
  }
  Vec3 next3() {
    float a = next(), b = next();
    return {a, b, next()};
  }

private:
  uint64_t key_;
  uint64_t counter_ = 0;
};

namespace sobol {

// Generator matrices of the first four Sobol dimensions as 32 column vectors each (bit 31 is
// 1/2), built from Joe and Kuo's primitive polynomials and initial numbers: dimension 0 is van
// der Corput's; 1: degree 1, m = {1}; 2: x^2 + x + 1, m = {1, 3}; 3: x^3 + x + 1, m = {1, 3, 1}.
struct Matrices {
  uint32_t v[4][32];
};
constexpr Matrices make_matrices() {
  Matrices m{};
  constexpr int degree[4] = {0, 1, 2, 3};
  constexpr uint32_t poly[4] = {0, 0, 1, 1}; // inner coefficients a (x^s and 1 implied)
  constexpr uint32_t init[4][3] = {{0, 0, 0}, {1, 0, 0}, {1, 3, 0}, {1, 3, 1}};
  for (int i = 0; i < 32; ++i) m.v[0][i] = 1u << (31 - i);
  for (int d = 1; d < 4; ++d) {
    const int s = degree[d];
    for (int i = 0; i < 32; ++i) {
      if (i < s) {
        m.v[d][i] = init[d][i] << (31 - i);
        continue;
      }
      uint32_t x = m.v[d][i - s] ^ (m.v[d][i - s] >> s);
      for (int k = 1; k < s; ++k)
        if ((poly[d] >> (s - 1 - k)) & 1) x ^= m.v[d][i - k];
      m.v[d][i] = x;
    }
  }
  return m;
}
inline constexpr Matrices kMatrices = make_matrices();

// The matrices applied a byte of the index at a time: kBytes.t[dim][k][b] is the point of
// index b << 8k (16 kB; a point is three or four lookups instead of a loop over 32 bits).
struct ByteTables {
  uint32_t t[4][4][256];
};
constexpr ByteTables make_byte_tables() {
  ByteTables bt{};
  for (int d = 0; d < 4; ++d)
    for (int k = 0; k < 4; ++k)
      for (int b = 0; b < 256; ++b) {
        uint32_t x = 0;
        for (int i = 0; i < 8; ++i)
          if ((b >> i) & 1) x ^= kMatrices.v[d][8 * k + i];
        bt.t[d][k][b] = x;
      }
  return bt;
}
inline constexpr ByteTables kBytes = make_byte_tables();

// Point `index` of Sobol dimension `dim` (< 4) as 32 bits of a fraction.
inline uint32_t point(uint32_t index, int dim) {
  const auto& t = kBytes.t[dim];
  return t[0][index & 0xff] ^ t[1][(index >> 8) & 0xff] ^ t[2][(index >> 16) & 0xff] ^
         t[3][index >> 24];
}

constexpr uint32_t reverse_bits(uint32_t x) {
  x = ((x >> 1) & 0x55555555u) | ((x & 0x55555555u) << 1);
  x = ((x >> 2) & 0x33333333u) | ((x & 0x33333333u) << 2);
  x = ((x >> 4) & 0x0f0f0f0fu) | ((x & 0x0f0f0f0fu) << 4);
  return __builtin_bswap32(x);
}

// The same points in the bit-reversed domain: point_reversed(y, dim) is
// reverse_bits(point(reverse_bits(y), dim)). Byte k of y is byte 3 - k of the index, its bits
// in reverse order; the columns' XOR commutes with the reversal. Sampler works here so that a
// group of numbers reverses bits once per number instead of four times.
constexpr ByteTables make_reversed_byte_tables() {
  ByteTables bt{};
  for (int d = 0; d < 4; ++d)
    for (int k = 0; k < 4; ++k)
      for (uint32_t b = 0; b < 256; ++b)
        bt.t[d][k][b] = reverse_bits(kBytes.t[d][3 - k][reverse_bits(b) >> 24]);
  return bt;
}
inline constexpr ByteTables kBytesReversed = make_reversed_byte_tables();

inline uint32_t point_reversed(uint32_t y, int dim) {
  const auto& t = kBytesReversed.t[dim];
  return t[0][y & 0xff] ^ t[1][(y >> 8) & 0xff] ^ t[2][(y >> 16) & 0xff] ^ t[3][y >> 24];
}

// Owen scrambling by hashing (Burley, "Practical Hash-based Owen Scrambling", JCGT 2020): a
// Laine-Karras style hash on the bit-reversed value, in which a bit changes only bits below it
// (after reversal: only finer digits), is a nested uniform scramble of the fraction. A
// bijection on 32-bit values that maps every aligned block of 2^k values onto one.
// scramble_reversed is the hash itself, on and to bit-reversed values.
inline uint32_t scramble_reversed(uint32_t x, uint32_t seed) {
  x += seed;
  x ^= x * 0x6c50b47cu;
  x ^= x * 0xb82f1e52u;
  x ^= x * 0xc7afe638u;
  x ^= x * 0x8d22f6e6u;
  return x;
}
inline uint32_t owen_scramble(uint32_t x, uint32_t seed) {
  return reverse_bits(scramble_reversed(reverse_bits(x), seed));
}

} // namespace sobol

// The numbers of one path sample: Owen-scrambled Sobol points, padded (Burley 2020). Numbers
// come in groups of 1 to 3 dimensions; group g is the first dimensions of the Sobol sequence at
// the sample index shuffled by the group's own scramble, each dimension then scrambled with its
// own seed. So the `spp` samples of a pixel are stratified in every group (the first 2^k
// samples of a 2-D group put one point in each of 2^k elementary intervals of every shape),
// and groups are decorrelated from each other and from other pixels.
// Determinism: every number is a pure function of (pixel, sample index, seed, group), so images
// are bit-identical across thread counts.
// The path tracer gives each use its own group (a fixed layout per path vertex, PathTracer), so
// a use is stratified over a pixel's samples even when other uses are skipped; next(),
// next2() and next3() take groups 1, 2, 3, ... in turn.
class Sampler {
public:
  Sampler(uint64_t pixel, uint64_t sample, uint64_t seed)
      : key_(mix64(pixel * 0x9e3779b97f4a7c15ull + mix64(seed))),
        index_reversed_(sobol::reverse_bits(static_cast<uint32_t>(sample))) {}
  // Uniform in [0, 1) (24 bits, so 1 is never returned).
  float next() {
    float u[1];
    groups<1>(++counter_, {1}, u);
    return u[0];
  }
  void next2(float& a, float& b) {
    float u[2];
    groups<1>(++counter_, {2}, u);
    a = u[0], b = u[1];
  }
  Vec3 next3() {
    float u[3];
    groups<1>(++counter_, {3}, u);
    return {u[0], u[1], u[2]};
  }

  // The numbers of groups first, first + 1, ..., first + K - 1, dims[k] (1 to 3) of group k,
  // written to `out` one group after another. Computed together: the groups' hash chains are
  // independent and overlap in the processor, where drawn one group at a time each waits out
  // its chain's latency (a path's numbers are about 5% of the 524k-triangle bench scene's
  // render; drawn together it renders 1-2% faster). Number d of group g is
  // owen_scramble(point(owen_scramble(index, lo32(h)), d),
  // seed_d) with h = mix64(key + g C), seed_0 = hi32(h) and seed_d = hi32(mix64(h + d)) after
  // it; worked in the bit-reversed domain (sobol::point_reversed), one reversal a number.
  template <int K> void groups(uint64_t first, const int (&dims)[K], float* out) const {
    uint64_t h[K];
    uint32_t shuffled[K];
    for (int k = 0; k < K; ++k) {
      h[k] = mix64(key_ + (first + uint64_t(k)) * 0xd1b54a32d192ed03ull);
      shuffled[k] = sobol::scramble_reversed(index_reversed_, static_cast<uint32_t>(h[k]));
    }
    for (int k = 0; k < K; ++k)
      for (int d = 0; d < 3; ++d) {
        if (d >= dims[k]) break;
        uint32_t seed = static_cast<uint32_t>((d == 0 ? h[k] : mix64(h[k] + uint64_t(d))) >> 32);
        uint32_t x = sobol::scramble_reversed(sobol::point_reversed(shuffled[k], d), seed);
        *out++ = float(sobol::reverse_bits(x) >> 8) * 0x1p-24f;
      }
  }

private:
  uint64_t key_;
  uint32_t index_reversed_;
  uint64_t counter_ = 0;
};

// Orthonormal basis around n (Duff et al. 2017, branchless).
struct Frame {
  Vec3 t, b, n;
  explicit Frame(const Vec3& nn) : n(nn) {
    float s = std::copysign(1.0f, n.z);
    float a = -1.0f / (s + n.z), c = n.x * n.y * a;
    t = {1.0f + s * n.x * n.x * a, s * c, -s * n.x};
    b = {c, s + n.y * n.y * a, -n.y};
  }
  Vec3 to_world(const Vec3& v) const { return t * v.x + b * v.y + n * v.z; }
};

inline Vec3 square_to_uniform_sphere(float u1, float u2) {
  float z = 1 - 2 * u1, r = std::sqrt(std::max(0.0f, 1 - z * z)), phi = 2 * kPi * u2;
  return {r * std::cos(phi), r * std::sin(phi), z};
}

// Uniform direction in the cone around +Z with cos(half-angle) = cos_max; pdf 1/(2pi(1-cos_max)).
inline Vec3 square_to_uniform_cone(float u1, float u2, float cos_max) {
  float z = 1 - u1 * (1 - cos_max), r = std::sqrt(std::max(0.0f, 1 - z * z)), phi = 2 * kPi * u2;
  return {r * std::cos(phi), r * std::sin(phi), z};
}

// atan2 in float to within 3e-7 radians (glibc's atan2f goes through atanf: about a tenth of
// the Cornell box's light sampling). The angle reduced to the octant's |t| <= tan(pi/8) (past
// it, atan(a) = pi/4 + atan((a - 1) / (a + 1))), there t P(t^2) with P of degree 4: the
// least-squares fit of atan(t) / t at 4000 Chebyshev nodes of t^2 in [0, tan^2(pi/8)], whose
// error in float is 3.6e-8 on that interval. Zero, infinite and NaN arguments go to std::atan2.
inline float fast_atan2(float y, float x) {
  const float ax = std::abs(x), ay = std::abs(y);
  const float hi = std::max(ax, ay), lo = std::min(ax, ay);
  if (const float sum = ax + ay; !(sum > 0) || !(sum < INFINITY)) return std::atan2(y, x);
  constexpr float kPiF = 3.14159265358979f, kTanPi8 = 0.414213562373095f;
  const float a = lo / hi; // in [0, 1]
  const bool past = a > kTanPi8;
  const float t = past ? (a - 1) / (a + 1) : a, s = t * t;
  float r = t * ((((0.0798496291f * s - 0.138514784f) * s + 0.199744048f) * s - 0.333327969f) * s +
                 0.999999982f);
  if (past) r += kPiF / 4;
  if (ay > ax) r = kPiF / 2 - r;
  if (x < 0) r = kPiF - r;
  return std::copysign(r, y);
}

// Power heuristic (beta = 2) for the strategy with pdf `a` against one with pdf `b`.
inline float power_heuristic(float a, float b) {
  if (!(a > 0)) return 0;
  if (std::isinf(a)) return 1;
  float a2 = a * a, b2 = b * b;
  return a2 / (a2 + b2);
}

inline float luminance(const Vec3& c) { return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z; }

} // namespace lobe::render
