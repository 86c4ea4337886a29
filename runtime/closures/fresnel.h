// Fresnel reflectance: exact dielectric (with total internal reflection), exact conductor
// with a complex index of refraction per channel, classic and generalised Schlick.
//
//   dielectric  F = (r_s^2 + r_p^2) / 2,  r_s = (c - eta c_t)/(c + eta c_t),
//               r_p = (eta c - c_t)/(eta c + c_t),  c_t^2 = 1 - (1 - c^2)/eta^2 (< 0: TIR, F = 1)
//               eta = eta_transmitted / eta_incident, c = cos of the incident angle (>= 0).
//   conductor   the same two amplitudes with the complex index n + i k (absorbing medium;
//               n - ik in the other sign convention gives the same |r|^2), evaluated exactly
//               in complex arithmetic, per channel.
//   schlick     F = f0 + (f90 - f0)(1 - c)^p  (p = 5: Schlick 1994; generalised: any p > 0).
//
// Valid ranges: c in [0, 1] (clamped), eta > 0, n >= 0, k >= 0. Reference: Born & Wolf,
// Principles of Optics, ch. 1.5 and 13.2; pbrt-v4 section 9.3.
#pragma once

#include "common.h"

namespace lobe::closures {

inline float fresnel_dielectric(float c, float eta) {
  c = clampf(c, 0.0f, 1.0f);
  if (!(eta > 0.0f)) return 1.0f;
  float s2t = (1.0f - c * c) / (eta * eta);
  if (s2t >= 1.0f) return 1.0f;
  float ct = safe_sqrt(1.0f - s2t);
  float rs = (c - eta * ct) / (c + eta * ct);
  float rp = (eta * c - ct) / (eta * c + ct);
  float f = 0.5f * (rs * rs + rp * rp);
  return f == f ? clampf(f, 0.0f, 1.0f) : 1.0f;
}

// The same from both cosines, c (incident side) and ct (transmitted side), eta = eta_t / eta_i:
// for a refracting pair whose cosines are known from the geometry. Swapping the sides
// (c <-> ct, eta -> 1/eta) only flips the signs of r_s and r_p, so F is the same.
inline float fresnel_dielectric(float c, float ct, float eta) {
  c = clampf(c, 0.0f, 1.0f);
  ct = clampf(ct, 0.0f, 1.0f);
  if (!(eta > 0.0f)) return 1.0f;
  float rs = (c - eta * ct) / (c + eta * ct);
  float rp = (eta * c - ct) / (eta * c + ct);
  float f = 0.5f * (rs * rs + rp * rp);
  return f == f ? clampf(f, 0.0f, 1.0f) : 1.0f;
}

// Minimal complex arithmetic (std::complex is avoided to keep bitcode free of library calls).
struct Cpx {
  float re = 0, im = 0;
};
inline Cpx operator+(Cpx a, Cpx b) { return {a.re + b.re, a.im + b.im}; }
inline Cpx operator-(Cpx a, Cpx b) { return {a.re - b.re, a.im - b.im}; }
inline Cpx operator*(Cpx a, Cpx b) {
  return {a.re * b.re - a.im * b.im, a.re * b.im + a.im * b.re};
}
inline float norm2(Cpx a) { return a.re * a.re + a.im * a.im; }
inline Cpx operator/(Cpx a, Cpx b) {
  float d = norm2(b);
  return {(a.re * b.re + a.im * b.im) / d, (a.im * b.re - a.re * b.im) / d};
}
// Principal square root (real part >= 0), algebraically: with r = |z|, the larger of
// sqrt((r +- re)/2) is computed directly and the other from im / (2 t), so nothing cancels.
// Two square roots and a division (the polar form needs atan2, cos and sin).
inline Cpx csqrt(Cpx z) {
  float r = std::sqrt(norm2(z));
  if (r == 0.0f) return {};
  if (z.re >= 0.0f) {
    float t = std::sqrt(0.5f * (r + z.re));
    return {t, z.im / (2.0f * t)};
  }
  float t = std::sqrt(0.5f * (r - z.re));
  return {std::fabs(z.im) / (2.0f * t), std::copysign(t, z.im)};
}

// Exact conductor Fresnel for one channel, index n + i k.
inline float fresnel_conductor(float c, float n, float k) {
  c = clampf(c, 0.0f, 1.0f);
  Cpx eta{maxf(n, 0.0f), maxf(k, 0.0f)};
  if (eta.re == 0.0f && eta.im == 0.0f) return 1.0f;
  Cpx s2t = Cpx{1.0f - c * c, 0.0f} / (eta * eta);
  Cpx ct = csqrt(Cpx{1.0f, 0.0f} - s2t);
  Cpx cc{c, 0.0f};
  Cpx rp = (eta * cc - ct) / (eta * cc + ct);
  Cpx rs = (cc - eta * ct) / (cc + eta * ct);
  float f = 0.5f * (norm2(rp) + norm2(rs));
  return f == f ? clampf(f, 0.0f, 1.0f) : 1.0f;
}

inline Vec3 fresnel_conductor(float c, const Vec3& n, const Vec3& k) {
  return {fresnel_conductor(c, n.x, k.x), fresnel_conductor(c, n.y, k.y),
          fresnel_conductor(c, n.z, k.z)};
}

inline float schlick_weight(float c, float p) {
  float m = clampf(1.0f - c, 0.0f, 1.0f);
  if (p == 5.0f) return m * m * m * m * m;
  return m > 0.0f ? std::pow(m, maxf(p, 1e-6f)) : 0.0f;
}
inline Vec3 fresnel_schlick(float c, const Vec3& f0, const Vec3& f90, float p) {
  float w = schlick_weight(c, p);
  return f0 + (f90 - f0) * w;
}

// Thin-film interference (Airy summation of the multiple reflections inside a film of index
// n2 and thickness d between media n1 and n3; Born & Wolf 1.6, Belcour & Barla 2017 sec. 3):
//   r = (r12 + r23 e^{i delta}) / (1 + r12 r23 e^{i delta}),  delta = 4 pi n2 d cos(theta2) /
//   lambda,
// per polarisation (s, p), R = (|r_s|^2 + |r_p|^2) / 2. Cosines inside the film and the base
// are complex (Snell with complex n3 for conductors; imaginary under total internal
// reflection, which the same formula then handles). n1, n2 real; d and lambda in nm.
inline Cpx cexp_i(Cpx z) { // e^{i z}
  float m = std::exp(-z.im);
  return {m * std::cos(z.re), m * std::sin(z.re)};
}
inline float fresnel_thin_film(float c1, float n1, float n2, Cpx n3, float d, float lambda) {
  c1 = clampf(c1, 0.0f, 1.0f);
  Cpx N1{n1, 0.0f}, N2{n2, 0.0f}, C1{c1, 0.0f}, one{1.0f, 0.0f};
  float s1n1 = n1 * n1 * (1.0f - c1 * c1); // (n1 sin theta1)^2
  Cpx C2 = csqrt(one - Cpx{s1n1, 0.0f} / (N2 * N2));
  Cpx C3 = csqrt(one - Cpx{s1n1, 0.0f} / (n3 * n3));
  if (norm2(C2) == 0.0f || norm2(n3) == 0.0f) return 1.0f;
  Cpx E = cexp_i(Cpx{4.0f * kPi * n2 * d / lambda, 0.0f} * C2);
  auto airy = [&](Cpx r12, Cpx r23) { return norm2((r12 + r23 * E) / (one + r12 * r23 * E)); };
  Cpx rs12 = (N1 * C1 - N2 * C2) / (N1 * C1 + N2 * C2);
  Cpx rs23 = (N2 * C2 - n3 * C3) / (N2 * C2 + n3 * C3);
  Cpx rp12 = (N2 * C1 - N1 * C2) / (N2 * C1 + N1 * C2);
  Cpx rp23 = (n3 * C2 - N2 * C3) / (n3 * C2 + N2 * C3);
  float f = 0.5f * (airy(rs12, rs23) + airy(rp12, rp23));
  return f == f ? clampf(f, 0.0f, 1.0f) : 1.0f;
}

// Wavelengths (nm) at which the RGB channels evaluate thin films.
inline constexpr float kFilmLambda[3] = {650.0f, 550.0f, 450.0f};

// Hemispherical average 2 int_0^1 F(mu) mu dmu of any Fresnel, by Gauss-Legendre quadrature on
// mu (exact enough for the smooth Fresnel curves; used by energy compensation).
template <class F> Vec3 fresnel_average(F&& fresnel) {
  // 5 nodes: for measured metals (gold, silver, copper, aluminium, chrome, iron, titanium) the
  // error is <= 1.8e-4 against a 2e5-point midpoint rule (8 nodes: <= 8e-6, at 8/5 the cost;
  // this average is most of conductor_bsdf's set-up time).
  constexpr float x[5] = {-0.9061798459f, -0.5384693101f, 0.0f, 0.5384693101f, 0.9061798459f};
  constexpr float w[5] = {0.2369268851f, 0.4786286705f, 0.5688888889f, 0.4786286705f,
                          0.2369268851f};
  Vec3 sum;
  for (int i = 0; i < 5; ++i) {
    float mu = 0.5f * (x[i] + 1.0f);
    sum += fresnel(mu) * (w[i] * 0.5f * 2.0f * mu);
  }
  return sum;
}

} // namespace lobe::closures
