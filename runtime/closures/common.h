// Shared math for the closure library: constants, safe functions, the shading frame and the
// sampling warps every lobe uses.
//
// Plain header-only C++ with no allocation, exceptions or virtuals: the same source compiles
// natively and with clang-19 to LLVM bitcode (bitcode.cpp). Lobes work in a local frame where
// the shading normal is +z; world <-> local conversion happens once, in the dispatch.
#pragma once

#include "lobe/bsdf.h"
#include "lobe/vec.h"
#include "lobe/warp.h"

#include <cmath>
#include <cstdint>

namespace lobe::closures {

inline constexpr float kPi = 3.14159265358979323846f;
inline constexpr float kInvPi = 0.31830988618379067154f;
inline constexpr float kOneMinusEpsilon = 0x1.fffffep-1f;

inline float safe_sqrt(float x) { return std::sqrt(x > 0.0f ? x : 0.0f); }
inline float clampf(float x, float lo, float hi) { return x < lo ? lo : (x > hi ? hi : x); }
inline float sqr(float x) { return x * x; }
inline float maxf(float a, float b) { return a > b ? a : b; }
inline float minf(float a, float b) { return a < b ? a : b; }
inline bool finite_positive(float x) { return x > 0.0f && x < INFINITY; }
inline Vec3 vmax0(const Vec3& v) { return {maxf(v.x, 0.0f), maxf(v.y, 0.0f), maxf(v.z, 0.0f)}; }
inline Vec3 splat(float v) { return {v, v, v}; }
inline float luminance(const Vec3& c) { return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z; }
// NaN/Inf components become 0, negatives 0: what lobes return is always finite and >= 0.
inline Vec3 sanitize(const Vec3& v) {
  auto f = [](float x) { return (x > 0.0f && x < INFINITY) ? x : 0.0f; };
  return {f(v.x), f(v.y), f(v.z)};
}

// Lobes return the Bsdf's own result types and flags (lobe/bsdf.h): BsdfEval (value =
// f(wo, wi) |cos theta_i| and the pdf of sampling wi) and BsdfSample, in the lobe's local frame
// or world space depending on the caller; a lobe without a sample returns pdf 0. For delta
// lobes the pdf is the probability of the branch taken and the weight its throughput.

// Orthonormal frame around a normal; (t, b, n) right-handed.
struct Frame {
  Vec3 t, b, n;
  Vec3 to_local(const Vec3& v) const { return {dot(v, t), dot(v, b), dot(v, n)}; }
  Vec3 to_world(const Vec3& v) const { return t * v.x + b * v.y + n * v.z; }
};

// Frame from a normal alone (Duff et al. 2017 branchless basis). False if N is degenerate.
inline bool make_frame(const Vec3& N, Frame& f) {
  Vec3 n = normalize(N);
  if (is_zero(n)) return false;
  float sign = std::copysign(1.0f, n.z);
  float a = -1.0f / (sign + n.z);
  float b = n.x * n.y * a;
  f.t = {1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x};
  f.b = {b, sign + n.y * n.y * a, -n.y};
  f.n = n;
  return true;
}

// Frame whose t follows the tangent U projected onto the plane of N (anisotropic lobes);
// falls back to an arbitrary tangent when U is degenerate or parallel to N.
inline bool make_frame(const Vec3& N, const Vec3& U, Frame& f) {
  if (!make_frame(N, f)) return false;
  Vec3 t = normalize(U - f.n * dot(f.n, U));
  if (is_zero(t)) return true;
  f.t = t;
  f.b = cross(f.n, t);
  return true;
}

// Half vector m = normalize(wo + wi) of unit wo, wi, returning wo.m = wi.m = |wo + wi| / 2:
// free of the cancellation in dot(wo, m) = (1 + wo.wi) / |wo + wi| when wi is near -wo (grazing
// reflection), where a one-ulp change of |wi| moves dot(wo, m) by ~1e-7 / |wo + wi|^2
// relative, and symmetric in (wo, wi) (reciprocity). 0 (and m = 0) for wi = -wo.
inline float half_vector(const Vec3& wo, const Vec3& wi, Vec3& m) {
  Vec3 h = wo + wi;
  float l = length(h);
  if (!(l > 0.0f) || !(l < INFINITY)) {
    m = {};
    return 0.0f;
  }
  m = h * (1.0f / l);
  return 0.5f * l;
}

inline Vec3 reflect_z(const Vec3& w) { return {-w.x, -w.y, w.z}; }
inline Vec3 reflect(const Vec3& w, const Vec3& m) { return m * (2.0f * dot(w, m)) - w; }

// Refraction of w (pointing away from the surface) through a microfacet m; eta = eta_t /
// eta_i across the side w is on. False on total internal reflection.
inline bool refract(const Vec3& w, const Vec3& m, float eta, Vec3& out) {
  float c = dot(w, m);
  float inv = 1.0f / eta;
  float k = 1.0f - inv * inv * (1.0f - c * c);
  if (k <= 0.0f) return false;
  float ct = std::sqrt(k);
  out = -w * inv + m * (inv * c - (c >= 0.0f ? ct : -ct));
  return true;
}

} // namespace lobe::closures
