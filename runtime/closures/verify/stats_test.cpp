// Tests of the incomplete gamma / chi-square tail against closed forms for small degrees of
// freedom and the Wilson-Hilferty approximation for large ones.
#include "stats.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace lobe::verify;

TEST(Stats, GammaPClosedForms) {
  for (double x : {0.01, 0.5, 1.0, 3.0, 10.0, 40.0}) {
    EXPECT_NEAR(gamma_p(1.0, x), 1.0 - std::exp(-x), 1e-12) << x;
    EXPECT_NEAR(gamma_p(0.5, x), std::erf(std::sqrt(x)), 1e-12) << x;
    EXPECT_NEAR(gamma_p(2.0, x) + gamma_q(2.0, x), 1.0, 1e-12) << x;
  }
  EXPECT_EQ(gamma_p(3.0, 0.0), 0.0);
  EXPECT_TRUE(std::isnan(gamma_p(-1.0, 1.0)));
}

TEST(Stats, Chi2SurvivalSmallDof) {
  for (double x : {0.1, 1.0, 3.0, 7.5, 20.0}) {
    EXPECT_NEAR(chi2_survival(x, 2), std::exp(-x / 2), 1e-12) << x;
    EXPECT_NEAR(chi2_survival(x, 1), std::erfc(std::sqrt(x / 2)), 1e-12) << x;
    EXPECT_NEAR(chi2_survival(x, 4), std::exp(-x / 2) * (1 + x / 2), 1e-12) << x;
  }
  // Tabulated critical values: P(chi2_10 >= 23.209) = 0.01, P(chi2_1 >= 6.635) = 0.01.
  EXPECT_NEAR(chi2_survival(23.209, 10), 0.01, 1e-4);
  EXPECT_NEAR(chi2_survival(6.635, 1), 0.01, 1e-4);
}

TEST(Stats, Chi2SurvivalLargeDofMatchesWilsonHilferty) {
  for (double k : {500.0, 5000.0}) {
    for (double x : {0.9 * k, k, 1.1 * k}) {
      double z = (std::cbrt(x / k) - (1 - 2 / (9 * k))) / std::sqrt(2 / (9 * k));
      double approx = 0.5 * std::erfc(z / std::sqrt(2.0));
      EXPECT_NEAR(chi2_survival(x, k), approx, 2e-3) << k << " " << x;
    }
  }
}

TEST(Stats, Sidak) {
  EXPECT_DOUBLE_EQ(sidak_alpha(0.01, 1), 0.01);
  double a = sidak_alpha(0.01, 10);
  EXPECT_NEAR(1 - std::pow(1 - a, 10), 0.01, 1e-12);
  EXPECT_LT(a, 0.01 / 10 * 1.01);
}
