// What the verification harness needs of a BSDF: one closure component or a whole mixture
// (Bsdf), seen through the same four operations the renderer uses.
//
// The harness works in the local frame: normal +z, tangent +x. Adapters (closure_lobe.h) set
// up parameter blocks with N = (0,0,1), U = (1,0,0) so that world space is the local frame.
#pragma once

#include "lobe/bsdf.h"
#include "lobe/vec.h"

#include <cstdint>
#include <optional>

namespace lobe::verify {

class LobeView {
public:
  virtual ~LobeView() = default;
  // f(wo, wi) * |cos theta_i| (and the pdf of sampling wi).
  virtual BsdfEval eval(const Vec3& wo, const Vec3& wi, Transport mode) const = 0;
  virtual float pdf(const Vec3& wo, const Vec3& wi) const = 0;
  virtual std::optional<BsdfSample> sample(const Vec3& wo, const Vec3& u, Transport mode) const = 0;
  virtual Color3 albedo(const Vec3& wo) const = 0;
  // LobeFlags (bsdf.h): which hemispheres the lobe reaches, delta or not.
  virtual uint32_t flags() const = 0;
};

// Double-precision RGB accumulator for estimators and quadrature.
struct Color3d {
  double r = 0, g = 0, b = 0;
  Color3d& operator+=(const Color3d& o) {
    r += o.r;
    g += o.g;
    b += o.b;
    return *this;
  }
  Color3d& add(const Color3& c, double s = 1.0) {
    r += s * c.x;
    g += s * c.y;
    b += s * c.z;
    return *this;
  }
  double operator[](int i) const { return i == 0 ? r : (i == 1 ? g : b); }
  double max() const { return r > g ? (r > b ? r : b) : (g > b ? g : b); }
  double sum() const { return r + g + b; }
};
inline Color3d operator*(Color3d c, double s) { return {c.r * s, c.g * s, c.b * s}; }
inline Color3d operator+(Color3d a, const Color3d& b) { return a += b; }
inline Color3d operator-(const Color3d& a, const Color3d& b) {
  return {a.r - b.r, a.g - b.g, a.b - b.b};
}

// Every component finite and >= 0 (the contract of every value a BSDF returns).
inline bool finite_nonneg(const Vec3& c) {
  return is_finite(c) && c.x >= 0 && c.y >= 0 && c.z >= 0;
}
inline bool finite_nonneg(float v) { return std::isfinite(v) && v >= 0; }

} // namespace lobe::verify
