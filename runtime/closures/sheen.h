// sheen_bsdf: the "Charlie" microfibre sheen of Estevez & Kulla 2017 ("Production friendly
// microfacet sheen BRDF") with exact height-correlated Smith masking-shadowing:
//   D(m) = (2 + 1/r) sin(theta_m)^(1/r) / (2 pi),   r = roughness clamped to [0.01, 1],
//   P(mu) = int D(m) max(0, w.m) dm   (projected area; Smith: 1 + Lambda(w) = P(mu) / mu),
//   f = albedo D(h) G2 / (4 cos_i cos_o),  G2 = 1 / (1 + Lambda_o + Lambda_i),
// so f cos_i = albedo D(h) cos_i / (4 (P_o cos_i + P_i cos_o - cos_o cos_i)).
// P has no closed form; sheen_gen.cpp tabulates it (and the directional albedo E) by quadrature
// on x = sqrt(1 - mu), t = log(r / 0.01) / log(100), 65 x 33 nodes, bilinear in between.
// With the exact P the single-scattering albedo is <= 1 (G2 <= G1(wo) and the visible-normal
// integral of G1 is 1); the table nodes are scaled up by their interpolation error so the
// look-up never falls below the exact P. (Neubelt & Pettineo's visibility, the usual shortcut,
// amounts to P = 1 and reaches an albedo of 3.8 at grazing for small r.)
// Sampled uniformly over the hemisphere (the lobe peaks towards grazing, where cosine sampling
// would starve it); pdf 1/(2 pi). Albedo: the E table (sheen_gen raises its nodes by their
// interpolation error, so layering over a base never under-attenuates it).
#pragma once

#include "common.h"
#include "params.h"

namespace lobe::closures {

inline constexpr int kSheenMu = 65, kSheenR = 33;
inline constexpr float kSheenRMin = 0.01f;
// [t index][x index]: P at mu = 1 - x^2 (x = i/64), r = 0.01 * 100^(j/32).
inline constexpr float kSheenP[kSheenR][kSheenMu] = {
#include "sheen_tables_p.inc"
};
// [t index][s index]: E at mu = s^2 (s = i/64), same r.
inline constexpr float kSheenE[kSheenR][kSheenMu] = {
#include "sheen_tables_e.inc"
};

struct Sheen {
  Vec3 rho;
  float r = 0.5f;
  int row = 0;     // r's table row and
  float fr = 0.0f; // fraction towards the next one

  static Sheen make(const Vec3& rho, float roughness) {
    Sheen s;
    s.rho = rho;
    s.r = clampf(roughness, kSheenRMin, 1.0f);
    float t =
        clampf(std::log(s.r / kSheenRMin) * (1.0f / std::log(1.0f / kSheenRMin)), 0.0f, 1.0f) *
        (kSheenR - 1);
    s.row = t >= kSheenR - 1 ? kSheenR - 2 : static_cast<int>(t);
    s.fr = t - static_cast<float>(s.row);
    return s;
  }
  float lookup(const float (&table)[kSheenR][kSheenMu], float x) const {
    float p = clampf(x, 0.0f, 1.0f) * (kSheenMu - 1);
    int i = p >= kSheenMu - 1 ? kSheenMu - 2 : static_cast<int>(p);
    float fx = p - static_cast<float>(i);
    const float* a = table[row];
    const float* b = table[row + 1];
    float va = a[i] + (a[i + 1] - a[i]) * fx, vb = b[i] + (b[i + 1] - b[i]) * fx;
    return va + (vb - va) * fr;
  }
  float projected_area(float mu) const { return lookup(kSheenP, safe_sqrt(1.0f - mu)); }

  uint32_t flags() const { return kLobeReflect | kLobeGlossy; }
  BsdfEval eval(const Vec3& wo, const Vec3& wi) const {
    if (!(wi.z > 0.0f) || !(wo.z > 0.0f)) return {};
    Vec3 h = normalize(wo + wi);
    float inv = 1.0f / r;
    float sin_h = safe_sqrt(1.0f - h.z * h.z);
    float d = (2.0f + inv) * std::pow(sin_h, inv) / (2.0f * kPi);
    float mo = minf(wo.z, 1.0f), mi = minf(wi.z, 1.0f);
    // P >= mu (1 + Lambda >= 1), so the denominator is >= mo mi > 0.
    float den = 4.0f * maxf(projected_area(mo) * mi + projected_area(mi) * mo - mo * mi, mo * mi);
    return {rho * (d * mi / den), 1.0f / (2.0f * kPi)};
  }
  BsdfSample sample(const Vec3& wo, const Vec3& u) const {
    BsdfSample s;
    if (!(wo.z > 0.0f)) return s;
    float z = 1.0f - u.x, sr = safe_sqrt(1.0f - z * z), phi = 2.0f * kPi * u.y;
    Vec3 wi{sr * std::cos(phi), sr * std::sin(phi), z};
    BsdfEval e = eval(wo, wi);
    if (!(e.pdf > 0.0f) || !(wi.z > 0.0f)) return s;
    return {wi, e.value / e.pdf, e.pdf, flags(), 1.0f};
  }
  Vec3 albedo(const Vec3& wo) const {
    if (!(wo.z > 0.0f)) return {};
    return rho * clampf(lookup(kSheenE, safe_sqrt(minf(wo.z, 1.0f))), 0.0f, 1.0f);
  }
};

// ---- registry entries (params.h) ------------------------------------------------------------

template <> struct Closure<closure_id::sheen_bsdf> {
  using Params = AlbedoRoughnessParams;
  static constexpr size_t kOffsets[] = LOBE_ALBEDO_ROUGHNESS_OFFSETS;
  using Lobe = Sheen;
  static bool make(const Params& q, Lobe& l, Frame& f) {
    if (!make_frame(q.N, f)) return false;
    float r = q.roughness == q.roughness ? clampf(q.roughness, 0.01f, 1.0f) : 1.0f;
    l = Sheen::make(vmax0(sanitize(q.albedo)), r);
    return true;
  }
};

} // namespace lobe::closures
