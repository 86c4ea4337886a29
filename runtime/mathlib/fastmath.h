// OIIO's fast-math approximations (fmath.h 2.4 `fast_*`), the functions OSL 1.13's math
// builtins compute: polynomial and rational fits with their own argument reduction, accurate
// to a few ulp on the useful range, with the special values the formulas give (sin(NaN) = -1,
// log(x <= 0) = log(FLT_MIN), exp2 clamped to 2^+-126, ...).
//
// Each function with multiply-adds is a template on kFused:
//   false  every a*b+c rounds twice: what OSL's constant folder computes (liboslexec is built
//          for plain x86-64) and what Lobe computes for every value (docs/language.md, "Math");
//   true   every a*b+c is one fused multiply-add: what OSL's JIT computes on a host with FMA;
//          Lobe uses it only in the derivative factors (which OSL never constant-folds).
// Unfused a*b+c is written as two statements (a product, then a sum): a compiler may contract
// a*b+c within one expression (clang's default), never across statements unless told to
// (-ffp-contract=fast); lobe_mathlib's users build with -ffp-contract=off as well.
//
// The formulas and constants are OIIO's (BSD-3-Clause; fmath.h cites Cephes, sleef and
// Abramowitz & Stegun 7.1.28 for erf). Checked bit for bit against OSL 1.13.12: values in
// mathlib_test.cpp. float -> int conversions follow x86's cvttss2si (truncation; NaN and out
// of range give INT_MIN), as both of OSL's builds do.
#pragma once

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

namespace lobe::math {

constexpr float kFltMin = std::numeric_limits<float>::min();
constexpr float kFltMax = std::numeric_limits<float>::max();
constexpr float kPi = float(3.14159265358979323846);
constexpr float kPi2 = float(1.57079632679489661923); // pi/2
constexpr float kPi4 = float(0.78539816339744830962); // pi/4
constexpr float kInvPi = float(0.31830988618379067154);
constexpr float kTwoInvPi = float(0.63661977236758134308);
constexpr float kLn2 = float(0.69314718055994530942);
constexpr float kLn10 = float(2.30258509299404568402);
constexpr float kInvLn2 = float(1.44269504088896340736);     // 1/ln 2
constexpr float kLn2InvLn10 = float(0.30102999566398119521); // ln 2 / ln 10
constexpr float kTwoInvSqrtPi = float(1.12837916709551257390);

inline uint32_t bits_of(float x) {
  uint32_t u;
  std::memcpy(&u, &x, 4);
  return u;
}
inline float from_bits(uint32_t u) {
  float x;
  std::memcpy(&x, &u, 4);
  return x;
}
inline float abs_bits(float x) { return from_bits(bits_of(x) & 0x7fffffffu); }
inline float copysign_bits(float a, float b) {
  return from_bits((bits_of(a) & 0x7fffffffu) | (bits_of(b) & 0x80000000u));
}

// a*b + c, fused or rounded twice.
template <bool kFused> inline float madd(float a, float b, float c) {
  if constexpr (kFused) {
    return std::fma(a, b, c);
  } else {
    float p = a * b;
    return p + c;
  }
}

// x86 cvttss2si: truncation; NaN and values outside int32 give INT32_MIN.
inline int32_t cvtt(float x) {
  if (x >= -2147483648.0f && x < 2147483648.0f) return int32_t(x);
  return INT32_MIN;
}
// OIIO fast_rint without SSE4: x + copysign(0.5, x), truncated.
inline int32_t fast_rint(float x) { return cvtt(x + copysign_bits(0.5f, x)); }
// OIIO clamp: !(lo <= v) gives lo (so NaN gives lo), then v > hi gives hi.
inline float oiio_clamp(float v, float lo, float hi) {
  if (!(lo <= v)) v = lo;
  if (v > hi) v = hi;
  return v;
}

// ---- trigonometry ---------------------------------------------------------------------------

// x - q*pi in four parts (Cody-Waite), q = round(x/pi); the last line flushes denormals.
template <bool F> inline float reduce_pi(float x, int32_t& q) {
  q = fast_rint(x * kInvPi);
  float qf = float(q);
  x = madd<F>(qf, -0.78515625f * 4, x);
  x = madd<F>(qf, -0.00024187564849853515625f * 4, x);
  x = madd<F>(qf, -3.7747668102383613586e-08f * 4, x);
  x = madd<F>(qf, -1.2816720341285448015e-12f * 4, x);
  return kPi2 - (kPi2 - x);
}

template <bool F> inline float fast_sin(float x) {
  int32_t q;
  x = reduce_pi<F>(x, q);
  float s = x * x;
  if (q & 1) x = -x;
  float u = 2.6083159809786593541503e-06f;
  u = madd<F>(u, s, -0.0001981069071916863322258f);
  u = madd<F>(u, s, +0.00833307858556509017944336f);
  u = madd<F>(u, s, -0.166666597127914428710938f);
  u = madd<F>(s, u * x, x);
  return oiio_clamp(u, -1.0f, 1.0f);
}

template <bool F> inline float fast_cos(float x) {
  int32_t q;
  x = reduce_pi<F>(x, q);
  float s = x * x;
  float u = -2.71811842367242206819355e-07f;
  u = madd<F>(u, s, +2.47990446951007470488548e-05f);
  u = madd<F>(u, s, -0.00138888787478208541870117f);
  u = madd<F>(u, s, +0.0416666641831398010253906f);
  u = madd<F>(u, s, -0.5f);
  u = madd<F>(u, s, +1.0f);
  if (q & 1) u = -u;
  return oiio_clamp(u, -1.0f, 1.0f);
}

template <bool F> inline float fast_tan(float x) {
  int32_t q = fast_rint(x * kTwoInvPi);
  float qf = float(q);
  x = madd<F>(qf, -0.78515625f * 2, x);
  x = madd<F>(qf, -0.00024187564849853515625f * 2, x);
  x = madd<F>(qf, -3.7747668102383613586e-08f * 2, x);
  x = madd<F>(qf, -1.2816720341285448015e-12f * 2, x);
  if ((q & 1) == 0) x = kPi4 - (kPi4 - x);
  float s = x * x;
  float u = 0.00927245803177356719970703f;
  u = madd<F>(u, s, 0.00331984995864331722259521f);
  u = madd<F>(u, s, 0.0242998078465461730957031f);
  u = madd<F>(u, s, 0.0534495301544666290283203f);
  u = madd<F>(u, s, 0.133383005857467651367188f);
  u = madd<F>(u, s, 0.333331853151321411132812f);
  u = madd<F>(s, u * x, x);
  if (q & 1) u = -1.0f / u;
  return u;
}

// acos(m) / sqrt(1 - m) for m = |x| in [0, 1] (Abramowitz & Stegun 4.4.45).
template <bool F> inline float acos_poly(float m) {
  float p = madd<F>(m, -0.02164095f, 0.077980478f);
  p = madd<F>(m, p, -0.213300989f);
  return madd<F>(m, p, 1.5707963267f);
}
// |x| >= 1 (and NaN) act as |x| = 1: acos(2) = 0, asin(2) = pi/2.
inline float clamped_abs(float x) {
  float f = abs_bits(x);
  return f < 1.0f ? 1.0f - (1.0f - f) : 1.0f;
}
template <bool F> inline float fast_acos(float x) {
  float m = clamped_abs(x);
  float a = std::sqrt(1.0f - m) * acos_poly<F>(m);
  return x < 0 ? kPi - a : a;
}
template <bool F> inline float fast_asin(float x) {
  float m = clamped_abs(x);
  float a = madd<F>(-std::sqrt(1.0f - m), acos_poly<F>(m), kPi2);
  return copysign_bits(a, x);
}

// atan(k) for k in [0, 1]: a rational fit.
template <bool F> inline float atan_unit(float k) {
  float s = 1.0f - (1.0f - k);
  float t = s * s;
  float num = s * madd<F>(0.430165678f, t, 1.0f);
  return num / madd<F>(madd<F>(0.0579354987f, t, 0.763007998f), t, 1.0f);
}
template <bool F> inline float fast_atan(float x) {
  float a = abs_bits(x);
  float k = a > 1.0f ? 1 / a : a;
  float r = atan_unit<F>(k);
  if (a > 1.0f) r = 1.570796326794896557998982f - r;
  return copysign_bits(r, x);
}
// OIIO's scalar (non-SIMD-friendly) branch: the smaller of |y|/|x| and |x|/|y|, then octant
// fix-ups by comparison and by the sign bit of x.
template <bool F> inline float fast_atan2(float y, float x) {
  float a = abs_bits(x), b = abs_bits(y);
  float k = b == 0 ? 0.0f : (a == b ? 1.0f : (b > a ? a / b : b / a));
  float r = atan_unit<F>(k);
  if (b > a) r = 1.570796326794896557998982f - r;
  if (bits_of(x) & 0x80000000u) r = kPi - r;
  return copysign_bits(r, y);
}

// ---- exponentials and logarithms --------------------------------------------------------------

// 2^x: x clamped to [-126, 126] (NaN to -126), 2^int by the exponent bits, 2^frac by a
// degree-5 polynomial.
template <bool F> inline float fast_exp2(float xval) {
  float x = oiio_clamp(xval, -126.0f, 126.0f);
  int32_t m = int32_t(x);
  x -= float(m);
  x = 1.0f - (1.0f - x);
  float r = 1.33336498402e-3f;
  r = madd<F>(x, r, 9.810352697968e-3f);
  r = madd<F>(x, r, 5.551834031939e-2f);
  r = madd<F>(x, r, 0.2401793301105f);
  r = madd<F>(x, r, 0.693144857883f);
  r = madd<F>(x, r, 1.0f);
  return from_bits(bits_of(r) + (uint32_t(m) << 23));
}
template <bool F> inline float fast_exp(float x) { return fast_exp2<F>(x * kInvLn2); }
template <bool F> inline float fast_expm1(float x) {
  if (abs_bits(x) < 0.03f) {
    float y = 1.0f - (1.0f - x);
    return copysign_bits(madd<F>(0.5f, y * y, y), x);
  }
  return fast_exp<F>(x) - 1.0f;
}

// log2(x): x clamped to [FLT_MIN, FLT_MAX] (NaN to FLT_MIN), exponent bits plus a polynomial
// of the mantissa evaluated in two halves.
template <bool F> inline float fast_log2(float xval) {
  float x = oiio_clamp(xval, kFltMin, kFltMax);
  uint32_t bits = bits_of(x);
  int exponent = int(bits >> 23) - 127;
  float f = from_bits((bits & 0x007fffffu) | 0x3f800000u) - 1.0f;
  float f2 = f * f;
  float f4 = f2 * f2;
  float hi = madd<F>(f, -0.00931049621349f, 0.05206469089414f);
  float lo = madd<F>(f, 0.47868480909345f, -0.72116591947498f);
  hi = madd<F>(f, hi, -0.13753123777116f);
  hi = madd<F>(f, hi, 0.24187369696082f);
  hi = madd<F>(f, hi, -0.34730547155299f);
  lo = madd<F>(f, lo, 1.442689881667200f);
  return madd<F>(f4, hi, f * lo) + float(exponent);
}
template <bool F> inline float fast_log(float x) { return fast_log2<F>(x) * kLn2; }
template <bool F> inline float fast_log10(float x) { return fast_log2<F>(x) * kLn2InvLn10; }
// The exponent of |x| clamped to [FLT_MIN, FLT_MAX]: logb(0) = -126, logb(inf) = 127; NaN
// keeps its exponent bits (128).
inline float fast_logb(float x) {
  x = abs_bits(x);
  if (x < kFltMin) x = kFltMin;
  if (x > kFltMax) x = kFltMax;
  return float(int(bits_of(x) >> 23) - 127);
}

// ---- hyperbolic functions -------------------------------------------------------------------

template <bool F> inline float fast_sinh(float x) {
  float a = abs_bits(x);
  if (a > 1.0f) {
    float e = fast_exp<F>(a);
    return copysign_bits(madd<F>(e, 0.5f, -0.5f / e), x);
  }
  a = 1.0f - (1.0f - a);
  float a2 = a * a;
  float r = 2.03945513931e-4f;
  r = madd<F>(r, a2, 8.32990277558e-3f);
  r = madd<F>(r, a2, 0.1666673421859f);
  r = madd<F>(a2, r * a, a);
  return copysign_bits(r, x);
}
template <bool F> inline float fast_cosh(float x) {
  float e = fast_exp<F>(abs_bits(x));
  return madd<F>(e, 0.5f, 0.5f / e);
}
template <bool F> inline float fast_tanh(float x) {
  float e = fast_exp<F>(2.0f * abs_bits(x));
  return copysign_bits(1 - 2 / (1 + e), x);
}

// ---- powers, roots, error function ----------------------------------------------------------

// The sign of x^y for a negative x: +1 for an even integer y, -1 for an odd one; false when y
// is not an integer (OIIO reads it from the bits: |y| >= 2^24 is even, below 1 not integral).
inline bool integer_power_sign(float y, float& sign) {
  uint32_t ybits = bits_of(y) & 0x7fffffffu;
  if (ybits >= 0x4b800000u) return sign = 1.0f, true;
  if (ybits < 0x3f800000u) return false;
  int k = int(ybits >> 23) - 127;
  uint32_t j = ybits >> (23 - k);
  if ((j << (23 - k)) != ybits) return false;
  sign = from_bits(0x3f800000u | (j << 31));
  return true;
}

// OIIO fast_safe_pow: x^0 = 1, 0^y = 0, x^1 = x, x^2 = min(x*x, FLT_MAX); a negative x needs
// an integer y (else 0); otherwise +-2^(y log2|x|).
template <bool F> inline float fast_safe_pow(float x, float y) {
  if (y == 0) return 1.0f;
  if (x == 0) return 0.0f;
  if (y == 1.0f) return x;
  if (y == 2.0f) {
    float xx = x * x;
    return xx > kFltMax ? kFltMax : xx;
  }
  float sign = 1.0f;
  if (x < 0.0f && !integer_power_sign(y, sign)) return 0.0f;
  float l = fast_log2<F>(abs_bits(x));
  return sign * fast_exp2<F>(y * l);
}

// Cube root: an exponent-bits guess and two Newton steps; exact 0 for 0.
template <bool F> inline float fast_cbrt(float x) {
  float x0 = abs_bits(x);
  float a = from_bits(0x2a5137a0u + bits_of(x0) / 3);
  a = 0.333333333f * madd<F>(2.0f, a, x0 / (a * a));
  a = 0.333333333f * madd<F>(2.0f, a, x0 / (a * a));
  a = x0 == 0 ? 0 : a;
  return copysign_bits(a, x);
}

// erf(x) = 1 - 1/(1 + a1 x + ... + a6 x^6)^16 (Abramowitz & Stegun 7.1.28).
template <bool F> inline float fast_erf(float x) {
  const float a1 = 0.0705230784f, a2 = 0.0422820123f, a3 = 0.0092705272f;
  const float a4 = 0.0001520143f, a5 = 0.0002765672f, a6 = 0.0000430638f;
  float b = 1.0f - (1.0f - abs_bits(x));
  float r = madd<F>(a6, b, a5);
  r = madd<F>(r, b, a4);
  r = madd<F>(r, b, a3);
  r = madd<F>(r, b, a2);
  r = madd<F>(r, b, a1);
  r = madd<F>(r, b, 1.0f);
  float s = r * r, t = s * s, u = t * t, v = u * u;
  return copysign_bits(1.0f - 1.0f / v, x);
}
template <bool F> inline float fast_erfc(float x) { return 1.0f - fast_erf<F>(x); }

} // namespace lobe::math
