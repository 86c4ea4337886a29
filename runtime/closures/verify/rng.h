// Deterministic random numbers for the verification harness: PCG32 (O'Neill 2014), so every
// statistical test draws the same samples on every machine and compiler (fixed seeds).
#pragma once

#include "lobe/vec.h"

#include <cmath>
#include <cstdint>

namespace lobe::verify {

class Pcg32 {
public:
  explicit Pcg32(uint64_t seed, uint64_t stream = 0x853c49e6748fea9bULL) {
    inc_ = (stream << 1u) | 1u;
    next_u32();
    state_ += seed;
    next_u32();
  }

  uint32_t next_u32() {
    uint64_t old = state_;
    state_ = old * 6364136223846793005ULL + inc_;
    auto xorshifted = static_cast<uint32_t>(((old >> 18u) ^ old) >> 27u);
    auto rot = static_cast<uint32_t>(old >> 59u);
    return (xorshifted >> rot) | (xorshifted << ((-rot) & 31));
  }

  // Uniform in [0, 1): the top 24 bits, so 1 - 2^-24 is the largest value (exactly representable).
  float next_float() { return static_cast<float>(next_u32() >> 8) * 0x1p-24f; }
  double next_double() { return static_cast<double>(next_u32()) * 0x1p-32; }
  Vec3 next_vec3() { return {next_float(), next_float(), next_float()}; }

private:
  uint64_t state_ = 0;
  uint64_t inc_ = 0;
};

// Uniformly distributed direction on the unit sphere (Archimedes: z uniform in [-1, 1]).
inline Vec3 uniform_sphere(double u1, double u2) {
  double z = 1.0 - 2.0 * u1;
  double r = std::sqrt(std::fmax(0.0, 1.0 - z * z));
  double phi = 2.0 * M_PI * u2;
  return {static_cast<float>(r * std::cos(phi)), static_cast<float>(r * std::sin(phi)),
          static_cast<float>(z)};
}

// Direction at polar angle theta (from +z) in the x-z plane on the side of +x ("incident").
inline Vec3 direction_at(double theta, double phi = 0.0) {
  double s = std::sin(theta);
  return {static_cast<float>(s * std::cos(phi)), static_cast<float>(s * std::sin(phi)),
          static_cast<float>(std::cos(theta))};
}

} // namespace lobe::verify
