// The colour systems (color_system.h): RGB <-> XYZ from chromaticities, the named colour
// models, the sRGB curve, blackbody and wavelength_color, each as OSL 1.13 computes them so that
// results match it to the bit.
#include "color_system.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <memory>
#include <mutex>
#include <optional>

namespace lobe::shadeops {

namespace {

// ---- Dual arithmetic with OSL's rules (dual.h): the derivative formulas and their operation
// order decide the last bits of every derivative.
float val(float x) { return x; }
float val(const DualF& x) { return x.v; }

DualF operator+(const DualF& a, const DualF& b) { return {a.v + b.v, a.dx + b.dx, a.dy + b.dy}; }
DualF operator+(const DualF& a, float b) { return {a.v + b, a.dx, a.dy}; }
DualF operator+(float a, const DualF& b) { return {a + b.v, b.dx, b.dy}; }
DualF operator-(const DualF& a, const DualF& b) { return {a.v - b.v, a.dx - b.dx, a.dy - b.dy}; }
DualF operator-(const DualF& a, float b) { return {a.v - b, a.dx, a.dy}; }
DualF operator-(float a, const DualF& b) { return {a - b.v, -b.dx, -b.dy}; }
DualF operator*(const DualF& a, const DualF& b) {
  return {a.v * b.v, a.v * b.dx + a.dx * b.v, a.v * b.dy + a.dy * b.v};
}
DualF operator*(const DualF& a, float b) { return {a.v * b, a.dx * b, a.dy * b}; }
DualF operator*(float a, const DualF& b) { return b * a; }
DualF operator/(const DualF& a, const DualF& b) {
  float inv = 1.0f / b.v, q = a.v / b.v;
  return {q, inv * (a.dx - q * b.dx), inv * (a.dy - q * b.dy)};
}
DualF operator/(const DualF& a, float b) {
  float inv = 1.0f / b;
  return {a.v / b, inv * a.dx, inv * a.dy};
}
DualF operator/(float a, const DualF& b) {
  float inv = 1.0f / b.v, q = a / b.v;
  return {q, inv * (-q * b.dx), inv * (-q * b.dy)};
}

// min / max of duals compare values and keep the chosen one's derivatives; on a tie OSL's min
// keeps the second argument and its max the first.
template <class S> S min_(const S& a, const S& b) { return val(a) < val(b) ? a : b; }
template <class S> S max_(const S& a, const S& b) { return val(a) < val(b) ? b : a; }

float safe_pow(float x, float y) { // OIIO::safe_pow
  if (y == 0) return 1.0f;
  if (x == 0) return 0.0f;
  if (x < 0 && y != std::floor(y)) return 0.0f;
  float r = std::pow(x, y);
  const float big = std::numeric_limits<float>::max();
  return std::clamp(r, -big, big);
}
// pow(u, y) for a constant exponent. The dual form is OSL's: u^y as u^(y-1) * u, derivative
// y u^(y-1) u' plus log(u) u^y times the (zero) derivative of y.
float pow_const(float u, float y) { return safe_pow(u, y); }
DualF pow_const(const DualF& u, float y) {
  float pm1 = safe_pow(u.v, y - 1.0f), p = pm1 * u.v;
  float logu = u.v > 0 ? std::log(std::max(u.v, std::numeric_limits<float>::min())) : 0.0f;
  float dfdu = y * pm1, dfdv = logu * p;
  return {p, dfdu * u.dx + dfdv * 0.0f, dfdu * u.dy + dfdv * 0.0f};
}

template <class S> using C3 = Color3T<S>;
using Matrix = ColorSystem::Matrix;

// Row vector times matrix, summed left to right.
template <class S> C3<S> mul(const C3<S>& c, const Matrix& m) {
  return {c.r * m[0][0] + c.g * m[1][0] + c.b * m[2][0],
          c.r * m[0][1] + c.g * m[1][1] + c.b * m[2][1],
          c.r * m[0][2] + c.g * m[1][2] + c.b * m[2][2]};
}

// ---- Colour models (Foley & van Dam), in OSL's formulation.
template <class S> C3<S> hsv_to_rgb(const C3<S>& hsv) {
  S h = hsv.r, s = hsv.g, v = hsv.b;
  if (val(s) < 0.0001f) return {v, v, v};
  h = 6.0f * (h - std::floor(val(h))); // hue in [0, 6)
  int hi = int(val(h));
  S f = h - float(hi);
  S p = v * (1.0f - s);
  S q = v * (1.0f - s * f);
  S t = v * (1.0f - s * (1.0f - f));
  switch (hi) {
  case 0:
    return {v, t, p};
  case 1:
    return {q, v, p};
  case 2:
    return {p, v, t};
  case 3:
    return {p, q, v};
  case 4:
    return {t, p, v};
  default:
    return {v, p, q};
  }
}

template <class S> C3<S> rgb_to_hsv(const C3<S>& rgb) {
  S r = rgb.r, g = rgb.g, b = rgb.b;
  S mincomp = min_(r, min_(g, b));
  S maxcomp = max_(r, max_(g, b));
  S delta = maxcomp - mincomp; // chroma
  S h{}, s{}, v = maxcomp;
  if (val(maxcomp) > 0) s = delta / maxcomp;
  if (val(s) > 0) { // hue in turns: the sector's start plus the offset within it, /6 each
    if (val(r) >= val(maxcomp))
      h = (g - b) / (6.0f * delta);
    else if (val(g) >= val(maxcomp))
      h = 1.0f / 3.0f + (b - r) / (6.0f * delta);
    else
      h = 2.0f / 3.0f + (r - g) / (6.0f * delta);
    if (val(h) < 0) h = h + 1.0f;
  }
  return {h, s, v};
}

template <class S> C3<S> hsl_to_rgb(const C3<S>& hsl) {
  S h = hsl.r, s = hsl.g, l = hsl.b;
  // hsl -> hsv -> rgb
  S v = val(l) <= 0.5f ? l * (1.0f + s) : l * (1.0f - s) + s;
  if (val(v) <= 0) return {S{}, S{}, S{}};
  S min = 2.0f * l - v;
  return hsv_to_rgb(C3<S>{h, (v - min) / v, v});
}

template <class S> C3<S> rgb_to_hsl(const C3<S>& rgb) {
  S minval = min_(rgb.r, min_(rgb.g, rgb.b));
  C3<S> hsv = rgb_to_hsv(rgb);
  S maxval = hsv.b;
  S h = hsv.r, s{}, l = (minval + maxval) / 2.0f;
  if (val(minval) == val(maxval))
    s = S{}; // achromatic
  else if (val(l) <= 0.5f)
    s = (maxval - minval) / (maxval + minval);
  else
    s = (maxval - minval) / (2.0f - maxval - minval);
  return {h, s, l};
}

// YIQ (NTSC), in OSL's coefficients: the inverse has more digits than the forward matrix.
const Matrix kRgbToYiq = {
    {{0.299f, 0.596f, 0.212f}, {0.587f, -0.275f, -0.523f}, {0.114f, -0.321f, 0.311f}}};
const Matrix kYiqToRgb = {
    {{1.0000f, 1.0000f, 1.0000f}, {0.9557f, -0.2716f, -1.1082f}, {0.6199f, -0.6469f, 1.7051f}}};

template <class S> C3<S> xyz_to_xyy(const C3<S>& xyz) {
  S n = xyz.r + xyz.g + xyz.b;
  S n_inv = val(n) >= 1.0e-6f ? 1.0f / n : S{};
  return {xyz.r * n_inv, xyz.g * n_inv, xyz.g};
}
template <class S> C3<S> xyy_to_xyz(const C3<S>& xyy) {
  S y_y = val(xyy.g) > 1.0e-6f ? xyy.b / xyy.g : S{};
  return {xyy.r * y_y, xyy.b, (1.0f - xyy.r - xyy.g) * y_y};
}

// The sRGB transfer curve (IEC 61966-2-1) per component.
template <class S> S linear_to_srgb(const S& x) {
  return val(x) <= 0.0031308f ? 12.92f * x : 1.055f * pow_const(x, 1.0f / 2.4f) - 0.055f;
}
template <class S> S srgb_to_linear(const S& x) {
  return val(x) <= 0.04045f ? x * (1.0f / 12.92f) : pow_const((x + 0.055f) * (1.0f / 1.055f), 2.4f);
}
template <class S, class F> C3<S> per_component(const C3<S>& c, F f) {
  return {f(c.r), f(c.g), f(c.b)};
}

// ---- OpenImageIO's built-in colour transforms, which OSL asks for names it does not know
// itself (its ColorConfig without an OCIO config, as in OSL built here): a linear space
// ("linear", "lnf", "lnh", any case) to or from "sRGB" or "Rec709" (any case). Its sRGB curve is
// the SIMD one, whose pow is OIIO's fast_pow_pos (facts from OIIO's fmath.h and color.h).
float fast_log2(float x) {
  x = std::clamp(x, std::numeric_limits<float>::min(), std::numeric_limits<float>::max());
  uint32_t bits;
  std::memcpy(&bits, &x, 4);
  int exponent = int(bits >> 23) - 127;
  uint32_t mbits = (bits & 0x007FFFFF) | 0x3f800000;
  float f;
  std::memcpy(&f, &mbits, 4);
  f -= 1.0f; // mantissa - 1 in [0, 1)
  float f2 = f * f, f4 = f2 * f2;
  float hi = f * -0.00931049621349f + 0.05206469089414f;
  float lo = f * 0.47868480909345f + -0.72116591947498f;
  hi = f * hi + -0.13753123777116f;
  hi = f * hi + 0.24187369696082f;
  hi = f * hi + -0.34730547155299f;
  lo = f * lo + 1.442689881667200f;
  return ((f4 * hi) + (f * lo)) + float(exponent);
}
float fast_exp2(float x);
float fast_pow_pos(float x, float y) { return fast_exp2(y * fast_log2(x)); }

float oiio_linear_to_srgb(float x) {
  return x <= 0.0031308f ? 12.92f * x : 1.055f * fast_pow_pos(x, 1.f / 2.4f) + -0.055f;
}
float oiio_srgb_to_linear(float x) {
  return x <= 0.04045f ? x * (1.0f / 12.92f)
                       : fast_pow_pos(x * (1.0f / 1.055f) + 0.055f * (1.0f / 1.055f), 2.4f);
}
float oiio_linear_to_rec709(float x) {
  return x < 0.018f ? x * 4.5f : 1.099f * std::pow(x, 0.45f) - 0.099f;
}
float oiio_rec709_to_linear(float x) {
  return x < 0.081f ? x * (1.0f / 4.5f) : std::pow((x + 0.099f) * (1.0f / 1.099f), 1.0f / 0.45f);
}
// The same curves' exact derivatives, for derivatives through these transforms. (OSL takes
// them another way, not measured yet; these agree to about 1e-3.)
DualF oiio_curve(const DualF& x, float (*f)(float), float (*df)(float)) {
  float k = df(x.v);
  return {f(x.v), k * x.dx, k * x.dy};
}
float d_linear_to_srgb(float x) {
  return x <= 0.0031308f ? 12.92f : 1.055f / 2.4f * safe_pow(x, 1.f / 2.4f - 1.0f);
}
float d_srgb_to_linear(float x) {
  return x <= 0.04045f ? 1.0f / 12.92f
                       : 2.4f / 1.055f * safe_pow((x + 0.055f) * (1.0f / 1.055f), 1.4f);
}
float d_linear_to_rec709(float x) {
  return x < 0.018f ? 4.5f : 1.099f * 0.45f * safe_pow(x, 0.45f - 1.0f);
}
float d_rec709_to_linear(float x) {
  return x < 0.081f ? 1.0f / 4.5f
                    : (1.0f / 0.45f / 1.099f) *
                          safe_pow((x + 0.099f) * (1.0f / 1.099f), 1.0f / 0.45f - 1.0f);
}

bool iequals(std::string_view a, std::string_view b) {
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) {
           return std::tolower((unsigned char)x) == std::tolower((unsigned char)y);
         });
}
bool oiio_linear(std::string_view s) {
  return iequals(s, "linear") || iequals(s, "lnf") || iequals(s, "lnh");
}

struct OiioCurve {
  float (*f)(float);
  float (*df)(float);
  bool gamma = false; // a gamma curve (f, df null): x to `power`, through fast_pow_pos
  float power = 0;
};
// OIIO's "GammaX.Y" (any case): X.Y as a float, 0 when there is no number.
std::optional<float> oiio_gamma(std::string_view s) {
  if (s.size() < 5 || !iequals(s.substr(0, 5), "gamma")) return std::nullopt;
  std::string rest(s.substr(5));
  char* end = nullptr;
  float g = std::strtof(rest.c_str(), &end);
  return end == rest.c_str() ? 0.0f : g;
}
// The curve OIIO applies from `from` to `to`, or {} when it has none: sRGB and Rec709 curves
// between them and a linear space, and a gamma curve between a linear space and "GammaX.Y"
// (OSL 1.13.12: transformc("linear", "Gamma2.2", color(.2, .5, .8)) is 0.481156 0.729737
// 0.903545, as fast_pow_pos computes x^(1/2.2)).
OiioCurve oiio_curve_for(std::string_view from, std::string_view to) {
  if (auto g = oiio_gamma(to); g && oiio_linear(from)) return {nullptr, nullptr, true, 1.0f / *g};
  if (auto g = oiio_gamma(from); g && oiio_linear(to)) return {nullptr, nullptr, true, *g};
  if (oiio_linear(from) && iequals(to, "sRGB")) return {oiio_linear_to_srgb, d_linear_to_srgb};
  if (oiio_linear(from) && iequals(to, "Rec709"))
    return {oiio_linear_to_rec709, d_linear_to_rec709};
  if (iequals(from, "sRGB") && oiio_linear(to)) return {oiio_srgb_to_linear, d_srgb_to_linear};
  if (iequals(from, "Rec709") && oiio_linear(to))
    return {oiio_rec709_to_linear, d_rec709_to_linear};
  return {nullptr, nullptr};
}
float apply(const OiioCurve& k, float x) { return k.f ? k.f(x) : fast_pow_pos(x, k.power); }
DualF apply(const OiioCurve& k, const DualF& x) {
  if (k.f) return oiio_curve(x, k.f, k.df);
  float d = k.power * safe_pow(x.v, k.power - 1.0f); // the exact slope (OSL's not measured)
  return {fast_pow_pos(x.v, k.power), d * x.dx, d * x.dy};
}

bool is_linear_rgb(std::string_view s) { return s == "rgb" || s == "RGB" || s == "linear"; }

// ---- Spectra
// CIE 1931 2-degree colour matching functions (x-bar, y-bar, z-bar) from 380 to 780 nm every
// 5 nm, to 4 digits: the table OSL uses (from John Walker's specrend.c).
const float kCieMatch[81][3] = {
    {0.0014f, 0.0000f, 0.0065f}, {0.0022f, 0.0001f, 0.0105f}, {0.0042f, 0.0001f, 0.0201f},
    {0.0076f, 0.0002f, 0.0362f}, {0.0143f, 0.0004f, 0.0679f}, {0.0232f, 0.0006f, 0.1102f},
    {0.0435f, 0.0012f, 0.2074f}, {0.0776f, 0.0022f, 0.3713f}, {0.1344f, 0.0040f, 0.6456f},
    {0.2148f, 0.0073f, 1.0391f}, {0.2839f, 0.0116f, 1.3856f}, {0.3285f, 0.0168f, 1.6230f},
    {0.3483f, 0.0230f, 1.7471f}, {0.3481f, 0.0298f, 1.7826f}, {0.3362f, 0.0380f, 1.7721f},
    {0.3187f, 0.0480f, 1.7441f}, {0.2908f, 0.0600f, 1.6692f}, {0.2511f, 0.0739f, 1.5281f},
    {0.1954f, 0.0910f, 1.2876f}, {0.1421f, 0.1126f, 1.0419f}, {0.0956f, 0.1390f, 0.8130f},
    {0.0580f, 0.1693f, 0.6162f}, {0.0320f, 0.2080f, 0.4652f}, {0.0147f, 0.2586f, 0.3533f},
    {0.0049f, 0.3230f, 0.2720f}, {0.0024f, 0.4073f, 0.2123f}, {0.0093f, 0.5030f, 0.1582f},
    {0.0291f, 0.6082f, 0.1117f}, {0.0633f, 0.7100f, 0.0782f}, {0.1096f, 0.7932f, 0.0573f},
    {0.1655f, 0.8620f, 0.0422f}, {0.2257f, 0.9149f, 0.0298f}, {0.2904f, 0.9540f, 0.0203f},
    {0.3597f, 0.9803f, 0.0134f}, {0.4334f, 0.9950f, 0.0087f}, {0.5121f, 1.0000f, 0.0057f},
    {0.5945f, 0.9950f, 0.0039f}, {0.6784f, 0.9786f, 0.0027f}, {0.7621f, 0.9520f, 0.0021f},
    {0.8425f, 0.9154f, 0.0018f}, {0.9163f, 0.8700f, 0.0017f}, {0.9786f, 0.8163f, 0.0014f},
    {1.0263f, 0.7570f, 0.0011f}, {1.0567f, 0.6949f, 0.0010f}, {1.0622f, 0.6310f, 0.0008f},
    {1.0456f, 0.5668f, 0.0006f}, {1.0026f, 0.5030f, 0.0003f}, {0.9384f, 0.4412f, 0.0002f},
    {0.8544f, 0.3810f, 0.0002f}, {0.7514f, 0.3210f, 0.0001f}, {0.6424f, 0.2650f, 0.0000f},
    {0.5419f, 0.2170f, 0.0000f}, {0.4479f, 0.1750f, 0.0000f}, {0.3608f, 0.1382f, 0.0000f},
    {0.2835f, 0.1070f, 0.0000f}, {0.2187f, 0.0816f, 0.0000f}, {0.1649f, 0.0610f, 0.0000f},
    {0.1212f, 0.0446f, 0.0000f}, {0.0874f, 0.0320f, 0.0000f}, {0.0636f, 0.0232f, 0.0000f},
    {0.0468f, 0.0170f, 0.0000f}, {0.0329f, 0.0119f, 0.0000f}, {0.0227f, 0.0082f, 0.0000f},
    {0.0158f, 0.0057f, 0.0000f}, {0.0114f, 0.0041f, 0.0000f}, {0.0081f, 0.0029f, 0.0000f},
    {0.0058f, 0.0021f, 0.0000f}, {0.0041f, 0.0015f, 0.0000f}, {0.0029f, 0.0010f, 0.0000f},
    {0.0020f, 0.0007f, 0.0000f}, {0.0014f, 0.0005f, 0.0000f}, {0.0010f, 0.0004f, 0.0000f},
    {0.0007f, 0.0002f, 0.0000f}, {0.0005f, 0.0002f, 0.0000f}, {0.0003f, 0.0001f, 0.0000f},
    {0.0002f, 0.0001f, 0.0000f}, {0.0002f, 0.0001f, 0.0000f}, {0.0001f, 0.0000f, 0.0000f},
    {0.0001f, 0.0000f, 0.0000f}, {0.0001f, 0.0000f, 0.0000f}, {0.0000f, 0.0000f, 0.0000f}};

// Interpolates the table at `nm` (OSL's wavelength_color_XYZ): the index truncates toward zero,
// so wavelengths in (375, 380) extrapolate the first interval; 0 outside.
Color3f wavelength_xyz(float nm) {
  float ii = (nm - 380.0f) / 5.0f;
  int i = int(ii);
  if (i < 0 || i >= 80) return {0, 0, 0};
  ii -= float(i);
  const float* a = kCieMatch[i];
  const float* b = kCieMatch[i + 1];
  float w = 1.0f - ii;
  return {a[0] * w + b[0] * ii, a[1] * w + b[1] * ii, a[2] * w + b[2] * ii};
}

Color3f clamp_zero(Color3f c) {
  return {std::max(c.r, 0.0f), std::max(c.g, 0.0f), std::max(c.b, 0.0f)};
}

// OpenImageIO's fast_expm1 (fmath.h; facts carried over): x + x^2/2 below |x| < 0.03, else a
// 5th-degree polynomial for 2^x minus 1. OSL's Planck's law uses it, so its small errors are
// part of OSL's blackbody.
float fast_exp2(float x) {
  x = std::clamp(x, -126.0f, 126.0f);
  int m = int(x);
  x -= float(m);
  x = 1.0f - (1.0f - x); // flush denormals
  float r = 1.33336498402e-3f;
  r = x * r + 9.810352697968e-3f;
  r = x * r + 5.551834031939e-2f;
  r = x * r + 0.2401793301105f;
  r = x * r + 0.693144857883f;
  r = x * r + 1.0f;
  uint32_t bits;
  std::memcpy(&bits, &r, 4);
  bits += uint32_t(m) << 23; // times 2^m
  std::memcpy(&r, &bits, 4);
  return r;
}
float fast_expm1(float x) {
  if (std::fabs(x) < 0.03f) {
    float y = 1.0f - (1.0f - x);
    return std::copysign(0.5f * (y * y) + y, x);
  }
  return fast_exp2(x * float(1 / M_LN2)) - 1.0f;
}

// Planck's law: spectral exitance of a blackbody in W/m^2 per metre of wavelength, all in
// float as OSL 1.13.12's compiled code does it (read from its machine code): lambda^-5 as
// 1 / ((l^2)^2 l), times c1, over fast_expm1(c2 / (lambda T)).
float planck(float kelvin, float nm) {
  const float c1 = 3.74183e-16f; // 2 pi h c^2, W m^2
  const float c2 = 1.4388e-2f;   // h c / k, m K
  float l = nm * 1e-9f, l2 = l * l;
  return (1.0f / ((l2 * l2) * l)) * c1 / fast_expm1(c2 / (l * kelvin));
}

// OpenImageIO's fast_cbrt (fmath.h; facts carried over): a bit-level first guess, then two
// Newton steps.
float fast_cbrt(float x) {
  float x0 = std::fabs(x);
  int32_t bits;
  std::memcpy(&bits, &x0, 4);
  bits = 0x2a5137a0 + bits / 3;
  float a;
  std::memcpy(&a, &bits, 4);
  a = 0.333333333f * (2.0f * a + x0 / (a * a));
  a = 0.333333333f * (2.0f * a + x0 / (a * a));
  return x == 0 ? 0.0f : std::copysign(a, x);
}

// Blackbody temperatures are tabulated from the Draper point (800 K, below which OSL returns a
// very dim red) to 12000 K at T(i) = 800 + 2 i^1.5, dense where the colour changes fast. Each
// entry holds rgb^(1/5) so that linear interpolation follows the curve closely; hotter
// temperatures are integrated at each call.
constexpr float kDraper = 800.0f, kTableMax = 12000.0f;
float table_temperature(float i) {
  float s = std::sqrt(i);
  return s * s * s * 2.0f + kDraper;
}
// The inverse of table_temperature: ((T - 800) / 2)^(2/3), which OSL computes as the square of
// fast_cbrt.
float table_index(float kelvin) {
  float c = fast_cbrt((kelvin - kDraper) * 0.5f);
  return c * c;
}

} // namespace

ColorSystem::ColorSystem(std::string name, const Chromaticities& c) : name_(std::move(name)) {
  // xyz of the primaries and the white point (z = 1 - x - y).
  Color3f R{c.xr, c.yr, 0}, G{c.xg, c.yg, 0}, B{c.xb, c.yb, 0}, W{c.xw, c.yw, 0};
  R.b = 1.0f - (R.r + R.g);
  G.b = 1.0f - (G.r + G.g);
  B.b = 1.0f - (B.r + B.g);
  W.b = 1.0f - (W.r + W.g);
  auto dot = [](Color3f a, Color3f b) { return a.r * b.r + a.g * b.g + a.b * b.b; };
  // Columns of XYZ -> RGB before white scaling: cross products of the other two primaries.
  Color3f r{G.g * B.b - B.g * G.b, B.r * G.b - G.r * B.b, G.r * B.g - B.r * G.g};
  Color3f g{B.g * R.b - R.g * B.b, R.r * B.b - B.r * R.b, B.r * R.g - R.r * B.g};
  Color3f b{R.g * G.b - G.g * R.b, G.r * R.b - R.r * G.b, R.r * G.g - G.r * R.g};
  // Scale so that the white point maps to (1, 1, 1) times its luminance 1.
  Color3f w{dot(r, W), dot(g, W), dot(b, W)};
  if (W.g != 0) {
    float k = 1.0f / W.g;
    w = {w.r * k, w.g * k, w.b * k};
  }
  r = {r.r / w.r, r.g / w.r, r.b / w.r};
  g = {g.r / w.g, g.g / w.g, g.b / w.g};
  b = {b.r / w.b, b.g / w.b, b.b / w.b};
  xyz_to_rgb_ = {{{r.r, g.r, b.r}, {r.g, g.g, b.g}, {r.b, g.b, b.b}}};

  // RGB -> XYZ: the adjugate over the determinant (expanded along the first row).
  const Matrix& x = xyz_to_rgb_;
  Matrix s = {{{x[1][1] * x[2][2] - x[2][1] * x[1][2], x[2][1] * x[0][2] - x[0][1] * x[2][2],
                x[0][1] * x[1][2] - x[1][1] * x[0][2]},
               {x[2][0] * x[1][2] - x[1][0] * x[2][2], x[0][0] * x[2][2] - x[2][0] * x[0][2],
                x[1][0] * x[0][2] - x[0][0] * x[1][2]},
               {x[1][0] * x[2][1] - x[2][0] * x[1][1], x[2][0] * x[0][1] - x[0][0] * x[2][1],
                x[0][0] * x[1][1] - x[1][0] * x[0][1]}}};
  float det = x[0][0] * s[0][0] + x[0][1] * s[1][0] + x[0][2] * s[2][0];
  for (auto& row : s)
    for (float& e : row) e /= det;
  rgb_to_xyz_ = s;

  lum_ = {rgb_to_xyz_[0][1], rgb_to_xyz_[1][1], rgb_to_xyz_[2][1]};
  // Rounding can leave the weights a hair off summing to 1: close enough, make them exact.
  float blue = 1.0f - lum_[0] - lum_[1];
  if (std::fabs(blue - lum_[2]) < 0.001f) lum_[2] = blue;

  float last = 0;
  for (int i = 0; last <= kTableMax; ++i) {
    last = table_temperature(float(i));
    Color3f e = blackbody_spectral(last);
    blackbody_table_.push_back(
        {std::pow(e.r, 1.0f / 5.0f), std::pow(e.g, 1.0f / 5.0f), std::pow(e.b, 1.0f / 5.0f)});
  }
}

const std::vector<std::string>& ColorSystem::names() {
  static const std::vector<std::string> n = {"Rec709", "sRGB",       "NTSC", "EBU", "PAL",
                                             "SECAM",  "SMPTE",      "HDTV", "CIE", "AdobeRGB",
                                             "ACEScg", "ACES2065-1", "XYZ"};
  return n;
}

const ColorSystem* ColorSystem::find(std::string_view name) {
  // Chromaticities (x, y) of red, green, blue and white, in names() order (OSL's table).
  constexpr float d65x = 0.3127f, d65y = 0.3291f;
  static const Chromaticities kSpaces[] = {
      {0.64f, 0.33f, 0.30f, 0.60f, 0.15f, 0.06f, d65x, d65y},       // Rec709
      {0.64f, 0.33f, 0.30f, 0.60f, 0.15f, 0.06f, d65x, d65y},       // sRGB
      {0.67f, 0.33f, 0.21f, 0.71f, 0.14f, 0.08f, 0.3101f, 0.3162f}, // NTSC (illuminant C)
      {0.64f, 0.33f, 0.29f, 0.60f, 0.15f, 0.06f, d65x, d65y},       // EBU
      {0.64f, 0.33f, 0.29f, 0.60f, 0.15f, 0.06f, d65x, d65y},       // PAL
      {0.64f, 0.33f, 0.29f, 0.60f, 0.15f, 0.06f, d65x, d65y},       // SECAM
      {0.630f, 0.340f, 0.310f, 0.595f, 0.155f, 0.070f, d65x, d65y}, // SMPTE
      {0.670f, 0.330f, 0.210f, 0.710f, 0.150f, 0.060f, d65x, d65y}, // HDTV (as OSL has it)
      {0.7355f, 0.2645f, 0.2658f, 0.7243f, 0.1669f, 0.0085f, 0.33333333f, 0.33333333f}, // CIE
      {0.64f, 0.33f, 0.21f, 0.71f, 0.15f, 0.06f, d65x, d65y},                           // AdobeRGB
      {0.713f, 0.293f, 0.165f, 0.830f, 0.128f, 0.044f, 0.32168f, 0.33767f},             // ACEScg
      {0.7347f, 0.2653f, 0.0f, 1.0f, 0.0001f, -0.077f, 0.32168f, 0.33767f}, // ACES2065-1 (AP0)
      {1.0f, 0.0f, 0.0f, 1.0f, 0.0f, 0.0f, 0.33333333f, 0.33333333f},       // XYZ itself (white E)
  };
  constexpr size_t kCount = sizeof(kSpaces) / sizeof(kSpaces[0]);
  static std::once_flag once[kCount];
  static std::unique_ptr<ColorSystem> systems[kCount];
  const std::vector<std::string>& n = names();
  for (size_t i = 0; i < kCount; ++i) {
    if (n[i] != name) continue;
    std::call_once(once[i], [&] { systems[i] = std::make_unique<ColorSystem>(n[i], kSpaces[i]); });
    return systems[i].get();
  }
  return nullptr;
}

const ColorSystem& ColorSystem::rec709() { return *find("Rec709"); }

float ColorSystem::luminance(const Color3f& c) const {
  return c.r * lum_[0] + c.g * lum_[1] + c.b * lum_[2];
}

template <class C>
bool ColorSystem::to_rgb_builtin(std::string_view space, const C& c, C& out) const {
  if (space == "hsv")
    out = hsv_to_rgb(c);
  else if (space == "hsl")
    out = hsl_to_rgb(c);
  else if (space == "YIQ")
    out = mul(c, kYiqToRgb);
  else if (space == "XYZ")
    out = mul(c, xyz_to_rgb_);
  else if (space == "xyY")
    out = mul(xyy_to_xyz(c), xyz_to_rgb_);
  else
    return false;
  return true;
}

template <class C>
bool ColorSystem::from_rgb_builtin(std::string_view space, const C& c, C& out) const {
  if (space == "hsv")
    out = rgb_to_hsv(c);
  else if (space == "hsl")
    out = rgb_to_hsl(c);
  else if (space == "YIQ")
    out = mul(c, kRgbToYiq);
  else if (space == "XYZ")
    out = mul(c, rgb_to_xyz_);
  else if (space == "xyY")
    out = xyz_to_xyy(mul(c, rgb_to_xyz_));
  else
    return false;
  return true;
}

template <class C>
bool ColorSystem::transform_impl(std::string_view from, std::string_view to, const C& c,
                                 C& out) const {
  auto srgb_decode = [](const auto& x) { return srgb_to_linear(x); };
  auto srgb_encode = [](const auto& x) { return linear_to_srgb(x); };
  // The same space on both sides goes through rgb too, as OSL computes it (XYZ to XYZ rounds a
  // little); a name not OSL's own is the colour unchanged (below).
  C rgb;
  bool known = true;
  if (is_linear_rgb(from) || from == name_)
    rgb = c;
  else if (from == "sRGB")
    rgb = per_component(c, srgb_decode);
  else
    known = to_rgb_builtin(from, c, rgb);
  if (!known) {
  } else if (is_linear_rgb(to) || to == name_)
    out = rgb;
  else if (to == "sRGB")
    out = per_component(rgb, srgb_encode);
  else
    known = from_rgb_builtin(to, rgb, out);
  if (known) return true;
  if (from == to) { // any other name to itself: the colour unchanged, no error
    out = c;
    return true;
  }
  // Either name is not OSL's own: the pair goes to OpenImageIO, as named.
  OiioCurve k = oiio_curve_for(from, to);
  if (!k.f && !k.gamma) {
    out = c;
    return false;
  }
  out = per_component(c, [&](const auto& x) { return apply(k, x); });
  return true;
}

bool ColorSystem::transform(std::string_view from, std::string_view to, const Color3f& c,
                            Color3f& out) const {
  return transform_impl(from, to, c, out);
}
bool ColorSystem::transform(std::string_view from, std::string_view to, const Color3d& c,
                            Color3d& out) const {
  return transform_impl(from, to, c, out);
}

bool ColorSystem::to_rgb(std::string_view space, const Color3f& c, Color3f& out) const {
  if (space == "rgb" || space == "RGB" || space == name_) {
    out = c;
    return true;
  }
  if (to_rgb_builtin(space, c, out)) return true;
  out = c;
  return false;
}

// Planck's law weighted by the CIE functions every 5 nm (each sample times d lambda), to RGB
// with negative components clipped.
Color3f ColorSystem::blackbody_spectral(float kelvin) const {
  float X = 0, Y = 0, Z = 0;
  const float dlambda = 5e-9f;
  for (int i = 0; i < 81; ++i) {
    float me = planck(kelvin, float(i) * 5.0f + 380.0f) * dlambda;
    X += me * kCieMatch[i][0];
    Y += me * kCieMatch[i][1];
    Z += me * kCieMatch[i][2];
  }
  return clamp_zero(mul(Color3f{X, Y, Z}, xyz_to_rgb_));
}

Color3f ColorSystem::blackbody(float kelvin) const {
  if (kelvin < kDraper) return {1.0e-6f, 0, 0}; // very dim red
  if (kelvin >= kTableMax) return blackbody_spectral(kelvin);
  float t = table_index(kelvin);
  int i = int(t);
  t -= float(i);
  const Color3f& a = blackbody_table_[size_t(i)];
  const Color3f& b = blackbody_table_[size_t(i) + 1];
  float w = 1.0f - t;
  Color3f c{a.r * w + b.r * t, a.g * w + b.g * t, a.b * w + b.b * t};
  auto pow5 = [](float x) { // as OSL's compiled code: (x^2)^2 x
    float x2 = x * x;
    return (x2 * x2) * x;
  };
  return {pow5(c.r), pow5(c.g), pow5(c.b)};
}

Color3f ColorSystem::wavelength_color(float nm) const {
  Color3f c = mul(wavelength_xyz(nm), xyz_to_rgb_);
  const float k = float(1.0 / 2.52); // OSL's empirical scale: every component <= 1
  return clamp_zero({c.r * k, c.g * k, c.b * k});
}

} // namespace lobe::shadeops
