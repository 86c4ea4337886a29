// Directional albedo  a(wo) = integral over the sphere of f(wo, wi) |cos theta_i| dwi,
// two independent ways:
//  - Monte Carlo through sample(): the mean sample weight (failed samples count 0), with its
//    standard error, so a test can use a 4-sigma tolerance;
//  - deterministic quadrature of eval() in double precision: globally adaptive cubature that
//    splits the cell with the largest error estimate first, over the half-vector domain around
//    wo (m = (phi, c = wo.m) with pole wo, wi = 2 c m - wo, dwi = 4 c dm; exact over the whole
//    sphere, and a glossy reflection lobe is as wide in m as its roughness, while in wi it is a
//    sliver ~2 wo.z alpha wide at grazing incidence). Delta lobes are invisible to eval() and
//    therefore to the quadrature.
#pragma once

#include "lobe_view.h"

#include <cstdint>

namespace lobe::verify {

struct AlbedoEstimate {
  Color3d mean;
  Color3d std_error; // standard error of the mean, per channel
  uint64_t samples = 0;
  uint64_t nonfinite = 0; // weights that were NaN/Inf/negative (excluded from the mean)
};

AlbedoEstimate albedo_mc(const LobeView& lobe, const Vec3& wo, uint64_t samples, uint64_t seed,
                         Transport mode = Transport::Radiance);

struct QuadratureOptions {
  double abs_tol = 2e-5;            // stop when the summed error estimate is below this ...
  double rel_tol = 2e-5;            // ... or below rel_tol * |integral|
  uint64_t max_evals = 3000000;     // budget of eval() calls
  int base_phi = 16, base_cos = 32; // initial grid (per hemisphere in cos)
};

struct QuadratureResult {
  Color3d integral;
  double error_estimate = 0; // summed |coarse - fine| over the final cells (max channel)
  uint64_t evals = 0;
};

QuadratureResult albedo_quadrature(const LobeView& lobe, const Vec3& wo,
                                   Transport mode = Transport::Radiance,
                                   const QuadratureOptions& opt = {});

} // namespace lobe::verify
