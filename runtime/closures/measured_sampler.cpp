// Tabulated importance sampling of measured BRDFs (see measured_sampler.h).
#include "measured_sampler.h"

#include "measured.h"

#include <algorithm>

namespace lobe::closures {
namespace {

constexpr float kTwoPi = 2.0f * kPi;

int bin_of(float wo_z) {
  return std::clamp(static_cast<int>(wo_z * MeasuredSampler::kBinsO), 0,
                    MeasuredSampler::kBinsO - 1);
}

Vec3 direction(float c, float phi) {
  float s = safe_sqrt(1.0f - c * c);
  return {s * std::cos(phi), s * std::sin(phi), c};
}

// Index of the interval of a CDF (n + 1 values from 0 to 1) that contains u, and the
// remainder of u inside it, rescaled to [0, 1).
int invert_cdf(const float* cdf, int n, float u, float& rest) {
  int i = static_cast<int>(std::upper_bound(cdf, cdf + n + 1, u) - cdf) - 1;
  i = std::clamp(i, 0, n - 1);
  while (i < n - 1 && !(cdf[i + 1] > cdf[i])) ++i; // skip empty intervals
  float w = cdf[i + 1] - cdf[i];
  rest = w > 0.0f ? clampf((u - cdf[i]) / w, 0.0f, kOneMinusEpsilon) : 0.5f;
  return i;
}

// Weight of one cell in one bin: luminance(f) cos averaged over 2 x 2 x 2 points.
double cell_weight(const MeasuredTable& t, int bin, int r, int c) {
  double sum = 0.0;
  for (int o = 0; o < 2; ++o) {
    float co = (bin + 0.25f + 0.5f * o) / MeasuredSampler::kBinsO;
    Vec3 wo = direction(co, 0.0f);
    for (int a = 0; a < 2; ++a)
      for (int b = 0; b < 2; ++b) {
        float ci = (r + 0.25f + 0.5f * a) / MeasuredSampler::kCos;
        float phi = kTwoPi * (c + 0.25f + 0.5f * b) / MeasuredSampler::kPhi;
        sum += luminance(t.lookup(wo, direction(ci, phi))) * ci;
      }
  }
  return sum / 8.0;
}

} // namespace

void MeasuredSampler::build(const MeasuredTable& t) {
  row_cdf.assign(static_cast<size_t>(kBinsO) * (kCos + 1), 0.0f);
  cell_cdf.assign(static_cast<size_t>(kBinsO) * kCos * (kPhi + 1), 0.0f);
  cell_p.assign(static_cast<size_t>(kBinsO) * kCos * kPhi, 0.0f);
  std::vector<double> w(static_cast<size_t>(kCos) * kPhi);
  for (int bin = 0; bin < kBinsO; ++bin) {
    double total = 0.0;
    for (int r = 0; r < kCos; ++r)
      for (int c = 0; c < kPhi; ++c) total += w[r * kPhi + c] = cell_weight(t, bin, r, c);
    if (!(total > 0.0)) { // no data for this bin: uniform cells
      std::fill(w.begin(), w.end(), 1.0);
      total = static_cast<double>(w.size());
    }
    float* rows = &row_cdf[static_cast<size_t>(bin) * (kCos + 1)];
    double acc_rows = 0.0;
    for (int r = 0; r < kCos; ++r) {
      double row = 0.0;
      for (int c = 0; c < kPhi; ++c) row += w[r * kPhi + c];
      float* cols = &cell_cdf[(static_cast<size_t>(bin) * kCos + r) * (kPhi + 1)];
      double acc = 0.0;
      for (int c = 0; c < kPhi; ++c) {
        acc += w[r * kPhi + c];
        cols[c + 1] = row > 0.0 ? static_cast<float>(acc / row) : (c + 1.0f) / kPhi;
        cell_p[(static_cast<size_t>(bin) * kCos + r) * kPhi + c] =
            static_cast<float>(w[r * kPhi + c] / total);
      }
      cols[kPhi] = 1.0f;
      acc_rows += row;
      rows[r + 1] = static_cast<float>(acc_rows / total);
    }
    rows[kCos] = 1.0f;
  }
}

bool MeasuredSampler::sample(const Vec3& wo, float u1, float u2, Vec3& wi) const {
  if (empty() || !(wo.z > 0.0f)) return false;
  int bin = bin_of(wo.z);
  float r1, r2;
  int r = invert_cdf(&row_cdf[static_cast<size_t>(bin) * (kCos + 1)], kCos, u1, r1);
  int c = invert_cdf(&cell_cdf[(static_cast<size_t>(bin) * kCos + r) * (kPhi + 1)], kPhi, u2, r2);
  float ci = (r + r1) / kCos;
  float phi = std::atan2(wo.y, wo.x) + kTwoPi * (c + r2) / kPhi;
  wi = direction(ci, phi);
  return wi.z > 0.0f;
}

float MeasuredSampler::pdf(const Vec3& wo, const Vec3& wi) const {
  if (empty() || !(wo.z > 0.0f) || !(wi.z > 0.0f)) return 0.0f;
  int bin = bin_of(wo.z);
  int r = std::clamp(static_cast<int>(wi.z * kCos), 0, kCos - 1);
  float d = std::atan2(wi.y, wi.x) - std::atan2(wo.y, wo.x);
  d -= kTwoPi * std::floor(d / kTwoPi);
  int c = std::clamp(static_cast<int>(d / kTwoPi * kPhi), 0, kPhi - 1);
  float p = cell_p[(static_cast<size_t>(bin) * kCos + r) * kPhi + c];
  return p * (kCos * kPhi / kTwoPi);
}

} // namespace lobe::closures
