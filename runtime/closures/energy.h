// Directional albedo E(mu, alpha) of a microfacet reflection lobe with Fresnel = 1, and its
// hemispherical average E_avg(alpha) = 2 int E(mu) mu dmu, for Kulla-Conty energy
// compensation. The tables (energy_tables.inc) are produced by energy_gen.cpp from this
// library's own distributions (visible-normal estimator, 128x128 stratified samples per
// entry) and re-derived independently, by quadrature, in energy_test.cpp.
// Grid: mu = i/31 and alpha = j/31 for i, j in 0..31, bilinear in between; alpha > 1 uses 1.
#pragma once

#include "common.h"

namespace lobe::closures {

inline constexpr int kEnergyN = 32;
// [distribution: 0 GGX, 1 Beckmann][alpha index][mu index]
inline constexpr float kEnergyE[2][kEnergyN][kEnergyN] = {
#include "energy_tables_e.inc"
};
inline constexpr float kEnergyEavg[2][kEnergyN] = {
#include "energy_tables_eavg.inc"
};

// Bilinear look-up of a table with coordinates in [0, 1].
inline float energy_lerp(const float* row0, const float* row1, float fa, float mu) {
  float x = clampf(mu, 0.0f, 1.0f) * (kEnergyN - 1);
  int i = static_cast<int>(x);
  if (i >= kEnergyN - 1) i = kEnergyN - 2;
  float fx = x - static_cast<float>(i);
  float a = row0[i] + (row0[i + 1] - row0[i]) * fx;
  float b = row1[i] + (row1[i + 1] - row1[i]) * fx;
  return a + (b - a) * fa;
}

inline void energy_alpha_index(float alpha, int& j, float& fa) {
  float y = clampf(alpha, 0.0f, 1.0f) * (kEnergyN - 1);
  j = static_cast<int>(y);
  if (j >= kEnergyN - 1) j = kEnergyN - 2;
  fa = y - static_cast<float>(j);
}

inline float energy_E(float mu, float alpha, bool beckmann) {
  int j;
  float fa;
  energy_alpha_index(alpha, j, fa);
  const auto& t = kEnergyE[beckmann ? 1 : 0];
  return clampf(energy_lerp(t[j], t[j + 1], fa, mu), 0.0f, 1.0f);
}

inline float energy_E_avg(float alpha, bool beckmann) {
  int j;
  float fa;
  energy_alpha_index(alpha, j, fa);
  const auto& t = kEnergyEavg[beckmann ? 1 : 0];
  return clampf(t[j] + (t[j + 1] - t[j]) * fa, 0.0f, 1.0f);
}

} // namespace lobe::closures
