// Random numbers and warps for the path tracer.
//
// Determinism: every random number of a path is a pure function of (pixel index, sample
// index, seed, dimension counter), hashed with a 64-bit finaliser (SplitMix64-style). Nothing
// depends on which thread ran the pixel, so images are bit-identical across thread counts.
#pragma once

#include "lobe/vec.h"

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

// A counter-based stream: the n-th number of stream (pixel, sample, seed).
class Sampler {
public:
  Sampler(uint64_t pixel, uint64_t sample, uint64_t seed)
      : key_(mix64(mix64(pixel * 0x9e3779b97f4a7c15ull + seed) ^
                   (sample * 0xd1b54a32d192ed03ull))) {}
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

// Concentric map of the unit square to the unit disk (Shirley and Chiu).
inline void square_to_disk(float u1, float u2, float& x, float& y) {
  float a = 2 * u1 - 1, b = 2 * u2 - 1;
  if (a == 0 && b == 0) {
    x = y = 0;
    return;
  }
  float r, phi;
  if (std::abs(a) > std::abs(b))
    r = a, phi = (kPi / 4) * (b / a);
  else
    r = b, phi = kPi / 2 - (kPi / 4) * (a / b);
  x = r * std::cos(phi);
  y = r * std::sin(phi);
}

// Cosine-weighted direction on the hemisphere around +Z (Malley's method); pdf z / pi.
inline Vec3 square_to_cosine_hemisphere(float u1, float u2) {
  float x, y;
  square_to_disk(u1, u2, x, y);
  return {x, y, std::sqrt(std::max(0.0f, 1 - x * x - y * y))};
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
