// A colour system: the RGB space a material's colours are in (CompileOptions::colorspace, OSL's
// ShadingSystem "colorspace" attribute) and the colour functions that depend on it:
// transformc and color("space", ...), luminance, blackbody, wavelength_color.
//
// An RGB space is given by the CIE xy chromaticities of its primaries and white point. Its
// XYZ -> RGB matrix is built as OSL builds it (in float, from cross products of the primaries'
// xyz, scaled so that the white point has luminance 1), RGB -> XYZ is its inverse by the
// adjugate (Imath's Matrix33::inverse), and the luminance weights are the Y row of RGB -> XYZ
// (the blue weight replaced by 1 - r - g when that is within 0.001). Colours are row vectors
// (rgb = xyz * M), summed left to right, as Imath's Vec3 * Matrix33.
//
// Every function has a value-only form and a form that carries screen-space derivatives with
// OSL's dual-number rules (DualF), so a transformc whose result is differentiated gives OSL's
// derivatives. Immutable after construction: shared by every material and thread.
#pragma once

#include <array>
#include <string>
#include <string_view>
#include <vector>

namespace lobe::shadeops {

// A float and its derivatives d/dx, d/dy (OSL's Dual2<float>).
struct DualF {
  float v = 0, dx = 0, dy = 0;
};

template <class S> struct Color3T { S r, g, b; };
using Color3f = Color3T<float>;
using Color3d = Color3T<DualF>; // value and derivatives

class ColorSystem {
public:
  // The named RGB spaces, as OSL 1.13 names them (case-sensitive): Rec709 (the default), sRGB
  // (the same primaries), NTSC, EBU, PAL, SECAM, SMPTE, HDTV, CIE, AdobeRGB, ACEScg, ACES2065-1,
  // XYZ. Null for any other name. The result lives for the whole process.
  static const ColorSystem* find(std::string_view name);
  static const ColorSystem& rec709();
  static const std::vector<std::string>& names();

  const std::string& name() const { return name_; }
  // Luminance weights (the Y row of RGB -> XYZ).
  const std::array<float, 3>& luminance_weights() const { return lum_; }
  float luminance(const Color3f& c) const;

  // transformc(from, to, c): false (and `out` = c) when either name is unknown. Known names:
  // "rgb", "RGB", "linear" and this system's own name (the identity), "hsv", "hsl", "YIQ",
  // "XYZ", "xyY" and "sRGB" (the sRGB transfer curve over this system's primaries).
  bool transform(std::string_view from, std::string_view to, const Color3f& c, Color3f& out) const;
  bool transform(std::string_view from, std::string_view to, const Color3d& c, Color3d& out) const;
  // color("space", a, b, c): to RGB from `space`, which is "rgb", "RGB", this system's name,
  // "hsv", "hsl", "YIQ", "XYZ" or "xyY" (OSL's constructor does not know "linear" or "sRGB").
  // False (and `out` = c) for any other name.
  bool to_rgb(std::string_view space, const Color3f& c, Color3f& out) const;

  // Emission of a blackbody at `kelvin`, in this space's RGB (W/m^2 per unit of the CIE
  // functions, not normalised).
  Color3f blackbody(float kelvin) const;
  // The colour of monochromatic light of wavelength `nm` (OSL's wavelength_color).
  Color3f wavelength_color(float nm) const;

  struct Chromaticities {
    float xr, yr, xg, yg, xb, yb, xw, yw;
  };
  using Matrix = std::array<std::array<float, 3>, 3>;
  ColorSystem(std::string name, const Chromaticities& c);

private:
  template <class C> bool to_rgb_builtin(std::string_view space, const C& c, C& out) const;
  template <class C> bool from_rgb_builtin(std::string_view space, const C& c, C& out) const;
  template <class C>
  bool transform_impl(std::string_view from, std::string_view to, const C& c, C& out) const;
  Color3f blackbody_spectral(float kelvin) const;

  std::string name_;
  Matrix xyz_to_rgb_{}, rgb_to_xyz_{};
  std::array<float, 3> lum_{};
  std::vector<Color3f> blackbody_table_; // blackbody^(1/5) at blackbody_table_temperature(i)
};

} // namespace lobe::shadeops
