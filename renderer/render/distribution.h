// Piecewise-constant 1-D and 2-D distributions for importance sampling tabulated functions
// (the environment map, emissive triangles by area, lights by power).
#pragma once

#include "lobe/memory.h"

#include <cstddef>
#include <initializer_list>
#include <span>

namespace lobe::render {

class Distribution1D {
public:
  Distribution1D() = default;
  // `f` >= 0; an all-zero function becomes uniform.
  explicit Distribution1D(std::span<const float> f);
  explicit Distribution1D(std::initializer_list<float> f)
      : Distribution1D(std::span<const float>(f.begin(), f.size())) {}
  int size() const { return static_cast<int>(func_.size()); }
  float integral() const { return integral_; } // of f over [0,1], i.e. mean(f)
  // Continuous sample in [0,1): returns x, sets pdf (density over [0,1]) and the cell index.
  float sample_continuous(float u, float& pdf, int& index) const;
  // Discrete sample: index with probability f[i] / sum(f).
  int sample_discrete(float u, float& prob) const;
  // Same, and `u_rest` receives u rescaled to [0,1) within the chosen cell (re-usable).
  int sample_discrete(float u, float& prob, float& u_rest) const;
  float discrete_prob(int i) const;
  float pdf(int i) const;                                 // density over [0,1] in cell i
  float cdf(int i) const { return cdf_[std::size_t(i)]; } // i in [0, size()]

private:
  int find(float u) const;

  LargeVector<float> func_, cdf_;
  // guide_[k]: the cell of u = k / size() (a start for the search of any u in [k, k+1) /
  // size(): a few steps forward instead of a binary search; same cell as the binary search).
  LargeVector<int> guide_;
  float integral_ = 0;
};

// f(u, v) on a w x h grid, u along rows; sampled as marginal(v) * conditional(u | v).
//
// Laid out for a table far larger than the caches (a 1448 x 724 environment): the rows' CDFs
// are one array, and each row has a coarse guide of kRowGuide cells (all rows' guides together
// fit in L2), so that the search in a row reads one or two cache lines of its CDF; the caller
// that keeps the density beside its own data per cell (the environment's texels) takes the
// cell instead of the density and reads both with one miss. The cells and positions sampled
// are those of the binary search over each row's CDF, bit for bit.
class Distribution2D {
public:
  static constexpr int kRowGuide = 64;

  Distribution2D() = default;
  // `f` >= 0; a row of zeros has density 0 (never sampled); an all-zero f becomes uniform.
  Distribution2D(std::span<const float> f, int w, int h);
  // Sample (u, v) in [0,1)^2 with density pdf over the unit square.
  void sample(float u1, float u2, float& u, float& v, float& pdf) const;
  // The same (u, v), and the cell (x, y) it lies in, whose pdf_cell() is the density.
  void sample_cell(float u1, float u2, float& u, float& v, int& x, int& y) const;
  float pdf(float u, float v) const;
  float pdf_cell(int x, int y) const { // pdf() in that cell
    return cells_[pdf_at() + std::size_t(y) * w_ + x];
  }
  bool empty() const { return h_ == 0; }

private:
  int find_in_row(int y, float u) const; // last cell i of row y with cdf[i] <= u (clamped)
  const float* cdf_row(int y) const { return &cells_[std::size_t(y) * (w_ + 1)]; }
  std::size_t pdf_at() const { return std::size_t(w_ + 1) * h_; }

  Distribution1D marginal_;
  // One block (a large table's on huge pages, lobe/memory.h): h rows of w + 1, each row's
  // CDF from 0 to 1; then w x h densities, marginal pdf x row pdf, one load for pdf().
  LargeVector<float> cells_;
  LargeVector<int> guide_; // h rows of kRowGuide + 1: the cell of u = k / kRowGuide
  int w_ = 0, h_ = 0;
};

} // namespace lobe::render
