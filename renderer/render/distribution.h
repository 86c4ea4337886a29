// Piecewise-constant 1-D and 2-D distributions for importance sampling tabulated functions
// (the environment map, emissive triangles by area, lights by power).
#pragma once

#include <cstddef>
#include <vector>

namespace lobe::render {

class Distribution1D {
public:
  Distribution1D() = default;
  // `f` >= 0; an all-zero function becomes uniform.
  explicit Distribution1D(const std::vector<float>& f);
  int size() const { return static_cast<int>(func_.size()); }
  float integral() const { return integral_; } // of f over [0,1], i.e. mean(f)
  // Continuous sample in [0,1): returns x, sets pdf (density over [0,1]) and the cell index.
  float sample_continuous(float u, float& pdf, int& index) const;
  // Discrete sample: index with probability f[i] / sum(f).
  int sample_discrete(float u, float& prob) const;
  // Same, and `u_rest` receives u rescaled to [0,1) within the chosen cell (re-usable).
  int sample_discrete(float u, float& prob, float& u_rest) const;
  float discrete_prob(int i) const;
  float pdf(int i) const; // density over [0,1] in cell i

private:
  int find(float u) const;

  std::vector<float> func_, cdf_;
  // guide_[k]: the cell of u = k / size() (a start for the search of any u in [k, k+1) /
  // size(): a few steps forward instead of a binary search; same cell as the binary search).
  std::vector<int> guide_;
  float integral_ = 0;
};

// f(u, v) on a w x h grid, u along rows; sampled as marginal(v) * conditional(u | v).
class Distribution2D {
public:
  Distribution2D() = default;
  Distribution2D(const std::vector<float>& f, int w, int h);
  // Sample (u, v) in [0,1)^2 with density pdf over the unit square.
  void sample(float u1, float u2, float& u, float& v, float& pdf) const;
  float pdf(float u, float v) const;
  float pdf_cell(int x, int y) const { return pdf_[std::size_t(y) * w_ + x]; } // pdf() in that cell
  bool empty() const { return rows_.empty(); }

private:
  std::vector<Distribution1D> rows_;
  Distribution1D marginal_;
  std::vector<float> pdf_; // w x h: marginal pdf x row pdf, one load for pdf()
  int w_ = 0, h_ = 0;
};

} // namespace lobe::render
