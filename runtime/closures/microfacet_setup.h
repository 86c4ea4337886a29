// Parameter blocks -> Microfacet lobes for microfacet(), conductor_bsdf, dielectric_bsdf,
// generalized_schlick_bsdf, reflection() and refraction(): one place that decides the Fresnel
// mode, tints, delta threshold, index matching and Kulla-Conty compensation of each.
#pragma once

#include "microfacet.h"
#include "params.h"

namespace lobe::closures {

struct MicrofacetParams {
  Str distribution;
  Vec3 N, U;
  float xalpha, yalpha, eta;
  int refract;
  int energy_compensation;
  Str label;
};
struct ReflectionParams {
  Vec3 N;
  float eta;
  Str label;
}; // reflection(N, eta), refraction
struct ConductorParams {
  Vec3 N, U;
  float roughness_x, roughness_y;
  Color3 ior, extinction;
  Str distribution;
  float thinfilm_thickness, thinfilm_ior;
  int energy_compensation;
  Str label;
};
struct DielectricParams {
  Vec3 N, U;
  Color3 reflection_tint, transmission_tint;
  float roughness_x, roughness_y, ior;
  Str distribution;
  float thinfilm_thickness, thinfilm_ior;
  int energy_compensation;
  Str label;
};
struct GeneralizedSchlickParams {
  Vec3 N, U;
  Color3 reflection_tint, transmission_tint;
  float roughness_x, roughness_y;
  Color3 f0, f90;
  float exponent;
  Str distribution;
  float thinfilm_thickness, thinfilm_ior;
  int energy_compensation;
  Str label;
};

inline bool is_beckmann(const char* s) { return s && (s[0] == 'b' || s[0] == 'B'); }

// NaN/negative IOR: index-matched; within 1e-4 of 1: exactly 1 (pass-through).
inline float sane_eta(float e) {
  if (!(e > 0.0f) || !(e < 1e6f)) return 1.0f;
  return std::fabs(e - 1.0f) < 1e-4f ? 1.0f : e;
}

inline Microfacet microfacet_base(float ax, float ay, const char* distribution) {
  Microfacet m;
  float a = maxf(ax == ax ? ax : 0.0f, ay == ay ? ay : 0.0f);
  m.delta = !(a >= kDeltaAlpha);
  m.dist = MicrofacetDistribution::make(ax, ay, is_beckmann(distribution));
  return m;
}

// Kulla-Conty compensation for a reflection-only lobe with hemispherical Fresnel average fa.
inline void enable_compensation(Microfacet& m, const Vec3& fa) {
  if (m.delta || m.refracts()) return;
  float ea = energy_E_avg(m.alpha_eff(), m.dist.beckmann);
  if (!(1.0f - ea > 1e-4f)) return;
  Vec3 den = splat(1.0f) - fa * (1.0f - ea);
  Vec3 fms = fa * fa * ea / Vec3{maxf(den.x, 1e-6f), maxf(den.y, 1e-6f), maxf(den.z, 1e-6f)};
  m.ms = true;
  m.ms_color = fms * (1.0f / (kPi * (1.0f - ea)));
}

// Hemispherical average of the dielectric Fresnel for relative IOR e (Kulla & Conty's fit
// for e > 1; from the denser side 1 - F_avg(1/e) = (1 - F_avg(e)) e^2).
inline float fresnel_dielectric_avg(float e) {
  if (e >= 1.0f) return (e - 1.0f) / (4.08567f + 1.00071f * e);
  float r = 1.0f / e;
  return 1.0f - (1.0f - (r - 1.0f) / (4.08567f + 1.00071f * r)) * e * e;
}

// Kulla-Conty compensation for a rough dielectric (reflection and/or refraction; see
// microfacet.h): per side, c_T from the Fresnel average outside and generalised reciprocity.
inline void enable_dielectric_compensation(Microfacet& m) {
  if (m.delta || m.eta == 1.0f) return;
  float a = m.alpha_eff(), e0 = m.eta;
  m.ms_aniso = m.dist.ax != m.dist.ay;
  if (m.ms_aniso) m.ac = aniso_coord(m.dist.ax, m.dist.ay, e0);
  auto avg = [&](float e) {
    return m.ms_aniso ? dielectric_E_avg_aniso(m.ac, e, m.dist.beckmann)
                      : dielectric_E_avg(a, e, m.dist.beckmann);
  };
  float l0 = 1.0f - avg(e0);
  float l1 = 1.0f - avg(1.0f / e0);
  if (!(l0 > 1e-5f) || !(l1 > 1e-5f)) return;
  float ct0 = 1.0f - fresnel_dielectric_avg(e0);
  float ct1 = ct0 * l0 / (e0 * e0 * l1);
  if (ct1 > 1.0f) ct1 = 1.0f, ct0 = e0 * e0 * l1 / l0;
  m.dms[0] = {1.0f - ct0, ct0, (1.0f - ct0) / (kPi * l0), ct0 / (kPi * l1)};
  m.dms[1] = {1.0f - ct1, ct1, (1.0f - ct1) / (kPi * l1), ct1 / (kPi * l0)};
  m.ms_diel = true;
}

// Thin film from the keywords: a thickness that is not a positive finite number means none.
inline void set_film(Microfacet& m, float thickness, float ior) {
  if (!(thickness > 0.0f && thickness < 1e6f)) return;
  m.film_d = thickness;
  m.film_n = ior > 0.0f && ior < 1e3f ? ior : 1.0f;
}

inline Microfacet make_microfacet(const char* dist, float ax, float ay, float eta, int refract,
                                  int ec) {
  Microfacet m = microfacet_base(ax, ay, dist);
  m.fresnel = FresnelKind::Dielectric;
  m.eta = sane_eta(eta);
  m.refl_tint = refract == 1 ? Vec3{} : splat(1.0f);
  m.trans_tint = refract >= 1 ? splat(1.0f) : Vec3{};
  if (m.refracts() && m.eta == 1.0f) m.delta = true;
  if (ec) enable_dielectric_compensation(m);
  return m;
}

inline Microfacet make_conductor(const ConductorParams& p) {
  Microfacet m = microfacet_base(p.roughness_x, p.roughness_y, p.distribution);
  m.fresnel = FresnelKind::Conductor;
  m.n = vmax0(sanitize(p.ior));
  m.k = vmax0(sanitize(p.extinction));
  set_film(m, p.thinfilm_thickness, p.thinfilm_ior);
  if (p.energy_compensation)
    enable_compensation(m, fresnel_average([&](float mu) { return m.F(mu, 1.0f); }));
  return m;
}

inline Microfacet make_dielectric(const DielectricParams& p) {
  Microfacet m = microfacet_base(p.roughness_x, p.roughness_y, p.distribution);
  m.fresnel = FresnelKind::Dielectric;
  m.eta = sane_eta(p.ior);
  m.refl_tint = sanitize(p.reflection_tint);
  m.trans_tint = sanitize(p.transmission_tint);
  if (m.refracts() && m.eta == 1.0f) m.delta = true;
  set_film(m, p.thinfilm_thickness, p.thinfilm_ior);
  if (p.energy_compensation) enable_dielectric_compensation(m);
  return m;
}

inline Microfacet make_generalized_schlick(const GeneralizedSchlickParams& p) {
  Microfacet m = microfacet_base(p.roughness_x, p.roughness_y, p.distribution);
  m.fresnel = FresnelKind::Schlick;
  m.f0 = sanitize(p.f0);
  m.f90 = sanitize(p.f90);
  m.exponent = p.exponent > 0.0f && p.exponent < 1e4f ? p.exponent : 5.0f;
  m.refl_tint = sanitize(p.reflection_tint);
  m.trans_tint = sanitize(p.transmission_tint);
  float s = std::sqrt(clampf((m.f0.x + m.f0.y + m.f0.z) / 3.0f, 0.0f, 0.998f));
  m.eta = sane_eta((1.0f + s) / (1.0f - s));
  if (m.refracts() && m.eta == 1.0f) m.delta = true;
  set_film(m, p.thinfilm_thickness, p.thinfilm_ior);
  if (p.energy_compensation)
    enable_compensation(m, fresnel_average([&](float mu) { return m.F(mu, 2.0f) * m.refl_tint; }));
  return m;
}

// reflection(N) (eta <= 0: Fresnel 1), reflection(N, eta), refraction(N, eta).
inline Microfacet make_specular(float eta, bool refraction) {
  Microfacet m;
  m.delta = true;
  m.fresnel = eta > 0.0f ? FresnelKind::Dielectric : FresnelKind::One;
  m.eta = eta > 0.0f ? sane_eta(eta) : 1.0f;
  m.refl_tint = refraction ? Vec3{} : splat(1.0f);
  m.trans_tint = refraction ? splat(1.0f) : Vec3{};
  return m;
}

// ---- registry entries (params.h) ------------------------------------------------------------

template <> struct Closure<closure_id::microfacet> {
  using Params = MicrofacetParams;
  static constexpr size_t kOffsets[] = {offsetof(Params, distribution),
                                        offsetof(Params, N),
                                        offsetof(Params, U),
                                        offsetof(Params, xalpha),
                                        offsetof(Params, yalpha),
                                        offsetof(Params, eta),
                                        offsetof(Params, refract),
                                        offsetof(Params, energy_compensation),
                                        offsetof(Params, label)};
  using Lobe = Microfacet;
  static bool make(const Params& q, Lobe& l, Frame& f) {
    if (!make_frame(q.N, q.U, f)) return false;
    l = make_microfacet(q.distribution, q.xalpha, q.yalpha, q.eta, q.refract,
                        q.energy_compensation);
    return true;
  }
};

template <> struct Closure<closure_id::conductor_bsdf> {
  using Params = ConductorParams;
  static constexpr size_t kOffsets[] = {offsetof(Params, N),
                                        offsetof(Params, U),
                                        offsetof(Params, roughness_x),
                                        offsetof(Params, roughness_y),
                                        offsetof(Params, ior),
                                        offsetof(Params, extinction),
                                        offsetof(Params, distribution),
                                        offsetof(Params, thinfilm_thickness),
                                        offsetof(Params, thinfilm_ior),
                                        offsetof(Params, energy_compensation),
                                        offsetof(Params, label)};
  using Lobe = Microfacet;
  static bool make(const Params& q, Lobe& l, Frame& f) {
    if (!make_frame(q.N, q.U, f)) return false;
    l = make_conductor(q);
    return true;
  }
};

template <> struct Closure<closure_id::dielectric_bsdf> {
  using Params = DielectricParams;
  static constexpr size_t kOffsets[] = {offsetof(Params, N),
                                        offsetof(Params, U),
                                        offsetof(Params, reflection_tint),
                                        offsetof(Params, transmission_tint),
                                        offsetof(Params, roughness_x),
                                        offsetof(Params, roughness_y),
                                        offsetof(Params, ior),
                                        offsetof(Params, distribution),
                                        offsetof(Params, thinfilm_thickness),
                                        offsetof(Params, thinfilm_ior),
                                        offsetof(Params, energy_compensation),
                                        offsetof(Params, label)};
  using Lobe = Microfacet;
  static bool make(const Params& q, Lobe& l, Frame& f) {
    if (!make_frame(q.N, q.U, f)) return false;
    l = make_dielectric(q);
    return true;
  }
};

template <> struct Closure<closure_id::generalized_schlick_bsdf> {
  using Params = GeneralizedSchlickParams;
  static constexpr size_t kOffsets[] = {offsetof(Params, N),
                                        offsetof(Params, U),
                                        offsetof(Params, reflection_tint),
                                        offsetof(Params, transmission_tint),
                                        offsetof(Params, roughness_x),
                                        offsetof(Params, roughness_y),
                                        offsetof(Params, f0),
                                        offsetof(Params, f90),
                                        offsetof(Params, exponent),
                                        offsetof(Params, distribution),
                                        offsetof(Params, thinfilm_thickness),
                                        offsetof(Params, thinfilm_ior),
                                        offsetof(Params, energy_compensation),
                                        offsetof(Params, label)};
  using Lobe = Microfacet;
  static bool make(const Params& q, Lobe& l, Frame& f) {
    if (!make_frame(q.N, q.U, f)) return false;
    l = make_generalized_schlick(q);
    return true;
  }
};

// reflection(N, eta): eta 0 (OSL's reflection(N)) is a perfect mirror without Fresnel.
template <> struct Closure<closure_id::reflection> {
  using Params = ReflectionParams;
  static constexpr size_t kOffsets[] = {offsetof(Params, N), offsetof(Params, eta),
                                        offsetof(Params, label)};
  using Lobe = Microfacet;
  static bool make(const Params& q, Lobe& l, Frame& f) {
    if (!make_frame(q.N, f)) return false;
    l = make_specular(q.eta > 0.0f ? q.eta : 0.0f, false);
    return true;
  }
};

template <> struct Closure<closure_id::refraction> {
  using Params = ReflectionParams;
  static constexpr size_t kOffsets[] = {offsetof(Params, N), offsetof(Params, eta),
                                        offsetof(Params, label)};
  using Lobe = Microfacet;
  static bool make(const Params& q, Lobe& l, Frame& f) {
    if (!make_frame(q.N, f)) return false;
    l = make_specular(q.eta > 0.0f ? q.eta : 1.0f, true);
    return true;
  }
};

} // namespace lobe::closures
