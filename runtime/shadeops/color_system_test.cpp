// ColorSystem against values OSL 1.13.12 printed, equal as floats.
// Each value came from `oslc t.osl; testshade -g 1 1 --colorspace NAME t` on a shader printing
// it with "%.9g", e.g. printf("%.9g\n", transformc("rgb", "hsl", color(-.2, .5, .3) + k)) with
// k = (u > 10) ? 1 : 0 (so the call is not folded), wavelength_color(377.5 + k),
// blackbody(1500 + k); the derivatives from
//   color c = color(.1, .7, .2) + (u - .5) * color(.15, 0, -.01) + (v - .5) * color(-.025, .1, 0);
//   color h = transformc("rgb", "hsv", c); printf("%.9g / %.9g / %.9g\n", h, Dx(h), Dy(h));
// (-g 1 1 shades u = v = 0.5 with Dx(u) = Dy(v) = 1). The shader corpus
// (tests/shade/color_systems.osl) checks the same through compiled shaders in every space.
#include "color_system.h"

#include <gtest/gtest.h>

namespace {

using lobe::shadeops::Color3d;
using lobe::shadeops::Color3f;
using lobe::shadeops::ColorSystem;

const ColorSystem& space(const char* name) {
  const ColorSystem* cs = ColorSystem::find(name);
  EXPECT_NE(cs, nullptr) << name;
  return cs ? *cs : ColorSystem::rec709();
}

void expect_color(const Color3f& got, float r, float g, float b, const char* what) {
  EXPECT_EQ(got.r, r) << what;
  EXPECT_EQ(got.g, g) << what;
  EXPECT_EQ(got.b, b) << what;
}

Color3f tc(const ColorSystem& cs, const char* from, const char* to, Color3f c) {
  Color3f out;
  EXPECT_TRUE(cs.transform(from, to, c, out)) << from << " -> " << to;
  return out;
}

TEST(ColorSystem, NamesAreOslsAndCaseSensitive) {
  EXPECT_EQ(ColorSystem::names().size(), 13u);
  for (const std::string& n : ColorSystem::names()) EXPECT_EQ(space(n.c_str()).name(), n);
  EXPECT_EQ(ColorSystem::find("rec709"), nullptr);
  EXPECT_EQ(ColorSystem::find("Rec2020"), nullptr);
  EXPECT_EQ(ColorSystem::find("linear"), nullptr);
}

// XYZ <-> RGB matrices and luminance weights (the Y row; blue adjusted to sum to 1).
TEST(ColorSystem, MatricesAndLuminanceFromChromaticities) {
  const ColorSystem& rec = ColorSystem::rec709();
  expect_color(tc(rec, "XYZ", "rgb", {1, 0, 0}), 3.24297929f, -0.968997717f, 0.0556683466f, "X");
  expect_color(tc(rec, "rgb", "XYZ", {0, 0, 1}), 0.180356786f, 0.0721427053f, 0.94987905f, "b");
  EXPECT_EQ(rec.luminance_weights()[2], 0.072142601f);
  EXPECT_EQ(rec.luminance({.1f, .7f, .2f}), 0.536424339f);
  expect_color(tc(rec, "rgb", "XYZ", {.1f, .7f, .2f}), 0.327657461f, 0.536424398f, 0.275365174f,
               "Rec709");
  const ColorSystem& aces = space("ACEScg");
  expect_color(tc(aces, "rgb", "XYZ", {.1f, .7f, .2f}), 0.191285878f, 0.509817958f, 0.204352856f,
               "ACEScg");
  EXPECT_EQ(aces.luminance({.1f, .7f, .2f}), 0.509817958f);
  expect_color(tc(space("NTSC"), "rgb", "XYZ", {1, 0, 0}), 0.60693717f, 0.298939198f,
               2.52388443e-09f, "NTSC red");
  expect_color(tc(space("HDTV"), "XYZ", "rgb", {1, 0, 0}), 2.04234529f, -0.893684268f,
               0.0637959838f, "HDTV X");
  expect_color(tc(space("CIE"), "XYZ", "rgb", {0, 1, 0}), -0.833367765f, 1.4227581f, -0.015906807f,
               "CIE Y");
  EXPECT_EQ(space("SMPTE").luminance_weights()[1], 0.701260567f);
  EXPECT_EQ(space("EBU").luminance_weights()[0], space("SECAM").luminance_weights()[0]);
}

// The two spaces OSL 1.13 has beyond the RGB ones above: XYZ itself (primaries on the axes,
// white E), whose matrices are the identity, and ACES2065-1 (AP0), whose RGB -> XYZ luminance row
// the ACES specification gives (SMPTE ST 2065-1: 0.3439664498, 0.7281660966, -0.0721325464).
// OSL 1.13.12 prints 0.2 and 0.15839 for luminance(color(.1, .2, .3)) with `testshade
// --colorspace XYZ` and `--colorspace ACES2065-1`.
TEST(ColorSystem, XyzAndAces2065) {
  const ColorSystem& xyz = space("XYZ");
  expect_color(tc(xyz, "rgb", "XYZ", {.1f, .7f, .2f}), .1f, .7f, .2f, "XYZ rgb -> XYZ");
  expect_color(tc(xyz, "XYZ", "rgb", {.3f, .2f, .1f}), .3f, .2f, .1f, "XYZ XYZ -> rgb");
  EXPECT_FLOAT_EQ(xyz.luminance({.1f, .2f, .3f}), .2f);
  const ColorSystem& ap0 = space("ACES2065-1");
  EXPECT_NEAR(ap0.luminance_weights()[0], 0.3439664498f, 2e-6f);
  EXPECT_NEAR(ap0.luminance_weights()[1], 0.7281660966f, 2e-6f);
  EXPECT_NEAR(ap0.luminance_weights()[2], -0.0721325464f, 2e-6f);
  EXPECT_NEAR(ap0.luminance({.1f, .2f, .3f}), 0.15839f, 5e-6f);
}

// Colour models, including hue ties and out-of-gamut values.
TEST(ColorSystem, ModelsAsOsl) {
  const ColorSystem& cs = ColorSystem::rec709();
  expect_color(tc(cs, "rgb", "hsv", {0.7f, 0.7f, 0.1f}), 0.166666657f, 0.857142806f, 0.699999988f,
               "hsv tie");
  expect_color(tc(cs, "rgb", "hsl", {0.25f, 0.5f, 0.75f}), 0.583333373f, 0.5f, 0.5f, "hsl");
  expect_color(tc(cs, "rgb", "hsl", {-0.2f, 0.5f, 0.3f}), 0.452380955f, 2.33333325f, 0.150000006f,
               "hsl negative");
  expect_color(tc(cs, "hsv", "rgb", {0.7f, 0.7f, 0.1f}), 0.0439999886f, 0.0300000012f, 0.100000001f,
               "from hsv");
  expect_color(tc(cs, "hsl", "rgb", {-0.2f, 0.5f, 0.3f}), 0.390000075f, 0.149999991f, 0.450000018f,
               "from hsl");
  expect_color(tc(cs, "YIQ", "rgb", {0.25f, 0.5f, 0.75f}), 1.19277501f, -0.370975018f, 0.974725068f,
               "from YIQ");
  expect_color(tc(cs, "rgb", "xyY", {0.25f, 0.5f, 0.75f}), 0.251455247f, 0.280251443f, 0.464908928f,
               "xyY");
  expect_color(tc(cs, "xyY", "rgb", {-0.2f, 0.5f, 0.3f}), -1.06020486f, 0.696375966f, 0.376317978f,
               "from xyY");
  expect_color(tc(cs, "rgb", "sRGB", {-0.2f, 0.5f, 0.3f}), -2.58400011f, 0.735356927f, 0.583831489f,
               "sRGB");
  expect_color(tc(cs, "sRGB", "rgb", {0.25f, 0.5f, 0.75f}), 0.0508760884f, 0.214041144f,
               0.522521615f, "from sRGB");
  expect_color(tc(cs, "Rec709", "linear", {0.25f, 0.5f, 0.75f}), 0.25f, 0.5f, 0.75f, "own name");
  // In another system "Rec709" is OpenImageIO's Rec.709 curve, from a linear name only.
  const ColorSystem& aces = space("ACEScg");
  expect_color(tc(aces, "linear", "Rec709", {0.25f, 0.5f, 0.75f}), 0.489939541f, 0.705515087f,
               0.866551101f, "OIIO Rec709");
  expect_color(tc(aces, "Rec709", "lnf", {0.25f, 0.5f, 0.75f}), 0.0781538785f, 0.259589404f,
               0.563522279f, "OIIO Rec709 inverse");
  expect_color(tc(aces, "lnf", "sRGB", {0.01f, 0.5f, 0.9f}), 0.0998541489f, 0.735353529f,
               0.954687059f, "OIIO sRGB");
}

TEST(ColorSystem, UnknownNamesLeaveTheColour) {
  const ColorSystem& cs = ColorSystem::rec709();
  Color3f out;
  EXPECT_FALSE(cs.transform("rgb", "Rec2020", {.1f, .2f, .3f}, out));
  expect_color(out, .1f, .2f, .3f, "unknown");
  EXPECT_FALSE(space("ACEScg").transform("rgb", "Rec709", {.1f, .2f, .3f}, out)); // OIIO: no "rgb"
  EXPECT_TRUE(cs.transform("bogus", "bogus", {.1f, .2f, .3f}, out));              // same name
  // The constructor knows neither "linear" nor "sRGB".
  EXPECT_FALSE(cs.to_rgb("linear", {.1f, .2f, .3f}, out));
  EXPECT_FALSE(cs.to_rgb("sRGB", {.1f, .2f, .3f}, out));
  EXPECT_TRUE(cs.to_rgb("Rec709", {.1f, .2f, .3f}, out));
}

// Derivatives through OSL's dual formulas: c = (0.1, 0.7, 0.2), d/dx = (0.15, 0, -0.01),
// d/dy = (-0.025, 0.1, 0).
TEST(ColorSystem, DerivativesAsOsl) {
  Color3d c{{0.1f, 0.15f, -0.025f}, {0.7f, 0, 0.1f}, {0.2f, -0.01f, 0}}, out;
  const ColorSystem& cs = ColorSystem::rec709();
  ASSERT_TRUE(cs.transform("rgb", "hsv", c, out));
  EXPECT_EQ(out.r.v, 0.361111134f);
  EXPECT_EQ(out.r.dx, -0.0375000015f);
  EXPECT_EQ(out.r.dy, 0.00115740683f);
  EXPECT_EQ(out.g.dx, -0.214285731f);
  EXPECT_EQ(out.g.dy, 0.0561224595f);
  ASSERT_TRUE(cs.transform("rgb", "sRGB", c, out));
  EXPECT_EQ(out.r.v, 0.349190235f); // the dual curve rounds unlike the value-only one
  EXPECT_EQ(out.r.dx, 0.252618909f);
  EXPECT_EQ(out.r.dy, -0.042103149f);
  EXPECT_EQ(out.b.dx, -0.0112401918f);
  ASSERT_TRUE(cs.transform("sRGB", "rgb", c, out));
  EXPECT_EQ(out.r.dx, 0.0232788213f);
  EXPECT_EQ(out.g.dy, 0.142406926f);
  ASSERT_TRUE(cs.transform("rgb", "xyY", c, out));
  EXPECT_EQ(out.r.dx, 0.0313290581f);
  EXPECT_EQ(out.g.dy, 0.0155102313f);
  EXPECT_EQ(out.b.dy, 0.0662223324f);
}

TEST(ColorSystem, WavelengthColorAsOsl) {
  const ColorSystem& rec = ColorSystem::rec709();
  expect_color(rec.wavelength_color(377.5f), 0.0004264905f, 0, 0.00191488757f, "377.5");
  expect_color(rec.wavelength_color(500), 0, 0.242990404f, 0.0881098732f, "500");
  expect_color(rec.wavelength_color(779.9f), 2.57336092e-06f, 0, 4.41738095e-08f, "779.9");
  expect_color(rec.wavelength_color(375), 0, 0, 0, "375");
  expect_color(rec.wavelength_color(780), 0, 0, 0, "780");
  const ColorSystem& ntsc = space("NTSC");
  expect_color(ntsc.wavelength_color(450), 0.0441125222f, 0, 0.63743794f, "NTSC 450");
  expect_color(ntsc.wavelength_color(552.5f), 0.146716028f, 0.606508017f, 0, "NTSC 552.5");
}

// blackbody: the table below 12000 K (read with fast_cbrt, raised to the 5th power by
// multiplications) and Planck's law through fast_expm1 above, to the bit.
TEST(ColorSystem, BlackbodyAsOsl) {
  struct B {
    const char* space;
    float t, r, g, b;
  } const cases[] = {{"Rec709", 1500, 116.336136f, 15.4565277f, 0},
                     {"Rec709", 3000, 246272.578f, 117305.633f, 37833.5703f},
                     {"Rec709", 6500, 14753309, 13896832, 14630983},
                     {"Rec709", 20000, 215377984, 284642752, 530805856},
                     {"Rec709", 1e6f, 1.96196577e+10f, 2.88010076e+10f, 6.55486075e+10f},
                     {"ACEScg", 1500, 75.0558929f, 22.3460865f, 2.22219419f},
                     {"ACEScg", 6500, 14130217, 14007613, 15699098},
                     {"NTSC", 3000, 197257.562f, 128314.359f, 41407.3555f},
                     {"CIE", 20000, 168824480, 311018688, 544884608}};
  for (const B& c : cases) expect_color(space(c.space).blackbody(c.t), c.r, c.g, c.b, c.space);
  // At the Draper point the first table entry, read back exactly.
  expect_color(ColorSystem::rec709().blackbody(800), 0.000201023242f, 0, 0, "800");
  expect_color(ColorSystem::rec709().blackbody(799.9f), 1e-6f, 0, 0, "below the Draper point");
}

} // namespace
