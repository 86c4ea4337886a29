// Importance sampling of a measured (MERL) BRDF table, built once when the table loads.
//
// For each of kBinsO bins of the viewing elevation (uniform in cos theta_o), a piecewise-
// constant 2-D distribution over outgoing cells (cos theta_i, phi_i - phi_o): kCos x kPhi
// cells uniform in cos theta_i and in phi, so every cell spans the same solid angle
// 2 pi / (kCos kPhi). A cell's weight is luminance(f) cos theta_i averaged over 2 x 2 points
// of the cell and 2 viewing directions of the bin. Sampling picks a row from the marginal
// and a cell from the row's conditional (re-using the remainders for the position inside the
// cell); pdf(wo, wi) is the density of wi's cell in wo's bin. The measured lobe mixes it with
// cosine sampling (kCosineShare) so that pdf > 0 wherever f > 0 (cells with zero weight,
// no-data regions). Isotropic BRDFs only depend on phi_i - phi_o, hence the relative angle.
#pragma once

#include "common.h"

#include <vector>

namespace lobe::closures {

struct MeasuredTable;

struct MeasuredSampler {
  static constexpr int kBinsO = 32, kCos = 32, kPhi = 64;
  static constexpr float kCosineShare = 0.1f;
  std::vector<float> row_cdf;  // [bin][kCos + 1]
  std::vector<float> cell_cdf; // [bin][kCos][kPhi + 1], per row
  std::vector<float> cell_p;   // [bin][kCos][kPhi], probability of the cell

  void build(const MeasuredTable& table);
  bool empty() const { return cell_p.empty(); }
  // Table part only: a direction above the surface from u in [0,1)^2; false if none.
  bool sample(const Vec3& wo, float u1, float u2, Vec3& wi) const;
  // Solid-angle density of sample() at wi (0 below the surface).
  float pdf(const Vec3& wo, const Vec3& wi) const;
};

} // namespace lobe::closures
