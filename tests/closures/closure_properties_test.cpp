// Property suites over every registry entry that has an implementation, one CTest test per
// (check, closure): chi-square goodness of fit, sample/eval/pdf consistency, white furnace,
// reciprocity and the stress grid, each over the configurations of configs.h. A closure that
// gains an implementation is tested here without anyone writing a test.
#include "albedo.h"
#include "chi2.h"
#include "consistency.h"
#include "param_stress.h"
#include "reciprocity.h"
#include "stress.h"
#include "suite.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <map>

using namespace lobe;
using namespace lobe::verify;
using namespace lobe::verify::suite;

namespace {

// Chi-square tests in the whole suite at this level, for the Sidak correction.
int chi2_test_count() {
  int n = 0;
  for (int id : testable_ids())
    for (const ClosureConfig& c : configs_for(id, kSettings.level))
      n += static_cast<int>(c.incident.size());
  return n;
}

// Closures exempt from reciprocity, with the reason (reviewed: each is a published model that
// is not reciprocal by construction).
const std::map<std::string, std::string>& reciprocity_exemptions() {
  static const std::map<std::string, std::string> m = {};
  return m;
}

// Known failures found by these suites and reported to the closure library's owner, excused
// in the default suite only (the heavy suite asserts everything): (closure key, check,
// incident or "*") -> reason. Remove an entry when the closure is fixed.
std::string known_issue(const std::string& key, const std::string& check,
                        const std::string& incident) {
  (void)key, (void)check, (void)incident;
  return {}; // none open
}

// EXPECT_TRUE(ok) unless the failure is a listed known issue (then it is printed).
#define EXPECT_OR_KNOWN(ok, check, incident, msg)                                                  \
  do {                                                                                             \
    std::string reason_ = known_issue(key_name(GetParam()), check, incident);                      \
    if (!(ok) && !reason_.empty())                                                                 \
      std::printf("known issue (%s): %s\n", reason_.c_str(), std::string(msg).c_str());            \
    else                                                                                           \
      EXPECT_TRUE(ok) << msg;                                                                      \
  } while (0)

class ClosureProperties : public ::testing::TestWithParam<int> {
protected:
  std::vector<ClosureConfig> configs() const { return configs_for(GetParam(), kSettings.level); }
};

TEST_P(ClosureProperties, ChiSquare) {
  static const int n_tests = chi2_test_count();
  for (const ClosureConfig& c : configs()) {
    ClosureLobe lobe(c.params);
    for (const Incident& inc : c.incident) {
      Chi2Options o;
      o.samples = kSettings.chi2_samples;
      o.cell_tolerance = kSettings.chi2_cell_tolerance;
      o.n_tests = n_tests;
      o.seed = 0x5eed0000u + GetParam();
      Chi2Result r = chi2_test(lobe, inc.wo, o);
      EXPECT_OR_KNOWN(r.passed, "ChiSquare", inc.name,
                      c.name + " wo " + inc.name + ": " + r.message);
    }
  }
}

TEST_P(ClosureProperties, Consistency) {
  for (const ClosureConfig& c : configs()) {
    ClosureLobe lobe(c.params);
    for (const Incident& inc : c.incident)
      for (Transport mode : {Transport::Radiance, Transport::Importance}) {
        ConsistencyResult r =
            check_consistency(lobe, inc.wo, kSettings.consistency_samples, 17, mode);
        EXPECT_OR_KNOWN(r.ok(), "Consistency", inc.name,
                        c.name + " wo " + inc.name + " mode " + std::to_string(int(mode)) + ": " +
                            std::to_string(r.weight_mismatch) + " weight, " +
                            std::to_string(r.pdf_mismatch) + " pdf, " +
                            std::to_string(r.invalid_values) + " invalid of " +
                            std::to_string(r.valid) + "; " + r.first_failure);
      }
  }
}

// White furnace in importance mode (energy conservation for light arriving from wo, also for
// refraction): Monte Carlo and quadrature albedo <= 1, and the two agree.
TEST_P(ClosureProperties, WhiteFurnace) {
  QuadratureOptions qo;
  qo.max_evals = kSettings.quadrature_evals;
  for (const ClosureConfig& c : configs()) {
    ClosureLobe lobe(c.params);
    bool has_delta = lobe.flags() & kLobeSpecular;
    for (const Incident& inc : c.incident) {
      AlbedoEstimate mc =
          albedo_mc(lobe, inc.wo, kSettings.albedo_samples, 23, Transport::Importance);
      QuadratureResult q = albedo_quadrature(lobe, inc.wo, Transport::Importance, qo);
      Color3 api = lobe.albedo(inc.wo);
      EXPECT_TRUE(finite_nonneg(api)) << c.name << " " << inc.name;
      if (!known_issue(key_name(GetParam()), "WhiteFurnace", inc.name).empty()) continue;
      for (int ch = 0; ch < 3; ++ch) {
        std::string where = c.name + " wo " + inc.name + " channel " + std::to_string(ch);
        EXPECT_LE(mc.mean[ch], 1.0 + 4 * mc.std_error[ch] + 1e-4) << where;
        EXPECT_LE(q.integral[ch], 1.0 + 1e-3 + q.error_estimate) << where;
        if (!has_delta) {
          EXPECT_NEAR(mc.mean[ch], q.integral[ch],
                      4 * mc.std_error[ch] + 2 * q.error_estimate + 2e-3)
              << where << " (quadrature evals " << q.evals << ")";
        }
      }
    }
  }
}

TEST_P(ClosureProperties, Reciprocity) {
  const std::string key = key_name(GetParam());
  if (reciprocity_exemptions().count(key))
    GTEST_SKIP() << key << ": " << reciprocity_exemptions().at(key);
  for (const ClosureConfig& c : configs()) {
    ClosureLobe lobe(c.params);
    ReciprocityResult r = check_reciprocity(lobe, c.eta_below, kSettings.reciprocity_pairs, 31);
    EXPECT_OR_KNOWN(r.ok(), "Reciprocity", "*",
                    c.name + ": " + std::to_string(r.violations) + " + " +
                        std::to_string(r.mode_violations) + " of " + std::to_string(r.checked) +
                        ", max rel err " + std::to_string(r.max_rel_err) + "; " + r.first_failure);
  }
}

TEST_P(ClosureProperties, StressDirections) {
  for (const ClosureConfig& c : configs()) {
    ClosureLobe lobe(c.params);
    StressResult r;
    stress_grid(lobe, c.eta_below, r);
    stress_invalid_inputs(lobe, r);
    stress_random(lobe, kSettings.stress_random, 41, r);
    EXPECT_TRUE(r.ok()) << c.name << ": " << r.invalid_outputs << " invalid outputs, "
                        << r.invalid_inputs << " invalid inputs of " << r.calls << " calls; "
                        << r.first_failure;
  }
}

TEST_P(ClosureProperties, StressParameters) {
  std::vector<ClosureConfig> cs = configs();
  ASSERT_FALSE(cs.empty());
  const ClosureConfig& c = cs.front();
  StressResult r = stress_params(c.params, c.eta_below, kSettings.param_stress_random, 43);
  EXPECT_TRUE(r.ok()) << c.name << ": " << r.invalid_outputs << " invalid outputs, "
                      << r.invalid_inputs << " invalid inputs of " << r.calls << " calls; "
                      << r.first_failure;
  NormalCheck n = check_normals(c.params, 2000, 47);
  EXPECT_TRUE(n.ok()) << c.name << ": " << n.degenerate_violations << " degenerate, "
                      << n.unnormalised_mismatch << " unnormalised; " << n.first_failure;
}

LOBE_INSTANTIATE(ClosureProperties, ::testing::ValuesIn(testable_ids()),
                 [](const ::testing::TestParamInfo<int>& p) { return key_name(p.param); });

LOBE_TEST(ClosureCoverage, EveryImplementedBsdfIsTested) {
  // Every BSDF entry with an implementation is testable, except the documented exclusions
  // (layer: a combinator; measured_bsdf: needs a data file, tested by its own suite).
  int tested = 0;
  for (int id = 0; id < static_cast<int>(registry::closures().size()); ++id) {
    const registry::ClosureEntry& e = registry::closures()[id];
    bool bsdf = e.flags & (registry::kReflect | registry::kTransmit);
    std::string key = e.key;
    if (!bsdf || !closures::has_implementation(id) || key == "measured_bsdf") continue;
    EXPECT_TRUE(is_testable(id)) << key;
    EXPECT_FALSE(configs_for(id, kSettings.level).empty()) << key;
    ++tested;
  }
  EXPECT_GE(tested, 1);
}

} // namespace
