// From a registry id and a parameter block to a lobe in its local frame, and the generic
// world-space wrappers around any lobe. Shared by the native API (closures.cpp) and the
// bitcode entries (bitcode.cpp), where the id is a constant and the switch folds away.
//
// A lobe type L provides, in its local frame (normal = +z):
//   LobeEval eval(wo, wi[, mode]);  LobeSample sample(wo, u[, mode]);  Vec3 albedo(wo);
//   uint32_t flags();  and optionally `static constexpr bool kOneSided = true` for lobes that
// distinguish inside from outside (dielectrics). Other lobes are two-sided: when wo is below
// the shading normal the frame is mirrored so that they see wo above it.
#pragma once

#include "common.h"
#include "diffuse.h"
#include "glossy.h"
#ifndef LOBE_BITCODE
#include "measured.h"
#endif
#include "lobe/bsdf.h"
#include "microfacet_setup.h"
#include "params.h"
#include "sheen.h"
#include "toon.h"

namespace lobe::closures {

template <class P> const P& as(const unsigned char* p) { return as_params<P>(p); }

// Calls fn(lobe, frame) for closure `id` and returns true; false when `id` has no BSDF lobe or
// its parameters are degenerate (zero/NaN normal).
template <class Fn> bool with_lobe(int id, const unsigned char* p, Fn&& fn) {
  Frame f;
  switch (id) {
  case kDiffuseId:
  case kTranslucentId: {
    if (!make_frame(as<DiffuseParams>(p).N, f)) return false;
    fn(Lambert{splat(1.0f), id == kTranslucentId}, f);
    return true;
  }
  case kTranslucentBsdfId: {
    const auto& q = as<AlbedoParams>(p);
    if (!make_frame(q.N, f)) return false;
    fn(Lambert{vmax0(q.albedo), true}, f);
    return true;
  }
  case kOrenNayarId: {
    const auto& q = as<OrenNayarParams>(p);
    if (!make_frame(q.N, f)) return false;
    fn(OrenNayar::make(splat(1.0f), q.sigma), f);
    return true;
  }
  case kOrenNayarDiffuseId: {
    const auto& q = as<OrenNayarDiffuseParams>(p);
    if (!make_frame(q.N, f)) return false;
    float r = clampf(q.roughness, 0.0f, 1.0f);
    fn(FujiiOrenNayar{vmax0(q.albedo), r == r ? r : 0.0f, q.energy_compensation != 0}, f);
    return true;
  }
  case kBurleyId: {
    const auto& q = as<AlbedoRoughnessParams>(p);
    if (!make_frame(q.N, f)) return false;
    float r = clampf(q.roughness, 0.0f, 1.0f);
    fn(Burley{vmax0(q.albedo), r == r ? r : 0.0f}, f);
    return true;
  }
  case kMicrofacetId: {
    const auto& q = as<MicrofacetParams>(p);
    if (!make_frame(q.N, q.U, f)) return false;
    fn(make_microfacet(q.distribution, q.xalpha, q.yalpha, q.eta, q.refract, q.energy_compensation),
       f);
    return true;
  }
  case kConductorId: {
    const auto& q = as<ConductorParams>(p);
    if (!make_frame(q.N, q.U, f)) return false;
    fn(make_conductor(q), f);
    return true;
  }
  case kDielectricId: {
    const auto& q = as<DielectricParams>(p);
    if (!make_frame(q.N, q.U, f)) return false;
    fn(make_dielectric(q), f);
    return true;
  }
  case kGeneralizedSchlickId: {
    const auto& q = as<GeneralizedSchlickParams>(p);
    if (!make_frame(q.N, q.U, f)) return false;
    fn(make_generalized_schlick(q), f);
    return true;
  }
  case kReflectionId: { // eta 0 (OSL's reflection(N)): no Fresnel, a perfect mirror
    const auto& q = as<ReflectionParams>(p);
    if (!make_frame(q.N, f)) return false;
    fn(make_specular(q.eta > 0.0f ? q.eta : 0.0f, false), f);
    return true;
  }
  case kRefractionId: {
    const auto& q = as<ReflectionParams>(p);
    if (!make_frame(q.N, f)) return false;
    fn(make_specular(q.eta > 0.0f ? q.eta : 1.0f, true), f);
    return true;
  }
  case kPhongId: {
    const auto& q = as<PhongParams>(p);
    if (!make_frame(q.N, f)) return false;
    fn(Phong{clampf(q.exponent == q.exponent ? q.exponent : 0.0f, 0.0f, 1e6f)}, f);
    return true;
  }
  case kBlinnPhongId: {
    const auto& q = as<PhongParams>(p);
    if (!make_frame(q.N, f)) return false;
    fn(BlinnPhong::make(q.exponent), f);
    return true;
  }
  case kWardId: {
    const auto& q = as<WardParams>(p);
    if (!make_frame(q.N, q.T, f)) return false;
    auto c = [](float a) { return a == a ? clampf(a, 1e-3f, 4.0f) : 1e-3f; };
    fn(Ward{MicrofacetDistribution::make(c(q.ax), c(q.ay), true)}, f);
    return true;
  }
  case kSheenId: {
    const auto& q = as<AlbedoRoughnessParams>(p);
    if (!make_frame(q.N, f)) return false;
    float r = q.roughness == q.roughness ? clampf(q.roughness, 0.01f, 1.0f) : 1.0f;
    fn(Sheen::make(vmax0(sanitize(q.albedo)), r), f);
    return true;
  }
  case kSubsurfaceBssrdfId: { // Lobe has no subsurface transport: diffuse with the albedo
    const auto& q = as<SubsurfaceBssrdfParams>(p);
    if (!make_frame(q.N, f)) return false;
    fn(Lambert{vmax0(sanitize(q.albedo)), false}, f);
    return true;
  }
  case kToonId: {
    const auto& q = as<ToonParams>(p);
    if (!make_frame(q.N, f)) return false;
    fn(Toon::make(sanitize(q.albedo), sanitize(q.specular), q.shininess, q.bands, q.softness), f);
    return true;
  }
#ifndef LOBE_BITCODE
  case kMeasuredId: {
    const auto& q = as<MeasuredParams>(p);
    const MeasuredTable* t = measured_table(q.filename);
    if (!t || !make_frame(q.N, f)) return false;
    fn(Measured{t, vmax0(sanitize(q.tint))}, f);
    return true;
  }
#endif
  default:
    return false;
  }
}

template <class L> constexpr bool is_one_sided() {
  if constexpr (requires { L::kOneSided; }) return L::kOneSided;
  return false;
}

// Local directions for lobe L; mirrored across the tangent plane for two-sided lobes viewed
// from below. Returns the mirror sign (+1/-1) to undo it on sampled directions.
template <class L> float to_local(const Frame& f, const Vec3& wo, Vec3& o) {
  o = f.to_local(wo);
  if (!is_one_sided<L>() && o.z < 0.0f) {
    o.z = -o.z;
    return -1.0f;
  }
  return 1.0f;
}

template <class L>
LobeEval eval_lobe(const L& l, const Frame& f, const Vec3& wo, const Vec3& wi, Transport mode) {
  Vec3 o, i = f.to_local(wi);
  i.z *= to_local<L>(f, wo, o);
  LobeEval e;
  if constexpr (requires { l.eval(o, i, mode); })
    e = l.eval(o, i, mode);
  else
    e = l.eval(o, i);
  e.value = sanitize(e.value);
  if (!(e.pdf > 0.0f && e.pdf < INFINITY)) e.pdf = 0.0f;
  return e;
}

template <class L>
LobeSample sample_lobe(const L& l, const Frame& f, const Vec3& wo, const Vec3& u, Transport mode) {
  Vec3 o;
  float sign = to_local<L>(f, wo, o);
  Vec3 uc = {clampf(u.x, 0.0f, kOneMinusEpsilon), clampf(u.y, 0.0f, kOneMinusEpsilon),
             clampf(u.z, 0.0f, kOneMinusEpsilon)};
  LobeSample s;
  if constexpr (requires { l.sample(o, uc, mode); })
    s = l.sample(o, uc, mode);
  else
    s = l.sample(o, uc);
  if (!s.ok || !(s.pdf > 0.0f && s.pdf < INFINITY)) return {};
  s.wi.z *= sign;
  // The lobe evaluated s.wi; a direction that is already unit is not normalised again, since
  // one ulp moves sharp lobes at grazing incidence by more than 1e-4 and then sample() would
  // disagree with eval()/pdf() at the direction it returns (exact for an orthonormal frame
  // aligned with the axes; otherwise to the rounding of the frame change).
  s.wi = f.to_world(s.wi);
  if (!(std::fabs(dot(s.wi, s.wi) - 1.0f) <= 1e-6f)) s.wi = normalize(s.wi);
  s.weight = sanitize(s.weight);
  if (is_zero(s.wi)) return {};
  return s;
}

template <class L> Vec3 albedo_lobe(const L& l, const Frame& f, const Vec3& wo) {
  Vec3 o;
  to_local<L>(f, wo, o);
  return sanitize(l.albedo(o));
}

} // namespace lobe::closures
