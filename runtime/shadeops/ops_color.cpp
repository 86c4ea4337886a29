// Colour shadeops: conversions between "rgb" (linear Rec.709, D65) and the named spaces "hsv",
// "hsl", "YIQ", "XYZ", "xyY"; blackbody(); wavelength_color(). Spectral colours use the CIE
// 1931 2-degree observer tabulated every 5 nm, as OSL's opcolor.cpp does.
#include "lobe/context.h"
#include "lobe/shading.h"

#include <algorithm>
#include <cmath>
#include <string>

using lobe::ShaderGlobals;

namespace {

struct C3 {
  float r, g, b;
};

C3 xyz_to_rgb(C3 c) {
  return {3.2404542f * c.r - 1.5371385f * c.g - 0.4985314f * c.b,
          -0.9692660f * c.r + 1.8760108f * c.g + 0.0415560f * c.b,
          0.0556434f * c.r - 0.2040259f * c.g + 1.0572252f * c.b};
}
C3 rgb_to_xyz(C3 c) {
  return {0.4124564f * c.r + 0.3575761f * c.g + 0.1804375f * c.b,
          0.2126729f * c.r + 0.7151522f * c.g + 0.0721750f * c.b,
          0.0193339f * c.r + 0.1191920f * c.g + 0.9503041f * c.b};
}

C3 hsv_to_rgb(C3 c) {
  float h = c.r, s = c.g, v = c.b;
  if (s <= 0) return {v, v, v};
  h = (h - std::floor(h)) * 6.0f;
  int i = int(h);
  float f = h - float(i), p = v * (1 - s), q = v * (1 - s * f), t = v * (1 - s * (1 - f));
  switch (i) {
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
C3 rgb_to_hsv(C3 c) {
  float mx = std::max({c.r, c.g, c.b}), mn = std::min({c.r, c.g, c.b}), d = mx - mn;
  float h = 0, s = mx > 0 ? d / mx : 0;
  if (d > 0) {
    if (c.r == mx)
      h = (c.g - c.b) / d;
    else if (c.g == mx)
      h = 2 + (c.b - c.r) / d;
    else
      h = 4 + (c.r - c.g) / d;
    h /= 6.0f;
    if (h < 0) h += 1.0f;
  }
  return {h, s, mx};
}
C3 hsl_to_rgb(C3 c) {
  float h = c.r, s = c.g, l = c.b;
  float v = l <= 0.5f ? l * (1 + s) : l + s - l * s;
  if (v <= 0) return {0, 0, 0};
  float mn = 2 * l - v;
  return hsv_to_rgb({h, (v - mn) / v, v});
}
C3 rgb_to_hsl(C3 c) {
  float mx = std::max({c.r, c.g, c.b}), mn = std::min({c.r, c.g, c.b});
  float l = 0.5f * (mx + mn), d = mx - mn;
  float s = 0;
  if (d > 0) s = l <= 0.5f ? d / (mx + mn) : d / (2 - mx - mn);
  return {rgb_to_hsv(c).r, s, l};
}
C3 yiq_to_rgb(C3 c) {
  return {c.r + 0.956f * c.g + 0.621f * c.b, c.r - 0.272f * c.g - 0.647f * c.b,
          c.r - 1.107f * c.g + 1.704f * c.b};
}
C3 rgb_to_yiq(C3 c) {
  return {0.299f * c.r + 0.587f * c.g + 0.114f * c.b, 0.596f * c.r - 0.275f * c.g - 0.321f * c.b,
          0.212f * c.r - 0.523f * c.g + 0.311f * c.b};
}
C3 xyy_to_rgb(C3 c) {
  float x = c.r, y = c.g, Y = c.b;
  if (y == 0) return {0, 0, 0};
  return xyz_to_rgb({x * Y / y, Y, (1 - x - y) * Y / y});
}
C3 rgb_to_xyy(C3 c) {
  C3 xyz = rgb_to_xyz(c);
  float s = xyz.r + xyz.g + xyz.b;
  if (s == 0) return {0, 0, 0};
  return {xyz.r / s, xyz.g / s, xyz.g};
}

// Converts between rgb and a named space; false for an unknown name.
bool to_rgb(const std::string& s, C3 in, C3& out) {
  if (s == "rgb" || s == "RGB" || s == "linear")
    out = in;
  else if (s == "hsv")
    out = hsv_to_rgb(in);
  else if (s == "hsl")
    out = hsl_to_rgb(in);
  else if (s == "YIQ")
    out = yiq_to_rgb(in);
  else if (s == "XYZ")
    out = xyz_to_rgb(in);
  else if (s == "xyY")
    out = xyy_to_rgb(in);
  else
    return false;
  return true;
}
bool from_rgb(const std::string& s, C3 in, C3& out) {
  if (s == "rgb" || s == "RGB" || s == "linear")
    out = in;
  else if (s == "hsv")
    out = rgb_to_hsv(in);
  else if (s == "hsl")
    out = rgb_to_hsl(in);
  else if (s == "YIQ")
    out = rgb_to_yiq(in);
  else if (s == "XYZ")
    out = rgb_to_xyz(in);
  else if (s == "xyY")
    out = rgb_to_xyy(in);
  else
    return false;
  return true;
}

// CIE 1931 2-degree colour matching functions (x-bar, y-bar, z-bar) from 380 to 780 nm every
// 5 nm: the table OSL's opcolor.cpp uses (John Walker's specrend.c, 4 digits).
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

// XYZ of a single wavelength (OSL's wavelength_color_XYZ): the table linearly interpolated,
// 0 outside [380, 780) nm.
C3 wavelength_xyz(float lambda_nm) {
  float ii = (lambda_nm - 380.0f) / 5.0f;
  if (!(ii >= 0)) return {0, 0, 0};
  int i = int(ii);
  if (i >= 80) return {0, 0, 0};
  float t = ii - float(i);
  const float* a = kCieMatch[i];
  const float* b = kCieMatch[i + 1];
  return {a[0] + (b[0] - a[0]) * t, a[1] + (b[1] - a[1]) * t, a[2] + (b[2] - a[2]) * t};
}

void store_clamped(float* dst, C3 c) {
  dst[0] = std::max(c.r, 0.0f);
  dst[1] = std::max(c.g, 0.0f);
  dst[2] = std::max(c.b, 0.0f);
}

} // namespace

extern "C" {

// dst = src converted from space `from` to space `to` (either may be "rgb").
void lobe_transformc(ShaderGlobals* sg, const char* from, const char* to, float* dst,
                     const float* src) {
  C3 in{src[0], src[1], src[2]}, rgb, out;
  bool ok = to_rgb(from, in, rgb) && from_rgb(to, rgb, out);
  if (!ok) {
    out = in;
    if (sg && sg->context) {
      sg->context->error(std::string("Unknown color space \"") +
                         (to_rgb(from, in, rgb) ? to : from) + "\"");
    }
  }
  dst[0] = out.r;
  dst[1] = out.g;
  dst[2] = out.b;
}

// OSL's wavelength_color: the XYZ of the spectral line in linear Rec.709 RGB, scaled by
// 1/2.52 (OSL's empirical scale keeping every component <= 1), negative components clipped.
void lobe_wavelength_color(float* dst, float lambda_nm) {
  C3 c = xyz_to_rgb(wavelength_xyz(lambda_nm));
  const float k = float(1.0 / 2.52);
  store_clamped(dst, {c.r * k, c.g * k, c.b * k});
}

// OSL's blackbody: the emission of a blackbody at `kelvin` in W/m^2 (not normalised): Planck's
// spectral exitance c1 lambda^-5 / (exp(c2 / (lambda T)) - 1) sampled every 5 nm over
// 380-780 nm, times d lambda, weighted by the CIE table, then XYZ -> RGB with negatives
// clipped. Below the Draper point (800 K) it is OSL's "very dim red" (1e-6, 0, 0). OSL reads
// temperatures under 12000 K from an interpolated table of this function; Lobe computes it.
void lobe_blackbody(float* dst, float kelvin) {
  if (!(kelvin >= 800.0f)) {
    dst[0] = 1.0e-6f;
    dst[1] = dst[2] = 0;
    return;
  }
  const double c1 = 3.74183e-16; // 2 pi h c^2, W m^2
  const double c2 = 1.4388e-2;   // h c / k, m K
  const float dlambda = 5.0f * 1e-9f;
  float X = 0, Y = 0, Z = 0;
  for (int i = 0; i < 81; ++i) {
    double wlm = (380.0 + 5.0 * i) * 1e-9;
    float Me = float(c1 * std::pow(wlm, -5.0) / std::expm1(c2 / (wlm * kelvin))) * dlambda;
    X += Me * kCieMatch[i][0];
    Y += Me * kCieMatch[i][1];
    Z += Me * kCieMatch[i][2];
  }
  store_clamped(dst, xyz_to_rgb({X, Y, Z}));
}

float lobe_luminance(const float* c) {
  return 0.2126729f * c[0] + 0.7151522f * c[1] + 0.0721750f * c[2];
}

} // extern "C"
