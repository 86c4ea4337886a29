// toon (Lobe extension): toon(normal N, color albedo, color specular, float shininess,
// "bands", int = 3, "softness", float = 0.05). Cel shading as a bounded-energy BRDF.
//
//   diffuse   value = k_d albedo / pi * q(cos_i) * B/(B+1),  q(c) = (floor(cB) + s(frac(cB)))/B
//             where s ramps 0 -> 1 over the last `softness` of each band (smoothstep), so
//             q(c) <= ceil(cB)/B and the albedo is at most k_d albedo (the B/(B+1) factor is
//             the integral of ceil(cB)/B over the hemisphere, divided by pi).
//   specular  value = specular * band(cos(theta_h)^shininess) * cos_i / (4 Omega_h): a flat
//             highlight where the Blinn term exceeds 1/2 (smoothed over +-softness); Omega_h is
//             the solid angle of half vectors it covers, and since dw_i <= 4 dw_h its albedo is
//             at most `specular`.
//   k_d = 1 - max(specular) keeps the sum <= 1 when albedo, specular <= 1.
// Sampled by cosine; albedo estimate: k_d albedo + specular (an upper bound).
#pragma once

#include "common.h"
#include "params.h"

namespace lobe::closures {

inline float smoothstep01(float e0, float e1, float x) {
  if (!(e1 > e0)) return x >= e1 ? 1.0f : 0.0f;
  float t = clampf((x - e0) / (e1 - e0), 0.0f, 1.0f);
  return t * t * (3.0f - 2.0f * t);
}

struct Toon {
  Vec3 albedo_d, specular;
  float shininess = 10.0f, softness = 0.05f;
  int bands = 3;
  float omega_h = 1.0f; // solid angle of the highlight in half-vector space

  static Toon make(Vec3 a, Vec3 s, float n, int bands, float soft) {
    Toon t;
    t.specular = vmax0(s);
    t.albedo_d = vmax0(a) * maxf(0.0f, 1.0f - minf(1.0f, max_component(t.specular)));
    t.shininess = clampf(n == n ? n : 1.0f, 1.0f, 1e5f);
    t.bands = bands < 1 ? 1 : (bands > 64 ? 64 : bands);
    t.softness = clampf(soft == soft ? soft : 0.0f, 0.0f, 0.5f);
    float c0 = std::pow(maxf(0.5f - t.softness, 1e-3f), 1.0f / t.shininess);
    t.omega_h = maxf(2.0f * kPi * (1.0f - c0), 1e-6f);
    return t;
  }
  uint32_t flags() const { return kLobeReflect | kLobeDiffuse; }
  float quantise(float c) const {
    float x = c * bands, k = std::floor(x);
    return (k + smoothstep01(1.0f - softness, 1.0f, x - k)) / bands;
  }
  BsdfEval eval(const Vec3& wo, const Vec3& wi) const {
    if (!(wi.z > 0.0f) || !(wo.z > 0.0f)) return {};
    float b = static_cast<float>(bands);
    Vec3 v = albedo_d * (kInvPi * quantise(wi.z) * b / (b + 1.0f));
    Vec3 h = normalize(wo + wi);
    float blinn = std::pow(maxf(h.z, 0.0f), shininess);
    float band = smoothstep01(0.5f - softness, 0.5f + softness, blinn);
    v += specular * (band * wi.z / (4.0f * omega_h));
    return {v, wi.z * kInvPi};
  }
  BsdfSample sample(const Vec3& wo, const Vec3& u) const {
    BsdfSample s;
    if (!(wo.z > 0.0f)) return s;
    Vec3 wi = sample_cosine_hemisphere(u.x, u.y);
    BsdfEval e = eval(wo, wi);
    if (!(e.pdf > 0.0f)) return s;
    return {wi, e.value / e.pdf, e.pdf, flags(), 1.0f};
  }
  Vec3 albedo(const Vec3& wo) const { return wo.z > 0.0f ? albedo_d + specular : Vec3{}; }
};

// ---- registry entries (params.h) ------------------------------------------------------------

struct ToonParams {
  Vec3 N;
  Color3 albedo, specular;
  float shininess;
  int bands;
  float softness;
  Str label;
};

template <> struct Closure<closure_id::toon> {
  using Params = ToonParams;
  static constexpr size_t kOffsets[] = {offsetof(Params, N),        offsetof(Params, albedo),
                                        offsetof(Params, specular), offsetof(Params, shininess),
                                        offsetof(Params, bands),    offsetof(Params, softness),
                                        offsetof(Params, label)};
  using Lobe = Toon;
  static bool make(const Params& q, Lobe& l, Frame& f) {
    if (!make_frame(q.N, f)) return false;
    l = Toon::make(sanitize(q.albedo), sanitize(q.specular), q.shininess, q.bands, q.softness);
    return true;
  }
};

} // namespace lobe::closures
