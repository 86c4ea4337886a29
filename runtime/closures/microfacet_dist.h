// Microfacet normal distributions: GGX (Trowbridge-Reitz) and Beckmann, anisotropic, with the
// Smith masking function, height-correlated G2 and exact visible-normal sampling.
//
//   GGX       D(m) = 1 / (pi ax ay ((mx/ax)^2 + (my/ay)^2 + mz^2)^2)     (from m's components:
//             no 1 - cos^2 cancellation), Lambda(w) = (sqrt(1 + t) - 1)/2,
//             t = (ax^2 wx^2 + ay^2 wy^2) / wz^2
//   Beckmann  D(m) = exp(-((mx/ax)^2 + (my/ay)^2) / mz^2) / (pi ax ay mz^4),
//             Lambda(w) = (erf(a) - 1)/2 + exp(-a^2)/(2 a sqrt(pi)), a = 1/sqrt(t)
//   G1 = 1/(1 + Lambda(wo)),  G2 = 1/(1 + Lambda(wo) + Lambda(wi))   (Heitz 2014)
//   Visible normals D_wo(m) = G1(wo) max(0, wo.m) D(m) / wo.z, sampled exactly: GGX by Heitz
//   2018 ("Sampling the GGX distribution of visible normals"), Beckmann by inverting the
//   slope CDF with Newton-bisection (Heitz & d'Eon 2014, with Jakob's initial guess).
//
// Ranges: alphas are clamped to [kMinAlpha, 4]; callers treat max(ax, ay) < kDeltaAlpha as a
// delta lobe. Lambda is 0 at normal incidence and infinite at the horizon (G1 = 0).
#pragma once

#include "common.h"

namespace lobe::closures {

inline constexpr float kDeltaAlpha = 1e-4f; // below this a lobe is a perfect mirror/refractor
inline constexpr float kMinAlpha = 1e-4f;

// Inverse error function (Giles 2010, single-precision version).
inline float erfinv_approx(float x) {
  x = clampf(x, -0.99999994f, 0.99999994f);
  float w = -std::log((1.0f - x) * (1.0f + x)), p;
  if (w < 5.0f) {
    w -= 2.5f;
    p = 2.81022636e-08f;
    p = 3.43273939e-07f + p * w;
    p = -3.5233877e-06f + p * w;
    p = -4.39150654e-06f + p * w;
    p = 0.00021858087f + p * w;
    p = -0.00125372503f + p * w;
    p = -0.00417768164f + p * w;
    p = 0.246640727f + p * w;
    p = 1.50140941f + p * w;
  } else {
    w = std::sqrt(w) - 3.0f;
    p = -0.000200214257f;
    p = 0.000100950558f + p * w;
    p = 0.00134934322f + p * w;
    p = -0.00367342844f + p * w;
    p = 0.00573950773f + p * w;
    p = -0.0076224613f + p * w;
    p = 0.00943887047f + p * w;
    p = 1.00167406f + p * w;
    p = 2.83297682f + p * w;
  }
  return p * x;
}

struct MicrofacetDistribution {
  float ax = 0.5f, ay = 0.5f;
  bool beckmann = false;

  static MicrofacetDistribution make(float ax, float ay, bool beckmann) {
    auto c = [](float a) { return a == a ? clampf(a, kMinAlpha, 4.0f) : kMinAlpha; };
    return {c(ax), c(ay), beckmann};
  }

  float D(const Vec3& m) const {
    if (!(m.z > 0.0f)) return 0.0f;
    float x = m.x / ax, y = m.y / ay;
    if (beckmann) {
      float z2 = m.z * m.z;
      return std::exp(-(x * x + y * y) / z2) / (kPi * ax * ay * z2 * z2);
    }
    float d = x * x + y * y + m.z * m.z;
    return 1.0f / (kPi * ax * ay * d * d);
  }

  float lambda(const Vec3& w) const {
    float num = sqr(ax * w.x) + sqr(ay * w.y), z2 = w.z * w.z;
    if (num == 0.0f) return 0.0f;
    if (z2 == 0.0f) return INFINITY;
    float t = num / z2;
    if (beckmann) {
      float a = 1.0f / std::sqrt(t);
      if (a >= 6.0f) return 0.0f;
      return 0.5f * (std::erf(a) - 1.0f) + std::exp(-a * a) / (2.0f * a * 1.7724538509f);
    }
    return t / (2.0f * (1.0f + std::sqrt(1.0f + t)));
  }
  float G1(const Vec3& w) const { return 1.0f / (1.0f + lambda(w)); }
  float G2(const Vec3& wo, const Vec3& wi) const { return 1.0f / (1.0f + lambda(wo) + lambda(wi)); }
  // Density of visible normals seen from wo (wo.z > 0).
  float D_visible(const Vec3& wo, const Vec3& m) const {
    float c = dot(wo, m);
    if (!(c > 0.0f) || !(wo.z > 0.0f)) return 0.0f;
    return G1(wo) * c * D(m) / wo.z;
  }

  Vec3 sample_visible(const Vec3& wo, float u1, float u2) const {
    return beckmann ? sample_visible_beckmann(wo, u1, u2) : sample_visible_ggx(wo, u1, u2);
  }

  Vec3 sample_visible_ggx(const Vec3& wo, float u1, float u2) const {
    Vec3 vh = normalize(Vec3{ax * wo.x, ay * wo.y, wo.z});
    float len2 = vh.x * vh.x + vh.y * vh.y;
    Vec3 t1 = len2 > 1e-14f ? Vec3{-vh.y, vh.x, 0.0f} * (1.0f / std::sqrt(len2)) : Vec3{1, 0, 0};
    Vec3 t2 = cross(vh, t1);
    float r = std::sqrt(u1), phi = 2.0f * kPi * u2;
    float p1 = r * std::cos(phi), p2 = r * std::sin(phi);
    float s = 0.5f * (1.0f + vh.z);
    p2 = (1.0f - s) * safe_sqrt(1.0f - p1 * p1) + s * p2;
    Vec3 nh = t1 * p1 + t2 * p2 + vh * safe_sqrt(1.0f - p1 * p1 - p2 * p2);
    return normalize(Vec3{ax * nh.x, ay * nh.y, maxf(nh.z, 1e-7f)});
  }

  // Slopes of Beckmann visible normals for a unit-roughness wo at cos theta = c.
  static void beckmann_slopes(float c, float u1, float u2, float& sx, float& sy) {
    if (c > 0.99999f) { // normal incidence: the plain Beckmann slope distribution
      float r = std::sqrt(-std::log(maxf(1.0f - u1, 1e-30f)));
      sx = r * std::cos(2.0f * kPi * u2);
      sy = r * std::sin(2.0f * kPi * u2);
      return;
    }
    float s = safe_sqrt(1.0f - c * c), tan_t = s / maxf(c, 1e-30f), cot_t = c / s;
    float theta = std::acos(clampf(c, 0.0f, 1.0f));
    float a = -1.0f, b_hi = std::erf(cot_t);
    float fit = 1.0f + theta * (-0.876f + theta * (0.4265f - 0.0594f * theta));
    float b = b_hi - (1.0f + b_hi) * std::pow(1.0f - u1, fit);
    float norm = 1.0f / (1.0f + b_hi + 0.5641895835f * tan_t * std::exp(-cot_t * cot_t));
    for (int it = 0; it < 64; ++it) {
      if (!(b >= a && b <= b_hi)) b = 0.5f * (a + b_hi);
      float x = erfinv_approx(b);
      float value = norm * (1.0f + b + 0.5641895835f * tan_t * std::exp(-x * x)) - u1;
      float deriv = norm * (1.0f - x * tan_t);
      if (std::fabs(value) < 1e-6f) break;
      if (value > 0.0f)
        b_hi = b;
      else
        a = b;
      b -= value / deriv;
    }
    sx = erfinv_approx(b);
    sy = erfinv_approx(2.0f * u2 - 1.0f);
  }

  Vec3 sample_visible_beckmann(const Vec3& wo, float u1, float u2) const {
    Vec3 w = normalize(Vec3{ax * wo.x, ay * wo.y, wo.z}); // stretch to unit roughness
    float sx, sy;
    beckmann_slopes(w.z, u1, u2, sx, sy);
    float r = std::sqrt(w.x * w.x + w.y * w.y);
    float cp = r > 1e-7f ? w.x / r : 1.0f, sp = r > 1e-7f ? w.y / r : 0.0f;
    float x = cp * sx - sp * sy, y = sp * sx + cp * sy; // rotate to wo's azimuth
    return normalize(Vec3{-x * ax, -y * ay, 1.0f});
  }
};

} // namespace lobe::closures
