// Piecewise-constant distributions (see distribution.h): CDF tables and inversion by binary
// search, in double precision while building so long tables stay accurate.
#include "distribution.h"

#include <tbb/parallel_for.h>

#include <algorithm>

namespace lobe::render {

Distribution1D::Distribution1D(std::span<const float> f)
    : func_(f.begin(), f.end()), cdf_(f.size() + 1) {
  const size_t n = f.size();
  double sum = 0;
  cdf_[0] = 0;
  for (size_t i = 0; i < n; ++i) {
    func_[i] = f[i] > 0 ? f[i] : 0.0f; // negative and NaN weights count as zero
    sum += func_[i];
    cdf_[i + 1] = static_cast<float>(sum);
  }
  integral_ = n ? static_cast<float>(sum / double(n)) : 0.0f;
  if (!(sum > 0)) {
    for (size_t i = 0; i < n; ++i) func_[i] = 1, cdf_[i + 1] = float(i + 1) / float(n);
    integral_ = n ? 1.0f : 0.0f;
    guide_.clear(); // binary search (a uniform table is rare and small)
    return;
  }
  for (size_t i = 1; i <= n; ++i) cdf_[i] = static_cast<float>(cdf_[i] / sum);
  cdf_[n] = 1;
  guide_.resize(n);
  for (size_t k = 0, i = 0; k < n; ++k) { // guide_[k] = last cell i with cdf_[i] <= k / n
    float u = float(k) / float(n);
    while (i + 1 < n && cdf_[i + 1] <= u) ++i;
    guide_[k] = int(i);
  }
}

static int find_interval(const LargeVector<float>& cdf, float u) {
  // Last index i with cdf[i] <= u, clamped to a valid cell; skips zero-width cells.
  auto it = std::upper_bound(cdf.begin(), cdf.end(), u);
  int i = static_cast<int>(it - cdf.begin()) - 1;
  return std::clamp(i, 0, static_cast<int>(cdf.size()) - 2);
}

// The cell find_interval gives (last i with cdf_[i] <= u, clamped), searched only between the
// guides around u: cdf_[guide_[k]] <= k/n <= u < (k+1)/n < cdf_[guide_[k+1] + 1].
int Distribution1D::find(float u) const {
  const int n = size();
  if (n == 1) return 0; // one light, one row: nothing to search
  if (guide_.empty() || !(u >= 0) || !(u < 1)) return find_interval(cdf_, u);
  int k = std::min(int(u * float(n)), n - 1);
  int lo = guide_[size_t(k)], hi = k + 1 < n ? guide_[size_t(k) + 1] : n - 1;
  auto it = std::upper_bound(cdf_.begin() + lo + 1, cdf_.begin() + hi + 1, u);
  return int(it - cdf_.begin()) - 1;
}

float Distribution1D::sample_continuous(float u, float& pdf, int& index) const {
  index = find(u);
  float width = cdf_[index + 1] - cdf_[index];
  float du = width > 0 ? (u - cdf_[index]) / width : 0.5f;
  pdf = integral_ > 0 ? func_[index] / integral_ : 0;
  float x = (float(index) + std::clamp(du, 0.0f, 1.0f)) / float(size());
  return std::min(x, 0x1.fffffep-1f);
}

int Distribution1D::sample_discrete(float u, float& prob) const {
  int i = find(u);
  prob = discrete_prob(i);
  return i;
}

int Distribution1D::sample_discrete(float u, float& prob, float& u_rest) const {
  int i = sample_discrete(u, prob);
  u_rest = prob > 0 ? std::clamp((u - cdf_[i]) / prob, 0.0f, 0x1.fffffep-1f) : 0.5f;
  return i;
}

float Distribution1D::discrete_prob(int i) const { return cdf_[i + 1] - cdf_[i]; }

float Distribution1D::pdf(int i) const { return integral_ > 0 ? func_[i] / integral_ : 0; }

Distribution2D::Distribution2D(std::span<const float> f, int w, int h) : w_(w), h_(h) {
  std::vector<float> marg(static_cast<size_t>(h));
  cells_.resize(pdf_at() + size_t(w) * h);
  guide_.resize(size_t(kRowGuide + 1) * h);
  // Rows in parallel (each writes its own slices; a 1448x724 background table's rows took
  // 40 ms on one core).
  tbb::parallel_for(0, h, [&](int y) {
    Distribution1D row(f.subspan(size_t(y) * w, size_t(w)));
    // A row of zeros is uniform within itself but never chosen (Distribution1D's integral of
    // an all-zero function is that of the uniform one it becomes).
    bool zero = true;
    for (int x = 0; x < w && zero; ++x) zero = !(f[size_t(y) * w + x] > 0);
    marg[size_t(y)] = zero ? 0.0f : row.integral();
    float* cdf = &cells_[size_t(y) * (w + 1)];
    for (int i = 0; i <= w; ++i) cdf[i] = row.cdf(i);
    float* pdf = &cells_[pdf_at() + size_t(y) * w];
    for (int x = 0; x < w; ++x) pdf[x] = row.pdf(x); // the marginal's factor comes below
    int* guide = &guide_[size_t(y) * (kRowGuide + 1)];
    for (int k = 0, i = 0; k <= kRowGuide; ++k) { // last cell i with cdf[i] <= k / kRowGuide
      float u = float(k) / float(kRowGuide);
      while (i + 1 < w && cdf[i + 1] <= u) ++i;
      guide[k] = i;
    }
  });
  marginal_ = Distribution1D(marg);
  tbb::parallel_for(0, h, [&](int y) {
    float* pdf = &cells_[pdf_at() + size_t(y) * w];
    for (int x = 0; x < w; ++x) pdf[x] = marginal_.pdf(y) * pdf[x];
  });
}

// The cell find_interval gives over the row's CDF, searched between the guides around u:
// cdf[guide[k]] <= k/G <= u < (k+1)/G, and the cell of any such u is at most guide[k+1].
int Distribution2D::find_in_row(int y, float u) const {
  const float* cdf = cdf_row(y);
  if (!(u >= 0) || !(u < 1)) {
    int i = int(std::upper_bound(cdf, cdf + w_ + 1, u) - cdf) - 1;
    return std::clamp(i, 0, w_ - 1);
  }
  const int* guide = &guide_[size_t(y) * (kRowGuide + 1)];
  int k = std::min(int(u * float(kRowGuide)), kRowGuide - 1);
  int lo = guide[k], hi = guide[k + 1];
  return int(std::upper_bound(cdf + lo + 1, cdf + hi + 1, u) - cdf) - 1;
}

void Distribution2D::sample_cell(float u1, float u2, float& u, float& v, int& x, int& y) const {
  float pv;
  v = marginal_.sample_continuous(u2, pv, y);
  x = find_in_row(y, u1);
  const float* cdf = cdf_row(y);
  float width = cdf[x + 1] - cdf[x];
  float du = width > 0 ? (u1 - cdf[x]) / width : 0.5f;
  u = std::min((float(x) + std::clamp(du, 0.0f, 1.0f)) / float(w_), 0x1.fffffep-1f);
}

void Distribution2D::sample(float u1, float u2, float& u, float& v, float& pdf) const {
  int x, y;
  sample_cell(u1, u2, u, v, x, y);
  pdf = pdf_cell(x, y);
}

float Distribution2D::pdf(float u, float v) const {
  int iu = std::clamp(int(u * w_), 0, w_ - 1), iv = std::clamp(int(v * h_), 0, h_ - 1);
  return pdf_cell(iu, iv);
}

} // namespace lobe::render
