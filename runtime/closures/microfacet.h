// Microfacet lobes (Torrance-Sparrow): reflection f = F D G2 / (4 |wo.z| |wi.z|) and rough
// refraction (Walter et al. 2007)
//   f_t = (1 - F) D G2 |wi.m| |wo.m| / (|wi.z| |wo.z| (wi.m + wo.m/eta)^2)   [/ eta^2 in
//   radiance transport], with the generalised half vector m = normalize(wo + eta wi).
// One lobe type serves microfacet(), conductor_bsdf, dielectric_bsdf, generalized_schlick_bsdf
// and, with alpha below kDeltaAlpha, the delta lobes reflection() and refraction(): the lobe
// then reflects/refracts about the normal with weight F / (1 - F).
//
// Fresnel: exact dielectric (eta), exact conductor (n + ik per channel), generalised Schlick
// (f0, f90, exponent; its refraction uses eta = (1 + sqrt f0)/(1 - sqrt f0)), or 1.
// Reflection is weighted by reflection_tint * F, refraction by transmission_tint * (1 - F);
// the lobe picks one with probability proportional to the luminance of those weights.
// Sampling: visible normals (microfacet_dist.h), so the weight is ~ F G2 / G1.
// wo below the surface means "inside": the lobe flips to that side and uses 1/eta.
// Energy compensation (Kulla & Conty 2017), on by default (keyword "energy_compensation"):
//  - conductors and generalized_schlick without transmission: an extra diffuse-like lobe
//    f_ms = F_ms (1 - E(wo))(1 - E(wi)) / (pi (1 - E_avg)), E from energy.h (Fresnel 1);
//  - dielectrics (dielectric_bsdf, microfacet()): E_s(mu) = the lobe's own reflection +
//    refraction albedo on side s (energy_dielectric.h; s = the side of wo, s' the other), and
//      reflection  f = c_R,s (1 - E_s(mu_o))(1 - E_s(mu_i))  / (pi (1 - E_avg,s))
//      refraction  f = c_T,s (1 - E_s(mu_o))(1 - E_s'(mu_i)) / (pi (1 - E_avg,s'))  [/ eta^2
//                  in radiance transport], c_R,s + c_T,s = 1,
//    so a lossless untinted lobe has albedo exactly 1 (up to the tables) from either side.
//    c_T,out = 1 - F_avg(eta) (fit of Kulla & Conty) and c_T,in from the generalised
//    reciprocity c_T,out (1 - E_avg,out) = eta^2 c_T,in (1 - E_avg,in) (clamped to <= 1).
//    Reflection parts are scaled by reflection_tint, refraction parts by transmission_tint.
//    Anisotropic lobes look E up by azimuth as well (energy_dielectric.h); both tables are
//    conservative (never below the lobe's albedo), so compensation never adds energy.
// The compensation lobes are sampled by cosine, with a share proportional to their albedo.
// Thin film (thinfilm_thickness in nm > 0, thinfilm_ior): F is replaced per channel by the
// Airy-summation reflectance of film + base at 650/550/450 nm (fresnel.h); thickness 0 (or
// negative/NaN) leaves the lobe exactly as without film. Compensation tables ignore the film.
// Ranges: alpha >= 0 (clamped to [1e-4, 4]); eta > 0, |eta - 1| < 1e-4 is index-matched
// (straight pass-through, a delta lobe); colours >= 0.
#pragma once

#include "common.h"
#include "energy.h"
#include "energy_dielectric.h"
#include "fresnel.h"
#include "lobe/bsdf.h"
#include "microfacet_dist.h"

namespace lobe::closures {

enum class FresnelKind : uint8_t { One, Dielectric, Conductor, Schlick };

struct Microfacet {
  MicrofacetDistribution dist;
  bool delta = false;
  FresnelKind fresnel = FresnelKind::One;
  float eta = 1.0f;      // dielectric / refraction IOR (inside over outside)
  Vec3 n, k;             // conductor
  Vec3 f0, f90;          // Schlick
  float exponent = 5.0f; // Schlick
  Vec3 refl_tint{1, 1, 1}, trans_tint{0, 0, 0};
  float film_d = 0.0f, film_n = 1.5f; // thin film (nm, index); film_d = 0: none
  bool ms = false;                    // Kulla-Conty compensation lobe (conductor form)
  Vec3 ms_color;                      // F_ms / (pi (1 - E_avg))
  // Dielectric compensation, per side of wo (0: relative IOR eta, 1: 1/eta): c_R, c_T and
  // kr = c_R / (pi (1 - E_avg,s)), kt = c_T / (pi (1 - E_avg,s')).
  struct DielMs {
    float cr = 0, ct = 0, kr = 0, kt = 0;
  };
  bool ms_diel = false;
  DielMs dms[2];
  bool ms_aniso = false; // anisotropic: E from the azimuth-dependent table at ac
  AnisoCoord ac;

  static constexpr bool kOneSided = true;

  bool refracts() const { return trans_tint.x > 0 || trans_tint.y > 0 || trans_tint.z > 0; }
  bool reflects() const { return refl_tint.x > 0 || refl_tint.y > 0 || refl_tint.z > 0; }
  uint32_t flags() const {
    uint32_t f = (reflects() ? kLobeReflect : 0u) | (refracts() ? kLobeTransmit : 0u);
    return f | (delta ? kLobeSpecular : kLobeGlossy);
  }

  // Fresnel reflectance for cosine c on the side whose relative IOR is `e`.
  Vec3 F(float c, float e) const {
    if (film_d > 0.0f) return F_film(c, e);
    switch (fresnel) {
    case FresnelKind::One:
      return splat(1.0f);
    case FresnelKind::Dielectric:
      return splat(fresnel_dielectric(c, e));
    case FresnelKind::Conductor:
      return fresnel_conductor(c, n, k);
    case FresnelKind::Schlick: {
      if (e < 1.0f) { // from inside: Schlick at the transmitted angle, TIR gives 1
        float s2t = (1.0f - c * c) / (e * e);
        if (s2t >= 1.0f) return splat(1.0f);
        c = safe_sqrt(1.0f - s2t);
      }
      return fresnel_schlick(c, f0, f90, exponent);
    }
    }
    return splat(1.0f);
  }

  // Thin film on the outer surface, per RGB wavelength: outside index 1, base index eta
  // (dielectric), n + ik (conductor) or (1 + sqrt f0)/(1 - sqrt f0) per channel (Schlick).
  // From inside (e != eta) the stack is traversed base -> film -> outside.
  Vec3 F_film(float c, float e) const {
    Vec3 r;
    for (int ch = 0; ch < 3; ++ch) {
      Cpx base{eta, 0.0f};
      if (fresnel == FresnelKind::Conductor) base = {(&n.x)[ch], (&k.x)[ch]};
      if (fresnel == FresnelKind::Schlick) {
        float s = std::sqrt(clampf((&f0.x)[ch], 0.0f, 0.998f));
        base = {(1.0f + s) / (1.0f - s), 0.0f};
      }
      bool inside = fresnel != FresnelKind::Conductor && e != eta;
      (&r.x)[ch] =
          inside ? fresnel_thin_film(c, base.re, film_n, {1.0f, 0.0f}, film_d, kFilmLambda[ch])
                 : fresnel_thin_film(c, 1.0f, film_n, base, film_d, kFilmLambda[ch]);
    }
    return r;
  }

  // Fresnel reflectance at a refracting microfacet from both cosines (c_above with the normal's
  // side, c_below on the other; both > 0), for the side whose relative IOR is `e`. Needing no
  // transmitted cosine from Snell's law, it avoids sqrt(1 - (1 - c^2)/e^2), whose cancellation
  // near the critical angle costs ~1e-3 relative from inside, and it is the same float
  // expression from either side (generalised reciprocity).
  Vec3 F_refract(float c_above, float c_below, float e) const {
    if (film_d > 0.0f) return F(e == eta ? c_above : c_below, e);
    switch (fresnel) {
    case FresnelKind::Dielectric:
      return splat(fresnel_dielectric(c_above, c_below, eta));
    case FresnelKind::Schlick: // Schlick at the outside angle, as F() from either side
      return fresnel_schlick(c_above, f0, f90, exponent);
    default:
      return F(e == eta ? c_above : c_below, e);
    }
  }

  // Reflection and refraction weights at cosine c, and the probability of reflecting.
  float split(float c, float e, Vec3& fr, Vec3& ft) const { return split_F(F(c, e), e, fr, ft); }
  float split_F(const Vec3& f, float e, Vec3& fr, Vec3& ft) const {
    fr = f * refl_tint;
    ft = (splat(1.0f) - f) * trans_tint;
    if (e == 1.0f && !delta) ft = {}; // index-matched rough refraction is handled as delta
    float lr = luminance(fr), lt = luminance(ft);
    return lr + lt > 0.0f ? lr / (lr + lt) : 0.0f;
  }

  float E(float mu) const { return energy_E(mu, alpha_eff(), dist.beckmann); }
  // Dielectric E at cosine mu and azimuth c (= cos^2 from the tangent; anisotropic lobes only).
  float Ed(float mu, float c, float e) const {
    return ms_aniso ? dielectric_E_aniso(mu, c, ac, e, dist.beckmann)
                    : dielectric_E(mu, alpha_eff(), e, dist.beckmann);
  }
  float Ed(const Vec3& w, float e) const {
    return Ed(std::fabs(w.z), ms_aniso ? azimuth_c(w) : 1.0f, e);
  }
  float alpha_eff() const { return std::sqrt(dist.ax * dist.ay); }
  int side(float e) const { return e == eta ? 0 : 1; }

  // Albedos of the compensation lobe at wo (reflected, transmitted part; importance). edo is
  // Ed(wo, e), looked up once by the caller (used when ms_diel).
  void ms_albedo(const Vec3& wo, float e, float edo, Vec3& ar, Vec3& at) const {
    ar = at = Vec3{};
    if (ms)
      ar = ms_color * (kPi * (1.0f - E(wo.z)) * (1.0f - energy_E_avg(alpha_eff(), dist.beckmann)));
    if (ms_diel) {
      const DielMs& s = dms[side(e)];
      float lo = 1.0f - edo;
      ar = refl_tint * (s.cr * lo);
      at = trans_tint * (s.ct * lo);
    }
  }
  // Probability p of sampling the compensation lobe at wo, and q, its reflected share.
  void ms_probs(const Vec3& wo, float e, float edo, float& p, float& q) const {
    p = 0.0f, q = 1.0f;
    if (!ms && !ms_diel) return;
    Vec3 ar, at;
    ms_albedo(wo, e, edo, ar, at);
    float mr = luminance(ar), mt = luminance(at), m = mr + mt;
    Vec3 f = F(wo.z, e);
    float ss = ms ? luminance(refl_tint * f) * E(wo.z)
                  : luminance(refl_tint * f + trans_tint * (splat(1.0f) - f)) * edo;
    p = m + ss > 0.0f ? clampf(m / (m + ss), 0.0f, 0.9f) : 0.0f;
    q = m > 0.0f ? mr / m : 1.0f;
  }

  BsdfEval eval(Vec3 wo, Vec3 wi, Transport mode) const {
    float e = eta;
    if (wo.z < 0.0f) {
      wo.z = -wo.z, wi.z = -wi.z, e = 1.0f / eta;
    }
    if (!(wo.z > 0.0f) || wi.z == 0.0f || delta) return {};
    return eval_above(wo, wi, e, mode);
  }

  // Ed(wo, e) when the dielectric compensation needs it (else 0): one look-up per wo.
  float Ed_wo(const Vec3& wo, float e) const { return ms_diel ? Ed(wo, e) : 0.0f; }

  // eval with wo.z > 0 and e the relative IOR below the surface.
  BsdfEval eval_above(const Vec3& wo, const Vec3& wi, float e, Transport mode) const {
    return eval_above(wo, wi, e, Ed_wo(wo, e), mode);
  }
  BsdfEval eval_above(const Vec3& wo, const Vec3& wi, float e, float edo, Transport mode) const {
    BsdfEval r = wi.z > 0.0f ? eval_reflect(wo, wi, e) : eval_refract(wo, wi, e, mode);
    if (!ms && !ms_diel) return r;
    float p, q;
    ms_probs(wo, e, edo, p, q);
    float c = std::fabs(wi.z);
    if (ms && wi.z > 0.0f) r.value += ms_color * ((1.0f - E(wo.z)) * (1.0f - E(wi.z)) * c);
    if (ms_diel) r.value += diel_ms_value(edo, wi, e, mode);
    r.pdf = (1.0f - p) * r.pdf + p * (wi.z > 0.0f ? q : 1.0f - q) * c * kInvPi;
    return r;
  }

  // Dielectric compensation value (times |wi.z|) for wo (edo = Ed(wo, e)) on the side with
  // relative IOR e.
  Vec3 diel_ms_value(float edo, const Vec3& wi, float e, Transport mode) const {
    const DielMs& s = dms[side(e)];
    float lo = 1.0f - edo, wz = wi.z;
    if (wz > 0.0f) return refl_tint * (s.kr * lo * (1.0f - Ed(wi, e)) * wz);
    float v = s.kt * lo * (1.0f - Ed(wi, 1.0f / e)) * -wz;
    if (mode == Transport::Radiance) v /= e * e;
    return trans_tint * v;
  }

  BsdfEval eval_reflect(const Vec3& wo, const Vec3& wi, float e) const {
    Vec3 m;
    float c = half_vector(wo, wi, m);
    if (!(c > 0.0f) || !(m.z > 0.0f)) return {};
    Vec3 fr, ft;
    float pr = split(c, e, fr, ft);
    float D = dist.D(m);
    float v = D * dist.G2(wo, wi) / (4.0f * wo.z);
    return {fr * v, pr * dist.G1(wo) * D / (4.0f * wo.z)};
  }

  BsdfEval eval_refract(const Vec3& wo, const Vec3& wi, float e, Transport mode) const {
    if (e == 1.0f) return {};
    // ht = e wi + wo, m = +-ht/|ht|: then ci + co/e = (ht/e).m = +-|ht|/e, so Walter's
    // denominator (ci + co/e)^2 is |ht|^2/e^2, without the cancellation of ci against co/e.
    Vec3 ht = wi * e + wo;
    float l2 = dot(ht, ht);
    if (!(l2 > 0.0f) || !(l2 < INFINITY)) return {};
    Vec3 m = ht * ((ht.z < 0.0f ? -1.0f : 1.0f) / std::sqrt(l2));
    float ci = dot(wi, m), co = dot(wo, m);
    if (!(m.z > 0.0f) || !(ci < 0.0f) || !(co > 0.0f)) return {}; // back-facing microfacet
    Vec3 fr, ft;
    bool above = e == eta; // wo on the normal's side
    float pr = split_F(F_refract(above ? co : -ci, above ? -ci : co, e), e, fr, ft);
    float denom = l2 / (e * e);
    float D = dist.D(m);
    float f = D * dist.G2(wo, wi) * std::fabs(ci * co) / (wo.z * denom); // times |wi.z|
    if (mode == Transport::Radiance) f /= e * e;
    float pdf = (1.0f - pr) * dist.D_visible(wo, m) * std::fabs(ci) / denom;
    return {ft * f, pdf};
  }

  BsdfSample sample(Vec3 wo, const Vec3& u, Transport mode) const {
    float e = eta, sign = 1.0f;
    if (wo.z < 0.0f) wo.z = -wo.z, e = 1.0f / eta, sign = -1.0f;
    if (!(wo.z > 0.0f)) return {};
    BsdfSample s = delta ? sample_delta(wo, u, e, mode) : sample_rough(wo, u, e, mode);
    s.wi.z *= sign;
    return s;
  }

  BsdfSample sample_delta(const Vec3& wo, const Vec3& u, float e, Transport mode) const {
    BsdfSample s;
    Vec3 fr, ft;
    float pr = split(wo.z, e, fr, ft);
    if (luminance(fr) + luminance(ft) <= 0.0f) return s;
    if (u.z < pr) {
      s.wi = reflect_z(wo);
      s.weight = fr / pr;
      s.pdf = pr;
      s.flags = kLobeReflect | kLobeSpecular;
    } else {
      if (!refract(wo, Vec3{0, 0, 1}, e, s.wi)) return {};
      s.weight = ft / (1.0f - pr);
      if (mode == Transport::Radiance) s.weight = s.weight / (e * e);
      s.pdf = 1.0f - pr;
      s.flags = kLobeTransmit | kLobeSpecular;
      s.eta = e;
    }
    if (s.wi.z == 0.0f) return {};
    return s;
  }

  BsdfSample sample_rough(const Vec3& wo, Vec3 u, float e, Transport mode) const {
    BsdfSample s;
    float p, q, edo = Ed_wo(wo, e);
    ms_probs(wo, e, edo, p, q);
    if (u.z < p) { // compensation lobe: cosine-distributed, reflected or transmitted
      s.wi = sample_cosine_hemisphere(u.x, u.y);
      s.flags = kLobeReflect | kLobeDiffuse;
      if (u.z >= p * q) {
        s.wi.z = -s.wi.z;
        s.flags = kLobeTransmit | kLobeDiffuse;
        s.eta = e;
      }
    } else {
      u.z = minf((u.z - p) / (1.0f - p), kOneMinusEpsilon);
      Vec3 m = dist.sample_visible(wo, u.x, u.y);
      float c = dot(wo, m);
      if (!(c > 0.0f)) return s;
      Vec3 fr, ft;
      float pr = split(c, e, fr, ft);
      if (u.z < pr) {
        s.wi = reflect(wo, m);
        s.flags = kLobeReflect | kLobeGlossy;
      } else {
        if (!refract(wo, m, e, s.wi)) return s;
        s.flags = kLobeTransmit | kLobeGlossy;
        s.eta = e;
        if (!(s.wi.z < 0.0f)) return s;
      }
    }
    s.wi = normalize(s.wi); // evaluated at the direction returned (see dispatch.h)
    if (s.wi.z == 0.0f || ((s.flags & kLobeReflect) && s.wi.z < 0.0f)) return s;
    BsdfEval ev = eval_above(wo, s.wi, e, edo, mode);
    if (!(ev.pdf > 0.0f)) return s;
    s.pdf = ev.pdf;
    s.weight = ev.value / ev.pdf;
    return s;
  }

  // Estimate: (F(wo.z) reflection_tint + (1 - F) transmission_tint) E(wo.z), E the dielectric
  // table (reflection + refraction) for dielectric Fresnel, the Fresnel-1 table otherwise,
  // plus the compensation lobe's albedo.
  Vec3 albedo(Vec3 wo) const {
    float e = eta;
    if (wo.z < 0.0f) wo.z = -wo.z, e = 1.0f / eta;
    if (!(wo.z > 0.0f)) return {};
    Vec3 fr, ft;
    split(wo.z, e, fr, ft);
    float Er = delta ? 1.0f : E(wo.z), Et = Er;
    bool split_e = !delta && fresnel == FresnelKind::Dielectric;
    float edo = split_e || ms_diel ? Ed(wo, e) : 0.0f;
    if (split_e) { // split Ed = F Er + (1 - F) Et
      float f = F(wo.z, e).x;
      Et = f < 1.0f ? clampf((edo - f * Er) / (1.0f - f), 0.0f, 1.0f) : 0.0f;
    }
    Vec3 a = fr * Er + ft * Et, ar, at;
    ms_albedo(wo, e, edo, ar, at);
    return a + ar + at;
  }
};

} // namespace lobe::closures
