// Chi-square goodness of fit of a lobe's sample() against its pdf() (the test of Mitsuba 3's
// and pbrt-v4's BSDF suites): sample directions are binned on a (phi, cos theta) grid, pdf()
// is integrated over every cell adaptively, sparse cells are pooled and the
// statistic's p-value is compared with a Sidak-corrected significance. pdf() is integrated per
// cell by recursive adaptive cubature (3x3 Gauss-Legendre, quadrants split while they disagree),
// and again around the cell's samples when the estimate cannot explain them (chi2.cpp).
#pragma once

#include "lobe_view.h"

#include <cstdint>
#include <string>
#include <vector>

namespace lobe::verify {

struct Chi2Options {
  int phi_res = 50;            // cells in phi over [0, 2 pi)
  int cos_res = 100;           // cells in cos theta per hemisphere the lobe reaches
  uint64_t samples = 1000000;  // sample() calls
  double cell_tolerance = 0.1; // pdf() cell integrals accurate to this many expected samples
  double min_expected = 5.0;   // cells expecting fewer samples are pooled into one
  double significance = 0.01;
  int n_tests = 1; // configurations in the suite (Sidak correction)
  uint64_t seed = 1;
  Transport mode = Transport::Radiance;
};

struct Chi2Result {
  bool passed = false;
  double statistic = 0;
  int dof = 0;
  double p_value = 0;
  double threshold = 0;    // per-test significance after the Sidak correction
  uint64_t valid = 0;      // samples that produced a direction
  uint64_t specular = 0;   // delta-lobe samples (not binned: pdf() excludes them)
  uint64_t outside = 0;    // non-delta samples in a hemisphere the lobe's flags exclude
  double pdf_integral = 0; // integral of pdf() over the grid (<= 1)
  std::string message;     // why it failed, or a summary
  // The histogram and the integrated expectation, cos-major (cos_cells x phi_res), for plots.
  int cos_cells = 0;
  double cos_min = 0, cos_max = 0;
  std::vector<double> observed, expected;
};

Chi2Result chi2_test(const LobeView& lobe, const Vec3& wo, const Chi2Options& opt);

// Integral of pdf() over the cell [phi0, phi1] x [c0, c1] by the midpoint rule on an n x n grid.
double integrate_pdf_cell(const LobeView& lobe, const Vec3& wo, double phi0, double phi1, double c0,
                          double c1, int n);

} // namespace lobe::verify
