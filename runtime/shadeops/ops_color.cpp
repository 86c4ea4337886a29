// Colour shadeops: conversions between "rgb" (linear Rec.709, D65) and the named spaces "hsv",
// "hsl", "YIQ", "XYZ", "xyY"; blackbody(); wavelength_color(). Spectral colours use the CIE
// 1931 2-degree observer in Wyman, Sloan & Shirley's multi-lobe Gaussian fit (JCGT 2013).
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

double lobe_g(double x, double mu, double s1, double s2) {
  double t = (x - mu) / (x < mu ? s1 : s2);
  return std::exp(-0.5 * t * t);
}
// CIE 1931 colour matching functions (Wyman et al. multi-lobe fit), lambda in nm.
C3 cie_xyz(double l) {
  double x = 1.056 * lobe_g(l, 599.8, 37.9, 31.0) + 0.362 * lobe_g(l, 442.0, 16.0, 26.7) -
             0.065 * lobe_g(l, 501.1, 20.4, 26.2);
  double y = 0.821 * lobe_g(l, 568.8, 46.9, 40.5) + 0.286 * lobe_g(l, 530.9, 16.3, 31.1);
  double z = 1.217 * lobe_g(l, 437.0, 11.8, 36.0) + 0.681 * lobe_g(l, 459.0, 26.0, 13.8);
  return {float(x), float(y), float(z)};
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
      sg->context->errors++;
      sg->context->message(std::string("ERROR: Unknown color space \"") +
                           (to_rgb(from, in, rgb) ? to : from) + "\"\n");
    }
  }
  dst[0] = out.r;
  dst[1] = out.g;
  dst[2] = out.b;
}

// The colour of a pure spectral line, negative components clipped to zero.
void lobe_wavelength_color(float* dst, float lambda_nm) {
  store_clamped(dst, xyz_to_rgb(cie_xyz(lambda_nm)));
}

// The colour of a blackbody at `kelvin`, scaled to luminance 1 (Planck's law integrated
// against the CIE observer over 380-780 nm in 1 nm steps).
void lobe_blackbody(float* dst, float kelvin) {
  if (!(kelvin > 0)) {
    dst[0] = dst[1] = dst[2] = 0;
    return;
  }
  const double h = 6.62607015e-34, c = 2.99792458e8, k = 1.380649e-23;
  double X = 0, Y = 0, Z = 0;
  for (int l = 380; l <= 780; ++l) {
    double lm = l * 1e-9;
    double b = 2 * h * c * c / (std::pow(lm, 5) * (std::expm1(h * c / (lm * k * kelvin))));
    C3 m = cie_xyz(l);
    X += b * m.r;
    Y += b * m.g;
    Z += b * m.b;
  }
  if (!(Y > 0)) {
    dst[0] = dst[1] = dst[2] = 0;
    return;
  }
  store_clamped(dst, xyz_to_rgb({float(X / Y), 1.0f, float(Z / Y)}));
}

float lobe_luminance(const float* c) {
  return 0.2126729f * c[0] + 0.7151522f * c[1] + 0.0721750f * c[2];
}

} // extern "C"
