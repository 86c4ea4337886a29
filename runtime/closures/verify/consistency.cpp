// Sample/eval/pdf consistency checks, one sample at a time; the first failure is described.
#include "consistency.h"

#include "rng.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace lobe::verify {
namespace {

std::string describe(const char* what, const Vec3& wo, const Vec3& u, const BsdfSample& s,
                     const BsdfEval& e, float p) {
  std::ostringstream os;
  os.precision(9);
  os << what << ": wo (" << wo.x << ", " << wo.y << ", " << wo.z << ") u (" << u.x << ", " << u.y
     << ", " << u.z << ") -> wi (" << s.wi.x << ", " << s.wi.y << ", " << s.wi.z << ") weight ("
     << s.weight.x << ", " << s.weight.y << ", " << s.weight.z << ") pdf " << s.pdf << "; eval ("
     << e.value.x << ", " << e.value.y << ", " << e.value.z << ") eval.pdf " << e.pdf << " pdf() "
     << p;
  return os.str();
}

// Weight against eval/pdf, per channel, relative to the largest channel (so a channel that is
// ~0 next to a bright one does not demand 1e-4 relative accuracy on its own). A value in
// float's subnormal range carries only an absolute precision of 2^-149 (a value of 7.6e-44
// has 6 significant bits), so eval/pdf is known to within a few 2^-149 / pdf, and that much
// is allowed besides the relative tolerance (seen at 85 deg for Beckmann refraction from
// inside, where f cos is 1e-44 and the sample's own weight is exact).
double weight_error(const Vec3& weight, const Vec3& value, float pdf) {
  double scale = 0, err = 0;
  double slack = 4.0 * std::numeric_limits<float>::denorm_min() / pdf;
  for (int c = 0; c < 3; ++c) {
    double expect = static_cast<double>(value[c]) / pdf;
    scale = std::max({scale, std::fabs(expect), std::fabs(static_cast<double>(weight[c]))});
    err = std::max(err, std::fabs(expect - weight[c]) - slack);
  }
  return scale > 0 ? err / scale : 0.0;
}

} // namespace

double rel_diff(double a, double b) {
  double m = std::max(std::fabs(a), std::fabs(b));
  return m > 0 ? std::fabs(a - b) / m : 0.0;
}

ConsistencyResult check_consistency(const LobeView& lobe, const Vec3& wo, uint64_t samples,
                                    uint64_t seed, Transport mode, double rel_tol) {
  ConsistencyResult r;
  Pcg32 rng(seed);
  auto fail = [&](uint64_t& counter, const char* what, const Vec3& u, const BsdfSample& s,
                  const BsdfEval& e, float p) {
    ++counter;
    if (r.first_failure.empty()) r.first_failure = describe(what, wo, u, s, e, p);
  };
  for (uint64_t k = 0; k < samples; ++k, ++r.samples) {
    Vec3 u = rng.next_vec3();
    auto s = lobe.sample(wo, u, mode);
    if (!s) continue;
    ++r.valid;
    if (!finite_nonneg(s->weight) || !std::isfinite(s->pdf) || !(s->pdf > 0) || !is_finite(s->wi)) {
      fail(r.invalid_values, "invalid sample", u, *s, {}, 0);
      continue;
    }
    if (s->flags & kLobeSpecular) {
      ++r.specular;
      continue;
    }
    BsdfEval e = lobe.eval(wo, s->wi, mode);
    float p = lobe.pdf(wo, s->wi);
    if (!finite_nonneg(e.value) || !finite_nonneg(p) || !(p > 0)) {
      fail(r.invalid_values, "pdf() == 0 or invalid eval at a sampled direction", u, *s, e, p);
      continue;
    }
    double pe = std::max(rel_diff(s->pdf, p), rel_diff(e.pdf, p));
    r.max_pdf_rel_err = std::max(r.max_pdf_rel_err, pe);
    if (pe > rel_tol) fail(r.pdf_mismatch, "pdf mismatch", u, *s, e, p);
    double we = weight_error(s->weight, e.value, p);
    r.max_weight_rel_err = std::max(r.max_weight_rel_err, we);
    if (we > rel_tol) fail(r.weight_mismatch, "weight != eval / pdf", u, *s, e, p);
  }
  return r;
}

} // namespace lobe::verify
