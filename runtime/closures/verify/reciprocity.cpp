// Generalised reciprocity and radiance/importance adjointness over random direction pairs.
#include "reciprocity.h"

#include "rng.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace lobe::verify {
namespace {

// f(wo <- wi) = eval / |cos theta_i|, in double.
Color3d bsdf_value(const LobeView& lobe, const Vec3& wo, const Vec3& wi, Transport mode) {
  Vec3 v = lobe.eval(wo, wi, mode).value;
  double inv = 1.0 / std::fabs(static_cast<double>(wi.z));
  return Color3d{}.add(v, inv);
}

double mismatch(const Color3d& a, const Color3d& b, double abs_tol) {
  double err = 0;
  double scale = std::max(a.max(), b.max());
  for (int c = 0; c < 3; ++c) err = std::max(err, std::fabs(a[c] - b[c]));
  if (err <= abs_tol) return 0.0;
  return scale > 0 ? err / scale : 0.0;
}

std::string describe(const char* what, const Vec3& wo, const Vec3& wi, const Color3d& a,
                     const Color3d& b) {
  std::ostringstream os;
  os.precision(8);
  os << what << ": wo (" << wo.x << ", " << wo.y << ", " << wo.z << ") wi (" << wi.x << ", " << wi.y
     << ", " << wi.z << "): " << a.r << " " << a.g << " " << a.b << " vs " << b.r << " " << b.g
     << " " << b.b;
  return os.str();
}

} // namespace

ReciprocityResult check_reciprocity(const LobeView& lobe, double eta_below, uint64_t pairs,
                                    uint64_t seed, double rel_tol, double abs_tol, double min_cos) {
  ReciprocityResult r;
  Pcg32 rng(seed);
  auto eta2 = [&](const Vec3& w) { return w.z < 0 ? eta_below * eta_below : 1.0; };
  for (uint64_t k = 0; k < pairs; ++k, ++r.pairs) {
    Vec3 wo = uniform_sphere(rng.next_double(), rng.next_double());
    Vec3 wi = uniform_sphere(rng.next_double(), rng.next_double());
    if (std::fabs(wo.z) < min_cos || std::fabs(wi.z) < min_cos) continue;
    ++r.checked;
    Color3d fwd = bsdf_value(lobe, wo, wi, Transport::Radiance) * (1.0 / eta2(wo));
    Color3d rev = bsdf_value(lobe, wi, wo, Transport::Radiance) * (1.0 / eta2(wi));
    double e = mismatch(fwd, rev, abs_tol);
    r.max_rel_err = std::max(r.max_rel_err, e);
    if (e > rel_tol) {
      ++r.violations;
      if (r.first_failure.empty())
        r.first_failure = describe("f(wo<-wi)/eta_o^2 != f(wi<-wo)/eta_i^2", wo, wi, fwd, rev);
    }
    Color3d imp = bsdf_value(lobe, wo, wi, Transport::Importance);
    Color3d rad_rev = bsdf_value(lobe, wi, wo, Transport::Radiance);
    double em = mismatch(imp, rad_rev, abs_tol);
    if (em > rel_tol) {
      ++r.mode_violations;
      if (r.first_failure.empty())
        r.first_failure = describe("importance(wo,wi) != radiance(wi,wo)", wo, wi, imp, rad_rev);
    }
  }
  return r;
}

} // namespace lobe::verify
