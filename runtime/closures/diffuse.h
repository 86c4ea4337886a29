// Diffuse lobes: Lambert (reflection and translucency), Oren-Nayar, Fujii/EON Oren-Nayar and
// Burley, all cosine-sampled.
//
//   lambert       f = rho / pi               (diffuse, translucent*, subsurface_bssrdf: Lobe
//                 renders its medium as this diffuse lobe with the albedo, see docs/closures.md)
//   oren_nayar    f = rho/pi (A + B max(0, s)/t),  A = 1 - 0.5 s2/(s2 + 0.33),
//                 B = 0.45 s2/(s2 + 0.09), s2 = sigma^2, s = wi.wo - cos_i cos_o,
//                 t = max(cos_i, cos_o)                     (Oren & Nayar 1994, qualitative)
//   FON           f = rho/pi A (1 + r s/t), t = max(cos) if s > 0 else 1,
//                 A = 1/(1 + (1/2 - 2/(3 pi)) r)            (Fujii 2012; r = roughness in [0,1])
//   EON           FON + f_ms, the energy-compensation term of Portsmouth, Kutz & Hill 2024
//                 ("EON: a practical energy-preserving rough diffuse BRDF"): with rho = 1 the
//                 albedo is exactly 1 at every angle.
//   burley        f = rho/pi k F(cos_i) F(cos_o), F(c) = 1 + (F90 - 1)(1 - c)^5,
//                 F90 = b + 2 r cos^2 theta_d, with Frostbite's renormalisation b = r/2,
//                 k = 1 - r (1 - 1/1.51) (Lagarde & de Rousiers 2014). That alone leaves the
//                 albedo above 1 at grazing views for r > 0.945 (1.0315 at r = 1, wo on the
//                 horizon, by double-precision quadrature), so k is also divided by
//                 max(1, A0(r)), A0(r) = 1.03149 + 0.59093 (r-1) - 0.48028 (r-1)^2 + 1e-4, the
//                 fitted horizon albedo (fit error < 1e-5 on [0.93, 1]); the albedo's maximum
//                 over wo is at the horizon there, so it stays <= 1 and f stays reciprocal.
//
// Directional albedos: Lambert rho; Oren-Nayar and FON/EON in closed form (hemispherical
// integral of s/t, derived in docs/closures.md); Burley: rho (an upper-bound estimate).
// Ranges: rho in [0, 1], sigma >= 0 (radians), roughness clamped to [0, 1].
#pragma once

#include "common.h"
#include "params.h"

namespace lobe::closures {

// Samples a cosine-weighted direction and reports the lobe's own eval() for it, so sampling
// and evaluation cannot disagree. Works for reflection (wi.z > 0) and transmission lobes.
template <class L>
BsdfSample sample_cosine(const L& lobe, const Vec3& wo, const Vec3& u, bool transmit) {
  BsdfSample s;
  Vec3 wi = sample_cosine_hemisphere(u.x, u.y);
  if (transmit) wi.z = -wi.z;
  BsdfEval e = lobe.eval(wo, wi);
  if (!(e.pdf > 0.0f)) return s;
  s.wi = wi;
  s.pdf = e.pdf;
  s.weight = e.value / e.pdf;
  s.flags = kLobeDiffuse | (transmit ? kLobeTransmit : kLobeReflect);
  return s;
}

// Lambert reflection or transmission with albedo rho.
struct Lambert {
  Vec3 rho;
  bool transmit = false;
  uint32_t flags() const { return kLobeDiffuse | (transmit ? kLobeTransmit : kLobeReflect); }
  BsdfEval eval(const Vec3& wo, const Vec3& wi) const {
    float c = transmit ? -wi.z : wi.z;
    if (!(c > 0.0f) || !(wo.z > 0.0f)) return {};
    return {rho * (c * kInvPi), c * kInvPi};
  }
  BsdfSample sample(const Vec3& wo, const Vec3& u) const {
    return wo.z > 0.0f ? sample_cosine(*this, wo, u, transmit) : BsdfSample{};
  }
  Vec3 albedo(const Vec3& wo) const { return wo.z > 0.0f ? rho : Vec3{}; }
};

// sin(th)(th - sin cos) + 2/3 tan(th)(1 - sin^3): the hemispherical integral of
// max(0, s)/t cos_i / pi, times pi (see the file comment); finite as cos_o -> 0.
inline float oren_nayar_g(float mu) {
  mu = clampf(mu, 1e-6f, 1.0f);
  float si = safe_sqrt(1.0f - mu * mu);
  float th = std::acos(mu);
  float one_minus_si3 = 1.0f - si * si * si;
  return si * (th - si * mu) + (2.0f / 3.0f) * (si / mu) * one_minus_si3;
}

// The classic qualitative Oren-Nayar model (oren_nayar(N, sigma)).
struct OrenNayar {
  Vec3 rho;
  float A = 1, B = 0;
  static OrenNayar make(const Vec3& rho, float sigma) {
    float s2 = sqr(maxf(sigma, 0.0f));
    if (!(s2 < 1e30f)) s2 = 1e30f;
    return {rho, 1.0f - 0.5f * s2 / (s2 + 0.33f), 0.45f * s2 / (s2 + 0.09f)};
  }
  uint32_t flags() const { return kLobeDiffuse | kLobeReflect; }
  BsdfEval eval(const Vec3& wo, const Vec3& wi) const {
    if (!(wi.z > 0.0f) || !(wo.z > 0.0f)) return {};
    float s = dot(wo, wi) - wo.z * wi.z;
    float st = s > 0.0f ? s / maxf(wo.z, wi.z) : 0.0f;
    return {rho * ((A + B * st) * wi.z * kInvPi), wi.z * kInvPi};
  }
  BsdfSample sample(const Vec3& wo, const Vec3& u) const {
    return wo.z > 0.0f ? sample_cosine(*this, wo, u, false) : BsdfSample{};
  }
  Vec3 albedo(const Vec3& wo) const {
    if (!(wo.z > 0.0f)) return {};
    return rho * (A + B * oren_nayar_g(wo.z) * kInvPi);
  }
};

inline constexpr float kFonC1 = 0.5f - 2.0f / (3.0f * kPi);
inline constexpr float kFonC2 = 2.0f / 3.0f - 28.0f / (15.0f * kPi);

// Directional albedo of the FON lobe with rho = 1: A (1 + r G(mu) / pi), where the s < 0 half
// adds -2/3 sin(theta) to the Oren-Nayar G.
inline float fon_albedo(float mu, float r) {
  float A = 1.0f / (1.0f + kFonC1 * r);
  float si = safe_sqrt(1.0f - sqr(clampf(mu, 0.0f, 1.0f)));
  return A * (1.0f + r * (oren_nayar_g(mu) - (2.0f / 3.0f) * si) * kInvPi);
}

// Fujii's Oren-Nayar (oren_nayar_diffuse_bsdf), optionally with EON energy compensation.
struct FujiiOrenNayar {
  Vec3 rho;
  float r = 0;
  bool compensate = false;
  uint32_t flags() const { return kLobeDiffuse | kLobeReflect; }
  float avg_albedo() const { return (1.0f + kFonC2 * r) / (1.0f + kFonC1 * r); }
  Vec3 rho_ms() const {
    float e = avg_albedo();
    Vec3 den = splat(1.0f) - rho * (1.0f - e);
    return rho * rho * e / Vec3{maxf(den.x, 1e-6f), maxf(den.y, 1e-6f), maxf(den.z, 1e-6f)};
  }
  BsdfEval eval(const Vec3& wo, const Vec3& wi) const {
    if (!(wi.z > 0.0f) || !(wo.z > 0.0f)) return {};
    float s = dot(wo, wi) - wo.z * wi.z;
    float st = s > 0.0f ? s / maxf(wo.z, wi.z) : s;
    float A = 1.0f / (1.0f + kFonC1 * r);
    Vec3 f = rho * (kInvPi * A * maxf(1.0f + r * st, 0.0f));
    if (compensate) {
      float eo = fon_albedo(wo.z, r), ei = fon_albedo(wi.z, r), ea = avg_albedo();
      float k = maxf(1.0f - eo, 0.0f) * maxf(1.0f - ei, 0.0f) / maxf(1.0f - ea, 1e-7f);
      f += rho_ms() * (kInvPi * k);
    }
    return {f * wi.z, wi.z * kInvPi};
  }
  BsdfSample sample(const Vec3& wo, const Vec3& u) const {
    return wo.z > 0.0f ? sample_cosine(*this, wo, u, false) : BsdfSample{};
  }
  Vec3 albedo(const Vec3& wo) const {
    if (!(wo.z > 0.0f)) return {};
    float eo = fon_albedo(wo.z, r);
    Vec3 a = rho * eo;
    if (compensate) a += rho_ms() * maxf(1.0f - eo, 0.0f);
    return a;
  }
};

// Burley ("Disney") diffuse with Frostbite's energy renormalisation.
struct Burley {
  Vec3 rho;
  float r = 0;
  // max(1, albedo with wo on the horizon) of the Frostbite-normalised lobe (header comment).
  static float horizon_albedo(float r) {
    float d = r - 1.0f;
    return maxf(1.0f, 1.03149f + 0.59093f * d - 0.48028f * d * d + 1e-4f);
  }
  uint32_t flags() const { return kLobeDiffuse | kLobeReflect; }
  BsdfEval eval(const Vec3& wo, const Vec3& wi) const {
    if (!(wi.z > 0.0f) || !(wo.z > 0.0f)) return {};
    Vec3 h = normalize(wo + wi);
    float cd = dot(wi, h);
    float f90 = 0.5f * r + 2.0f * r * cd * cd;
    float k = (1.0f - r * (1.0f - 1.0f / 1.51f)) / horizon_albedo(r);
    auto F = [f90](float c) {
      float m = 1.0f - c;
      return 1.0f + (f90 - 1.0f) * (m * m * m * m * m);
    };
    float f = kInvPi * k * F(wi.z) * F(wo.z);
    return {rho * (f * wi.z), wi.z * kInvPi};
  }
  BsdfSample sample(const Vec3& wo, const Vec3& u) const {
    return wo.z > 0.0f ? sample_cosine(*this, wo, u, false) : BsdfSample{};
  }
  Vec3 albedo(const Vec3& wo) const { return wo.z > 0.0f ? rho : Vec3{}; }
};

// ---- registry entries (params.h) ------------------------------------------------------------

struct DiffuseParams {
  Vec3 N;
  Str label;
}; // diffuse, translucent
struct AlbedoParams {
  Vec3 N;
  Color3 albedo;
  Str label;
}; // translucent_bsdf
struct OrenNayarParams {
  Vec3 N;
  float sigma;
  Str label;
};
struct OrenNayarDiffuseParams {
  Vec3 N;
  Color3 albedo;
  float roughness;
  int energy_compensation;
  Str label;
};
struct SubsurfaceBssrdfParams {
  Vec3 N;
  Color3 albedo;
  float transmission_depth;
  Color3 transmission_color;
  float anisotropy;
  Str label;
};

// diffuse(N) and translucent(N): white Lambert reflection / transmission.
template <bool kTransmit> struct LambertClosure {
  using Params = DiffuseParams;
  static constexpr size_t kOffsets[] = {offsetof(Params, N), offsetof(Params, label)};
  using Lobe = Lambert;
  static bool make(const Params& q, Lobe& l, Frame& f) {
    if (!make_frame(q.N, f)) return false;
    l = Lambert{splat(1.0f), kTransmit};
    return true;
  }
};
template <> struct Closure<closure_id::diffuse> : LambertClosure<false> {};
template <> struct Closure<closure_id::translucent> : LambertClosure<true> {};

template <> struct Closure<closure_id::translucent_bsdf> {
  using Params = AlbedoParams;
  static constexpr size_t kOffsets[] = {offsetof(Params, N), offsetof(Params, albedo),
                                        offsetof(Params, label)};
  using Lobe = Lambert;
  static bool make(const Params& q, Lobe& l, Frame& f) {
    if (!make_frame(q.N, f)) return false;
    l = Lambert{vmax0(q.albedo), true};
    return true;
  }
};

template <> struct Closure<closure_id::oren_nayar> {
  using Params = OrenNayarParams;
  static constexpr size_t kOffsets[] = {offsetof(Params, N), offsetof(Params, sigma),
                                        offsetof(Params, label)};
  using Lobe = OrenNayar;
  static bool make(const Params& q, Lobe& l, Frame& f) {
    if (!make_frame(q.N, f)) return false;
    l = OrenNayar::make(splat(1.0f), q.sigma);
    return true;
  }
};

template <> struct Closure<closure_id::oren_nayar_diffuse_bsdf> {
  using Params = OrenNayarDiffuseParams;
  static constexpr size_t kOffsets[] = {
      offsetof(Params, N), offsetof(Params, albedo), offsetof(Params, roughness),
      offsetof(Params, energy_compensation), offsetof(Params, label)};
  using Lobe = FujiiOrenNayar;
  static bool make(const Params& q, Lobe& l, Frame& f) {
    if (!make_frame(q.N, f)) return false;
    float r = clampf(q.roughness, 0.0f, 1.0f);
    l = FujiiOrenNayar{vmax0(q.albedo), r == r ? r : 0.0f, q.energy_compensation != 0};
    return true;
  }
};

template <> struct Closure<closure_id::burley_diffuse_bsdf> {
  using Params = AlbedoRoughnessParams;
  static constexpr size_t kOffsets[] = LOBE_ALBEDO_ROUGHNESS_OFFSETS;
  using Lobe = Burley;
  static bool make(const Params& q, Lobe& l, Frame& f) {
    if (!make_frame(q.N, f)) return false;
    float r = clampf(q.roughness, 0.0f, 1.0f);
    l = Burley{vmax0(q.albedo), r == r ? r : 0.0f};
    return true;
  }
};

// Lobe has no subsurface transport: subsurface_bssrdf is diffuse with the medium's albedo.
template <> struct Closure<closure_id::subsurface_bssrdf> {
  using Params = SubsurfaceBssrdfParams;
  static constexpr size_t kOffsets[] = {offsetof(Params, N),
                                        offsetof(Params, albedo),
                                        offsetof(Params, transmission_depth),
                                        offsetof(Params, transmission_color),
                                        offsetof(Params, anisotropy),
                                        offsetof(Params, label)};
  using Lobe = Lambert;
  static bool make(const Params& q, Lobe& l, Frame& f) {
    if (!make_frame(q.N, f)) return false;
    l = Lambert{vmax0(sanitize(q.albedo)), false};
    return true;
  }
};

} // namespace lobe::closures
