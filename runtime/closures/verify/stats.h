// Statistics the harness needs: the chi-square distribution's tail (through the regularised
// incomplete gamma function) and the Sidak correction for testing many configurations at once.
#pragma once

namespace lobe::verify {

// Regularised lower incomplete gamma P(a, x) = gamma(a, x) / Gamma(a), a > 0, x >= 0.
double gamma_p(double a, double x);
// Upper tail Q(a, x) = 1 - P(a, x), computed directly (no cancellation for small tails).
double gamma_q(double a, double x);

// P(X >= stat) for X chi-square distributed with `dof` degrees of freedom: the p-value.
double chi2_survival(double stat, double dof);

// Per-test significance that keeps the family-wise rejection rate at `alpha` over `n_tests`
// independent tests: 1 - (1 - alpha)^(1/n).
double sidak_alpha(double alpha, int n_tests);

} // namespace lobe::verify
