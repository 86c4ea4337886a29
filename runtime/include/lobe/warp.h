// Square-to-disk and cosine-hemisphere warps shared by the closure library (cosine-weighted
// lobe sampling, also in the closures' bitcode) and the renderer (environment light, thin
// lens). Both run them once or twice per path vertex, where a libm sincos call was about 2% of
// a diffuse render.
#pragma once

#include "lobe/vec.h"

#include <cmath>

namespace lobe {

// sin and cos of |t| <= pi/4 by their Taylor polynomials to t^9 and t^10: the first omitted
// terms are below 2e-9 and 1.2e-10 there, under half an ulp of the results, so each is
// within about an ulp of the correctly rounded value (tested against double precision).
inline void sincos_quarter(float t, float& s, float& c) {
  float t2 = t * t;
  s = t *
      (1.0f + t2 * (-1.0f / 6 + t2 * (1.0f / 120 + t2 * (-1.0f / 5040 + t2 * (1.0f / 362880)))));
  c = 1.0f + t2 * (-0.5f + t2 * (1.0f / 24 + t2 * (-1.0f / 720 +
                                                   t2 * (1.0f / 40320 + t2 * (-1.0f / 3628800)))));
}

// Concentric map of the unit square to the unit disk (Shirley and Chiu): the square's
// concentric squares go to circles of radius r, its angle within each wedge of pi/2 linearly.
// The wedge angle is t in [-pi/4, pi/4] about the x or the y axis, so no range reduction.
inline void concentric_disk(float u1, float u2, float& x, float& y) {
  float a = 2.0f * u1 - 1.0f, b = 2.0f * u2 - 1.0f;
  if (a == 0.0f && b == 0.0f) {
    x = y = 0.0f;
    return;
  }
  float s, c;
  if (a * a > b * b) { // angle (pi/4) (b/a) about +x (or -x when a < 0)
    sincos_quarter(0.78539816339744831f * (b / a), s, c);
    x = a * c, y = a * s;
  } else { // angle pi/2 - (pi/4) (a/b) about +y (or -y when b < 0)
    sincos_quarter(0.78539816339744831f * (a / b), s, c);
    x = b * s, y = b * c;
  }
}

// Cosine-weighted direction on the hemisphere around +Z (Malley's method: the disk point lifted
// to the hemisphere); pdf z / pi.
inline Vec3 sample_cosine_hemisphere(float u1, float u2) {
  float x, y;
  concentric_disk(u1, u2, x, y);
  float z2 = 1.0f - x * x - y * y;
  return {x, y, std::sqrt(z2 > 0.0f ? z2 : 0.0f)};
}

} // namespace lobe
