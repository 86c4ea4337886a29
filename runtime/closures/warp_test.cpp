// lobe/warp.h against double-precision libm: the quarter-range sincos within an ulp or two,
// and the concentric disk map equal to its definition with the angle's sin and cos.
#include "lobe/warp.h"

#include <gtest/gtest.h>

#include <cmath>

namespace lobe {
namespace {

constexpr double kQuarterPi = 0.78539816339744830962;

TEST(Warp, SincosQuarterWithinTwoUlps) {
  double worst_s = 0, worst_c = 0;
  for (int i = -20000; i <= 20000; ++i) {
    float t = float(kQuarterPi * i / 20000.0);
    float s, c;
    sincos_quarter(t, s, c);
    double ws = std::sin(double(t)), wc = std::cos(double(t));
    // In ulps of the float result's magnitude (spacing at |x|: 2^(exponent - 23)).
    auto ulps = [](double got, double want) {
      int e;
      std::frexp(want == 0 ? 1e-30 : want, &e);
      return std::abs(got - want) / std::ldexp(1.0, e - 24);
    };
    if (t != 0) worst_s = std::max(worst_s, ulps(s, ws));
    worst_c = std::max(worst_c, ulps(c, wc));
  }
  EXPECT_LE(worst_s, 2.0);
  EXPECT_LE(worst_c, 2.0);
  float s, c;
  sincos_quarter(0.0f, s, c);
  EXPECT_EQ(s, 0.0f);
  EXPECT_EQ(c, 1.0f);
}

TEST(Warp, ConcentricDiskIsShirleyChiu) {
  // Shirley and Chiu's map written out in double precision with libm's sin and cos.
  double worst = 0;
  for (int i = 0; i <= 256; ++i)
    for (int j = 0; j <= 256; ++j) {
      float u1 = std::min(i / 256.0f, 0x1.fffffep-1f), u2 = std::min(j / 256.0f, 0x1.fffffep-1f);
      double a = 2.0 * u1 - 1, b = 2.0 * u2 - 1, r, phi;
      if (a == 0 && b == 0) {
        r = 0, phi = 0;
      } else if (std::abs(a) > std::abs(b)) {
        r = a, phi = kQuarterPi * (b / a);
      } else {
        r = b, phi = 2 * kQuarterPi - kQuarterPi * (a / b);
      }
      float x, y;
      concentric_disk(u1, u2, x, y);
      worst = std::max({worst, std::abs(x - r * std::cos(phi)), std::abs(y - r * std::sin(phi))});
      EXPECT_LE(double(x) * x + double(y) * y, 1.0 + 4e-7) << u1 << " " << u2;
    }
  EXPECT_LE(worst, 3e-7);
  float x, y;
  concentric_disk(0.5f, 0.5f, x, y);
  EXPECT_EQ(x, 0.0f);
  EXPECT_EQ(y, 0.0f);
  concentric_disk(1.0f, 0.5f, x, y); // the +x axis: (1, 0)
  EXPECT_EQ(x, 1.0f);
  EXPECT_EQ(y, 0.0f);
}

} // namespace
} // namespace lobe
