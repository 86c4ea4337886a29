// Incomplete gamma by its power series (x < a + 1) and by Lentz's continued fraction
// (otherwise), the standard split that keeps both expansions fast and accurate.
#include "stats.h"

#include <cmath>
#include <limits>

namespace lobe::verify {
namespace {

constexpr int kMaxIter = 1000000;
constexpr double kEps = 1e-15;

// P(a, x) by the series  e^-x x^a / Gamma(a+1) * sum_n x^n / ((a+1)...(a+n)).
double gamma_p_series(double a, double x) {
  double term = 1.0 / a, sum = term;
  for (int n = 1; n < kMaxIter; ++n) {
    term *= x / (a + n);
    sum += term;
    if (std::fabs(term) < std::fabs(sum) * kEps) break;
  }
  return sum * std::exp(-x + a * std::log(x) - std::lgamma(a));
}

// Q(a, x) by the continued fraction for Gamma(a, x) (modified Lentz).
double gamma_q_fraction(double a, double x) {
  const double tiny = std::numeric_limits<double>::min() / kEps;
  double b = x + 1.0 - a, c = 1.0 / tiny, d = 1.0 / b, h = d;
  for (int i = 1; i < kMaxIter; ++i) {
    double an = -i * (i - a);
    b += 2.0;
    d = an * d + b;
    if (std::fabs(d) < tiny) d = tiny;
    c = b + an / c;
    if (std::fabs(c) < tiny) c = tiny;
    d = 1.0 / d;
    double delta = d * c;
    h *= delta;
    if (std::fabs(delta - 1.0) < kEps) break;
  }
  return std::exp(-x + a * std::log(x) - std::lgamma(a)) * h;
}

} // namespace

double gamma_p(double a, double x) {
  if (!(a > 0) || !(x >= 0)) return std::numeric_limits<double>::quiet_NaN();
  if (x == 0) return 0.0;
  if (x < a + 1.0) return gamma_p_series(a, x);
  return 1.0 - gamma_q_fraction(a, x);
}

double gamma_q(double a, double x) {
  if (!(a > 0) || !(x >= 0)) return std::numeric_limits<double>::quiet_NaN();
  if (x == 0) return 1.0;
  if (x < a + 1.0) return 1.0 - gamma_p_series(a, x);
  return gamma_q_fraction(a, x);
}

double chi2_survival(double stat, double dof) {
  if (dof <= 0) return stat > 0 ? 0.0 : 1.0;
  return gamma_q(0.5 * dof, 0.5 * std::fmax(stat, 0.0));
}

double sidak_alpha(double alpha, int n_tests) {
  if (n_tests <= 1) return alpha;
  return 1.0 - std::pow(1.0 - alpha, 1.0 / n_tests);
}

} // namespace lobe::verify
