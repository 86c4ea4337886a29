// Consistency of a lobe's sample() with its eval() and pdf(): for every sample,
//   weight == eval(wo, wi).value / pdf(wo, wi)   (relative 1e-4, float arithmetic),
//   sample.pdf == pdf(wo, wi) == eval(wo, wi).pdf, pdf > 0 whenever a sample is returned,
//   everything finite and >= 0. Delta samples are checked for finiteness and sign only.
#pragma once

#include "lobe_view.h"

#include <cstdint>
#include <string>

namespace lobe::verify {

struct ConsistencyResult {
  uint64_t samples = 0, valid = 0, specular = 0;
  uint64_t invalid_values = 0;  // NaN, Inf or negative weight/pdf, or pdf == 0
  uint64_t weight_mismatch = 0; // weight != eval / pdf
  uint64_t pdf_mismatch = 0;    // sample.pdf != pdf() or eval().pdf != pdf()
  double max_weight_rel_err = 0, max_pdf_rel_err = 0;
  std::string first_failure;
  bool ok() const { return invalid_values == 0 && weight_mismatch == 0 && pdf_mismatch == 0; }
};

ConsistencyResult check_consistency(const LobeView& lobe, const Vec3& wo, uint64_t samples,
                                    uint64_t seed, Transport mode = Transport::Radiance,
                                    double rel_tol = 1e-4);

// |a - b| relative to the larger magnitude (0 when both are 0).
double rel_diff(double a, double b);

} // namespace lobe::verify
