// Helpers for the closure unit tests: spherical directions and double-precision quadrature of
// a lobe's eval() over the sphere, the independent reference the closed forms are checked
// against.
#pragma once

#include "closures.h"

#include <cmath>

namespace lobe::closures::test {

inline Vec3 dir(double theta, double phi) {
  return {static_cast<float>(std::sin(theta) * std::cos(phi)),
          static_cast<float>(std::sin(theta) * std::sin(phi)), static_cast<float>(std::cos(theta))};
}
inline Vec3 dir_cos(double cos_theta, double phi = 0.0) { return dir(std::acos(cos_theta), phi); }

// Midpoint quadrature of g(wi) over the whole sphere in (theta, phi), in double precision.
template <class G> double integrate_sphere(G&& g, int n_theta = 256, int n_phi = 256) {
  const double pi = 3.14159265358979323846;
  double sum = 0.0;
  for (int i = 0; i < n_theta; ++i) {
    double th = (i + 0.5) * pi / n_theta;
    double w = std::sin(th) * (pi / n_theta) * (2.0 * pi / n_phi);
    for (int j = 0; j < n_phi; ++j) sum += w * g(dir(th, (j + 0.5) * 2.0 * pi / n_phi));
  }
  return sum;
}

// Directional albedo (red channel) of a lobe by quadrature of eval().value (which already
// includes |cos theta_i|).
inline double albedo_by_quadrature(const Params& p, const Vec3& wo, int n = 256) {
  return integrate_sphere(
      [&](const Vec3& wi) { return static_cast<double>(eval(p.id(), p.data(), wo, wi).value.x); },
      n, n);
}

} // namespace lobe::closures::test
