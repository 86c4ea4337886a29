// Directional albedo of any lobe by a fixed quadrature of its eval() over the hemisphere
// (8 Gauss-Legendre nodes in cos theta x 16 in phi): used where no closed form exists and the
// estimate matters (lobe selection, layering). Deterministic, no allocation.
#pragma once

#include "common.h"

namespace lobe::closures {

template <class L> Vec3 quadrature_albedo(const L& lobe, const Vec3& wo, bool transmit = false) {
  constexpr float x[8] = {-0.9602898565f, -0.7966664774f, -0.5255324099f, -0.1834346425f,
                          0.1834346425f,  0.5255324099f,  0.7966664774f,  0.9602898565f};
  constexpr float w[8] = {0.1012285363f, 0.2223810345f, 0.3137066459f, 0.3626837834f,
                          0.3626837834f, 0.3137066459f, 0.2223810345f, 0.1012285363f};
  constexpr int kPhi = 16;
  Vec3 sum;
  for (int i = 0; i < 8; ++i) {
    float mu = 0.5f * (x[i] + 1.0f), s = safe_sqrt(1.0f - mu * mu);
    for (int j = 0; j < kPhi; ++j) {
      float phi = (j + 0.5f) * (2.0f * kPi / kPhi);
      Vec3 wi{s * std::cos(phi), s * std::sin(phi), transmit ? -mu : mu};
      sum += lobe.eval(wo, wi).value * (0.5f * w[i] * (2.0f * kPi / kPhi));
    }
  }
  return sum;
}

} // namespace lobe::closures
