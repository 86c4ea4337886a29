// Directional albedo of this library's rough dielectric lobe (reflection + refraction, exact
// Fresnel, importance transport, no tint), for Kulla-Conty energy compensation of
// dielectric_bsdf and microfacet(): E(mu, alpha, eta) for light arriving from the side whose
// relative IOR is eta (> 1: from outside) or 1/eta (from inside, with total internal
// reflection), and E_avg = 2 int E(mu) mu dmu.
//
// The tables (energy_tables_dielectric_*.inc) are produced by energy_gen.cpp from the lobe's
// own distributions and Fresnel (stratified visible normals, both Fresnel branches summed per
// normal, double accumulation) and re-derived by independent quadrature in
// energy_dielectric_test.cpp. Grid: mu = (i/63)^2 (64), alpha = (j/15)^2 (16),
// eta = 1 + 2 (k/15)^2 (16, so eta in [1, 3]); trilinear in sqrt(mu), sqrt(alpha),
// sqrt(eta - 1): the square-root axes put the nodes where E changes fastest (grazing angles,
// small roughness, eta near 1). alpha > 1 uses 1, eta > 3 uses 3.
#pragma once

#include "common.h"

namespace lobe::closures {

inline constexpr int kDielMu = 64, kDielAlpha = 16, kDielEta = 16;
inline constexpr float kDielEtaMax = 3.0f;
// [distribution: 0 GGX, 1 Beckmann][side: 0 outside (eta), 1 inside (1/eta)][eta][alpha][mu]
#ifdef LOBE_BITCODE
// In the bitcode the two large tables (256 KB and 246 KB) are declarations: the JIT resolves
// them to the host's copies (runtime/jit/jit.cpp) instead of compiling them into every
// material's module.
extern const float kDielE[2][2][kDielEta][kDielAlpha][kDielMu];
#else
inline constexpr float kDielE[2][2][kDielEta][kDielAlpha][kDielMu] = {
#include "energy_tables_dielectric_e.inc"
};
#endif
// [distribution][side][eta][alpha]
inline constexpr float kDielEavg[2][2][kDielEta][kDielAlpha] = {
#include "energy_tables_dielectric_eavg.inc"
};

// Grid coordinate of x in [0, 1] on n points: index i (<= n - 2) and fraction t.
inline void diel_grid(float x, int n, int& i, float& t) {
  float y = clampf(x, 0.0f, 1.0f) * static_cast<float>(n - 1);
  i = static_cast<int>(y);
  if (i >= n - 1) i = n - 2;
  t = y - static_cast<float>(i);
}

// Side and table eta for a relative IOR e (e < 1: the inside table at 1/e).
inline int diel_side(float e, float& eta) {
  eta = e >= 1.0f ? e : 1.0f / maxf(e, 1e-6f);
  return e >= 1.0f ? 0 : 1;
}

inline double diel_grid_mu(int i) { return double(i) * i / ((kDielMu - 1.0) * (kDielMu - 1.0)); }
inline double diel_grid_alpha(int j) {
  return double(j) * j / ((kDielAlpha - 1.0) * (kDielAlpha - 1.0));
}
inline double diel_grid_eta(int k) {
  return 1.0 + (kDielEtaMax - 1.0) * double(k) * k / ((kDielEta - 1.0) * (kDielEta - 1.0));
}

inline float lerpf(float a, float b, float t) { return a + (b - a) * t; }

// E for light arriving at cosine mu on the side with relative IOR e.
inline float dielectric_E(float mu, float alpha, float e, bool beckmann) {
  float eta;
  int side = diel_side(e, eta);
  int k, j, i;
  float tk, tj, ti;
  diel_grid(std::sqrt((eta - 1.0f) / (kDielEtaMax - 1.0f)), kDielEta, k, tk);
  diel_grid(std::sqrt(maxf(alpha, 0.0f)), kDielAlpha, j, tj);
  diel_grid(std::sqrt(maxf(mu, 0.0f)), kDielMu, i, ti);
  const auto& t = kDielE[beckmann ? 1 : 0][side];
  auto mu_lerp = [&](int kk, int jj) { return lerpf(t[kk][jj][i], t[kk][jj][i + 1], ti); };
  auto alpha_lerp = [&](int kk) { return lerpf(mu_lerp(kk, j), mu_lerp(kk, j + 1), tj); };
  return clampf(lerpf(alpha_lerp(k), alpha_lerp(k + 1), tk), 0.0f, 1.0f);
}

inline float dielectric_E_avg(float alpha, float e, bool beckmann) {
  float eta;
  int side = diel_side(e, eta);
  int k, j;
  float tk, tj;
  diel_grid(std::sqrt((eta - 1.0f) / (kDielEtaMax - 1.0f)), kDielEta, k, tk);
  diel_grid(std::sqrt(maxf(alpha, 0.0f)), kDielAlpha, j, tj);
  const auto& t = kDielEavg[beckmann ? 1 : 0][side];
  return clampf(lerpf(lerpf(t[k][j], t[k][j + 1], tj), lerpf(t[k + 1][j], t[k + 1][j + 1], tj), tk),
                0.0f, 1.0f);
}

// Anisotropic lobes (ax != ay): E depends on the azimuth of the direction as well, and no
// isotropic alpha reproduces it (measured: sqrt(ax ay) or the projected roughness of wo miss
// by up to 0.12, the largest isotropic E over [ay, ax] by 0.18). A 5-D table
// E(mu, c, ax, ay, eta) per distribution and side, c = cos^2 of the direction's azimuth from
// the tangent (the ax axis; E is symmetric under x -> -x, y -> -y).
// Grid: mu = (i/11)^2, c = l/4, alpha = (j/7)^2 per axis, eta = 1 + 2 (k/7)^2; multilinear in
// sqrt(mu), c, sqrt(ax), sqrt(ay), sqrt(eta - 1). Stored as E * 65535 rounded up. Both the
// isotropic and this table are conservative: energy_gen raises every node by the largest
// interpolation underestimate found in the cells around it, so the look-up does not fall below
// the lobe's albedo and the compensation never adds energy (its E_avg is integrated from the
// raised interpolant, which keeps the compensation lobe normalised).
inline constexpr int kAnMu = 12, kAnC = 5, kAnA = 8, kAnEta = 8;
// [distribution][side][eta][ax][ay][c][mu]
#ifdef LOBE_BITCODE
extern const uint16_t kDielEAniso[2][2][kAnEta][kAnA][kAnA][kAnC][kAnMu]; // see kDielE
#else
inline constexpr uint16_t kDielEAniso[2][2][kAnEta][kAnA][kAnA][kAnC][kAnMu] = {
#include "energy_tables_dielectric_aniso_e.inc"
};
#endif
// [distribution][side][eta][ax][ay]
inline constexpr float kDielEavgAniso[2][2][kAnEta][kAnA][kAnA] = {
#include "energy_tables_dielectric_aniso_eavg.inc"
};

inline double an_grid_mu(int i) { return double(i) * i / ((kAnMu - 1.0) * (kAnMu - 1.0)); }
inline double an_grid_c(int l) { return double(l) / (kAnC - 1.0); }
inline double an_grid_alpha(int j) { return double(j) * j / ((kAnA - 1.0) * (kAnA - 1.0)); }
inline double an_grid_eta(int k) {
  return 1.0 + (kDielEtaMax - 1.0) * double(k) * k / ((kAnEta - 1.0) * (kAnEta - 1.0));
}

// Grid position of a lobe's (ax, ay, eta) in the anisotropic table (eta: either side's
// relative IOR; the table uses max(eta, 1/eta) and the side comes with each look-up).
struct AnisoCoord {
  int k = 0, jx = 0, jy = 0;
  float tk = 0.0f, tx = 0.0f, ty = 0.0f;
};
inline AnisoCoord aniso_coord(float ax, float ay, float e) {
  AnisoCoord a;
  float eta;
  diel_side(e, eta);
  diel_grid(std::sqrt(maxf(eta - 1.0f, 0.0f) / (kDielEtaMax - 1.0f)), kAnEta, a.k, a.tk);
  diel_grid(std::sqrt(maxf(ax, 0.0f)), kAnA, a.jx, a.tx);
  diel_grid(std::sqrt(maxf(ay, 0.0f)), kAnA, a.jy, a.ty);
  return a;
}

// cos^2 of w's azimuth from the tangent (1 along the tangent, 0 along the bitangent).
inline float azimuth_c(const Vec3& w) {
  float xx = w.x * w.x, r = xx + w.y * w.y;
  return r > 0.0f ? clampf(xx / r, 0.0f, 1.0f) : 1.0f;
}

// E for light arriving at cosine mu, azimuth c, on the side with relative IOR e.
inline float dielectric_E_aniso(float mu, float c, const AnisoCoord& a, float e, bool beckmann) {
  float eta;
  int side = diel_side(e, eta);
  int i, l;
  float ti, tl;
  diel_grid(std::sqrt(maxf(mu, 0.0f)), kAnMu, i, ti);
  diel_grid(c, kAnC, l, tl);
  const auto& t = kDielEAniso[beckmann ? 1 : 0][side];
  float sum = 0.0f;
  for (int dk = 0; dk < 2; ++dk)
    for (int dx = 0; dx < 2; ++dx)
      for (int dy = 0; dy < 2; ++dy) {
        float w = (dk ? a.tk : 1.0f - a.tk) * (dx ? a.tx : 1.0f - a.tx) * (dy ? a.ty : 1.0f - a.ty);
        const auto& b = t[a.k + dk][a.jx + dx][a.jy + dy];
        float v0 = lerpf(float(b[l][i]), float(b[l][i + 1]), ti);
        float v1 = lerpf(float(b[l + 1][i]), float(b[l + 1][i + 1]), ti);
        sum += w * lerpf(v0, v1, tl);
      }
  return clampf(sum * (1.0f / 65535.0f), 0.0f, 1.0f);
}

inline float dielectric_E_avg_aniso(const AnisoCoord& a, float e, bool beckmann) {
  float eta;
  int side = diel_side(e, eta);
  const auto& t = kDielEavgAniso[beckmann ? 1 : 0][side];
  float sum = 0.0f;
  for (int dk = 0; dk < 2; ++dk)
    for (int dx = 0; dx < 2; ++dx)
      for (int dy = 0; dy < 2; ++dy)
        sum += (dk ? a.tk : 1.0f - a.tk) * (dx ? a.tx : 1.0f - a.tx) * (dy ? a.ty : 1.0f - a.ty) *
               t[a.k + dk][a.jx + dx][a.jy + dy];
  return clampf(sum, 0.0f, 1.0f);
}

} // namespace lobe::closures
