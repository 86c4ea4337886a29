// The Bsdf mixture (bsdf.h) under the same chi-square, consistency and furnace checks as single
// closures: mixtures of the first configuration of every testable closure, with grey and
// coloured weights, so lobe selection, the mixture pdf and the summed eval are all exercised.
#include "albedo.h"
#include "chi2.h"
#include "consistency.h"
#include "rng.h"
#include "suite.h"

#include <gtest/gtest.h>

#include <memory>

using namespace lobe;
using namespace lobe::verify;
using namespace lobe::verify::suite;

namespace {

struct MixtureCase {
  std::string name;
  std::vector<MixtureLobe::Term> terms;
};

// (a) every testable closure with equal grey weights summing to 0.9; (b) the first two with
// coloured weights; (c) a delta mirror (if implemented) over the first closure.
std::vector<MixtureCase> mixture_cases() {
  std::vector<MixtureLobe::Term> all;
  for (int id : testable_ids()) {
    std::vector<ClosureConfig> cs = configs_for(id, Level::Quick);
    if (!cs.empty()) all.push_back({Color3{1, 1, 1}, cs.front().params});
  }
  std::vector<MixtureCase> out;
  if (all.empty()) return out;
  MixtureCase every{"every closure", all};
  if (every.terms.size() > static_cast<size_t>(Bsdf::kMaxLobes))
    every.terms.erase(every.terms.begin() + Bsdf::kMaxLobes, every.terms.end());
  for (auto& t : every.terms) t.weight = Color3{1, 1, 1} * (0.9f / every.terms.size());
  out.push_back(every);
  if (all.size() >= 2)
    out.push_back(
        {"two coloured",
         {{Color3{0.6f, 0.3f, 0.1f}, all[0].params}, {Color3{0.3f, 0.6f, 0.8f}, all[1].params}}});
  int mirror = registry::id_of("reflection");
  if (mirror >= 0 && closures::has_implementation(mirror))
    out.push_back({"mirror over first",
                   {{Color3{0.3f, 0.3f, 0.3f}, closures::Params("reflection")},
                    {Color3{0.7f, 0.7f, 0.7f}, all[0].params}}});
  return out;
}

const Vec3 kIncident[] = {direction_at(0.5), direction_at(1.25)};

LOBE_TEST(MixtureProperties, ChiSquare) {
  auto cases = mixture_cases();
  ASSERT_FALSE(cases.empty());
  for (const MixtureCase& m : cases) {
    MixtureLobe lobe(m.terms);
    for (const Vec3& wo : kIncident) {
      Chi2Options o;
      o.samples = kSettings.chi2_samples;
      o.cell_tolerance = kSettings.chi2_cell_tolerance;
      o.n_tests = static_cast<int>(cases.size() * std::size(kIncident));
      Chi2Result r = chi2_test(lobe, wo, o);
      EXPECT_TRUE(r.passed) << m.name << " wo.z " << wo.z << ": " << r.message;
    }
  }
}

LOBE_TEST(MixtureProperties, Consistency) {
  for (const MixtureCase& m : mixture_cases()) {
    MixtureLobe lobe(m.terms);
    for (const Vec3& wo : kIncident) {
      ConsistencyResult r = check_consistency(lobe, wo, kSettings.consistency_samples, 5);
      EXPECT_TRUE(r.ok()) << m.name << ": " << r.first_failure;
      EXPECT_GT(r.valid, kSettings.consistency_samples / 2) << m.name;
    }
  }
}

LOBE_TEST(MixtureProperties, FurnaceAndSumOfParts) {
  // The mixture's albedo is the weighted sum of its lobes' albedos (quadrature of each part).
  for (const MixtureCase& m : mixture_cases()) {
    MixtureLobe lobe(m.terms);
    for (const Vec3& wo : kIncident) {
      AlbedoEstimate mc = albedo_mc(lobe, wo, kSettings.albedo_samples, 9, Transport::Importance);
      Color3d parts;
      bool delta = false;
      for (const auto& t : m.terms) {
        ClosureLobe part(t.params);
        delta |= (part.flags() & kLobeSpecular) != 0;
        QuadratureResult q = albedo_quadrature(part, wo, Transport::Importance);
        parts += Color3d{q.integral.r * t.weight.x, q.integral.g * t.weight.y,
                         q.integral.b * t.weight.z};
      }
      for (int ch = 0; ch < 3; ++ch) {
        EXPECT_LE(mc.mean[ch], 1.0 + 4 * mc.std_error[ch]) << m.name;
        if (!delta) {
          EXPECT_NEAR(mc.mean[ch], parts[ch], 4 * mc.std_error[ch] + 3e-3) << m.name;
        }
      }
    }
  }
}

} // namespace
