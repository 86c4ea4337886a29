// Reciprocity of f, in the generalised form that covers refraction (Veach 1997, ch. 5):
//     f(wo <- wi) / eta(wo)^2 == f(wi <- wo) / eta(wi)^2
// where f(wo <- wi) = eval(wo, wi).value / |cos theta_i| (light from wi leaving towards wo) and
// eta(w) is the refractive index of the side w points into (1 above, eta_below below). For
// reflection both etas are equal and this is plain symmetry. Transport modes are adjoint:
//     f_importance(wo <- wi) == f_radiance(wi <- wo),
// so radiance and importance differ by eta(wo)^2 / eta(wi)^2 for refraction.
#pragma once

#include "lobe_view.h"

#include <cstdint>
#include <string>

namespace lobe::verify {

struct ReciprocityResult {
  uint64_t pairs = 0, checked = 0;
  uint64_t violations = 0;      // radiance-mode generalised reciprocity
  uint64_t mode_violations = 0; // importance(wo, wi) vs radiance(wi, wo)
  double max_rel_err = 0;
  std::string first_failure;
  bool ok() const { return violations == 0 && mode_violations == 0; }
};

// Random direction pairs over the whole sphere (both sides), skipping |cos| < min_cos where the
// division by the cosine amplifies float rounding. Values are compared relative to the larger
// (rel_tol) with an absolute floor of abs_tol.
ReciprocityResult check_reciprocity(const LobeView& lobe, double eta_below, uint64_t pairs,
                                    uint64_t seed, double rel_tol = 1e-3, double abs_tol = 1e-6,
                                    double min_cos = 1e-2);

} // namespace lobe::verify
