// sheen_bsdf: the "Charlie" microfibre sheen of Estevez & Kulla 2017 ("Production friendly
// microfacet sheen BRDF") with Neubelt & Pettineo's visibility term:
//   D(m) = (2 + 1/r) sin(theta_m)^(1/r) / (2 pi),   f = albedo D(h) / (4 (cos_i + cos_o -
//   cos_i cos_o)),  r = roughness clamped to [0.01, 1].
// Sampled uniformly over the hemisphere (the lobe peaks towards grazing, where cosine sampling
// would starve it); pdf 1/(2 pi). Albedo by quadrature (quadrature.h).
#pragma once

#include "common.h"
#include "quadrature.h"

namespace lobe::closures {

struct Sheen {
  Vec3 rho;
  float r = 0.5f;
  uint32_t flags() const { return kFlagReflect | kFlagGlossy; }
  LobeEval eval(const Vec3& wo, const Vec3& wi) const {
    if (!(wi.z > 0.0f) || !(wo.z > 0.0f)) return {};
    Vec3 h = normalize(wo + wi);
    float inv = 1.0f / r;
    float sin_h = safe_sqrt(1.0f - h.z * h.z);
    float d = (2.0f + inv) * std::pow(sin_h, inv) / (2.0f * kPi);
    float v = 1.0f / (4.0f * (wi.z + wo.z - wi.z * wo.z));
    return {rho * (d * v * wi.z), 1.0f / (2.0f * kPi)};
  }
  LobeSample sample(const Vec3& wo, const Vec3& u) const {
    LobeSample s;
    if (!(wo.z > 0.0f)) return s;
    float z = 1.0f - u.x, sr = safe_sqrt(1.0f - z * z), phi = 2.0f * kPi * u.y;
    Vec3 wi{sr * std::cos(phi), sr * std::sin(phi), z};
    LobeEval e = eval(wo, wi);
    if (!(e.pdf > 0.0f) || !(wi.z > 0.0f)) return s;
    return {wi, e.value / e.pdf, e.pdf, flags(), 1.0f, true};
  }
  Vec3 albedo(const Vec3& wo) const { return quadrature_albedo(*this, wo); }
};

} // namespace lobe::closures
