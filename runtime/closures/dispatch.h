// From a registry id and a parameter block to a lobe in its local frame, and the generic
// world-space wrappers around any lobe. The family headers are included here (a new family is
// one more include); the switch over ids and the checks against the registry are generated
// from its table (LOBE_CLOSURE_TABLE), so a new closure is its family's Closure<> plus its
// registry row. Shared by the native API (closures.cpp) and the
// bitcode entries (bitcode.cpp), where the id is a constant and the switch folds away.
//
// A lobe type L provides, in its local frame (normal = +z):
//   BsdfEval eval(wo, wi[, mode]);  BsdfSample sample(wo, u[, mode]);  Vec3 albedo(wo);
//   uint32_t flags();  and optionally `static constexpr bool kOneSided = true` for lobes that
// distinguish inside from outside (dielectrics). Other lobes are two-sided: when wo is below
// the shading normal the frame is mirrored so that they see wo above it.
#pragma once

#include "common.h"
#include "components.h"
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

#include <new>
#include <type_traits>

namespace lobe::closures {

template <class P> const P& as(const unsigned char* p) { return as_params<P>(p); }

// Closure<Id> has a lobe (a BSDF entry's implementation, params.h).
template <int Id> constexpr bool has_lobe() {
  return requires { typename Closure<Id>::Lobe; };
}

// What the registry says about entry Id, checked against its family's Closure<Id>: the
// parameter struct has the registry's layout, and a BSDF entry has a lobe (in the bitcode,
// unless the entry is native-only). Nothing to check for entries out of the families' reach.
template <int Id> constexpr bool implementation_matches_registry() {
  using C = Closure<Id>;
  const registry::ClosureEntry& e = registry::table::kClosures[Id];
#ifdef LOBE_BITCODE
  if (e.flags & registry::kNativeOnly) return true;
#endif
  if constexpr (std::is_void_v<typename C::Params>) {
    if (!e.params.empty()) return false;
  } else {
    if (!layout_is(Id, C::kOffsets, sizeof(typename C::Params))) return false;
  }
  bool bsdf = (e.flags & (registry::kReflect | registry::kTransmit)) != 0;
  return bsdf == has_lobe<Id>();
}
#define LOBE_CHECK(key, ...)                                                                       \
  static_assert(implementation_matches_registry<closure_id::key>(),                                \
                "closure '" #key "': its Closure<> (family header) does not match the registry");
LOBE_CLOSURE_TABLE(LOBE_CHECK)
#undef LOBE_CHECK

// Calls fn(lobe, frame) for entry Id's lobe set up from parameter block p.
template <int Id, class Fn> bool with_closure(const unsigned char* p, Fn& fn) {
  if constexpr (has_lobe<Id>()) {
    using C = Closure<Id>;
    typename C::Lobe lobe;
    Frame f;
    if (!C::make(as<typename C::Params>(p), lobe, f)) return false;
    fn(lobe, f);
    return true;
  } else {
    return false;
  }
}

// Calls fn(lobe, frame) for closure `id` and returns true; false when `id` has no BSDF lobe or
// its parameters are degenerate (zero/NaN normal). The switch is generated from the registry.
template <class Fn> bool with_lobe(int id, const unsigned char* p, Fn&& fn) {
  switch (id) {
#define LOBE_CASE(key, ...)                                                                        \
  case closure_id::key:                                                                            \
    return with_closure<closure_id::key>(p, fn);
    LOBE_CLOSURE_TABLE(LOBE_CASE)
#undef LOBE_CASE
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
BsdfEval eval_lobe(const L& l, const Frame& f, const Vec3& wo, const Vec3& wi, Transport mode) {
  Vec3 o, i = f.to_local(wi);
  i.z *= to_local<L>(f, wo, o);
  BsdfEval e;
  if constexpr (requires { l.eval(o, i, mode); })
    e = l.eval(o, i, mode);
  else
    e = l.eval(o, i);
  e.value = sanitize(e.value);
  if (!(e.pdf > 0.0f && e.pdf < INFINITY)) e.pdf = 0.0f;
  return e;
}

template <class L>
BsdfSample sample_lobe(const L& l, const Frame& f, const Vec3& wo, const Vec3& u, Transport mode) {
  Vec3 o;
  float sign = to_local<L>(f, wo, o);
  Vec3 uc = {clampf(u.x, 0.0f, kOneMinusEpsilon), clampf(u.y, 0.0f, kOneMinusEpsilon),
             clampf(u.z, 0.0f, kOneMinusEpsilon)};
  BsdfSample s;
  if constexpr (requires { l.sample(o, uc, mode); })
    s = l.sample(o, uc, mode);
  else
    s = l.sample(o, uc);
  if (!(s.pdf > 0.0f && s.pdf < INFINITY)) return {};
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

// ---- lobes set up once per shading point ---------------------------------------------------
//
// Bsdf::build sets each lobe up once (Closure<Id>::make: the frame, clamping, Fresnel
// averages, table look-ups) into a state block of Bsdf::kLobeStateBytes; eval, sample and
// albedo then read the lobe from there. Same values as setting up at every call, bit for bit.

template <class L> struct Prepared {
  Frame frame;
  L lobe;
};

template <int Id> constexpr bool prepared_fits() {
  if constexpr (has_lobe<Id>()) {
    using P = Prepared<typename Closure<Id>::Lobe>;
    return sizeof(P) <= Bsdf::kLobeStateBytes && alignof(P) <= Bsdf::kLobeStateAlign;
  } else {
    return true;
  }
}
#define LOBE_CHECK(key, ...)                                                                       \
  static_assert(prepared_fits<closure_id::key>(),                                                  \
                "closure '" #key "': its lobe does not fit Bsdf::kLobeStateBytes");
LOBE_CLOSURE_TABLE(LOBE_CHECK)
#undef LOBE_CHECK

// Sets up closure `id`'s lobe from parameter block p in `state`; its LobeFlags, 0 when there
// is no lobe (state untouched).
inline uint32_t setup_lobe(int id, const unsigned char* p, void* state) {
  uint32_t flags = 0;
  with_lobe(id, p, [&](const auto& l, const Frame& f) {
    using L = std::decay_t<decltype(l)>;
    flags = (new (state) Prepared<L>{f, l})->lobe.flags();
  });
  return flags;
}

template <int Id, class Fn> bool with_prepared_as(const void* state, Fn& fn) {
  if constexpr (has_lobe<Id>()) {
    const auto& s = *static_cast<const Prepared<typename Closure<Id>::Lobe>*>(state);
    fn(s.lobe, s.frame);
    return true;
  } else {
    return false;
  }
}

// Calls fn(lobe, frame) for the lobe setup_lobe(id, ...) put in `state`.
template <class Fn> bool with_prepared(int id, const void* state, Fn&& fn) {
  switch (id) {
#define LOBE_CASE(key, ...)                                                                        \
  case closure_id::key:                                                                            \
    return with_prepared_as<closure_id::key>(state, fn);
    LOBE_CLOSURE_TABLE(LOBE_CASE)
#undef LOBE_CASE
  default:
    return false;
  }
}

} // namespace lobe::closures
