// Tests of the harness on analytic lobes (test_lobes.h): correct lobes pass every check with
// their closed-form expectations, and each deliberately broken lobe is caught by the check
// meant for its defect.
#include "albedo.h"
#include "chi2.h"
#include "consistency.h"
#include "reciprocity.h"
#include "rng.h"
#include "stress.h"
#include "test_lobes.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace lobe;
using namespace lobe::verify;
using namespace lobe::verify::testing;

namespace {
Chi2Options fast_chi2(uint64_t seed) {
  Chi2Options o;
  o.samples = 200000;
  o.seed = seed;
  return o;
}
} // namespace

TEST(Chi2Harness, CellIntegralOfCosinePdfIsOne) {
  Lambert l({1, 1, 1});
  double total = integrate_pdf_cell(l, {0, 0, 1}, 0, 2 * M_PI, 0, 1, 64);
  EXPECT_NEAR(total, 1.0, 1e-4);
}

TEST(Chi2Harness, CorrectLobesPass) {
  Lambert l({0.5f, 0.5f, 0.5f});
  Chi2Result r = chi2_test(l, direction_at(0.7), fast_chi2(1));
  EXPECT_TRUE(r.passed) << r.message;
  EXPECT_NEAR(r.pdf_integral, 1.0, 1e-3);
  for (double theta : {0.0, 1.0, 1.5}) {
    Phong p(30, 0.8f);
    Chi2Result rp = chi2_test(p, direction_at(theta), fast_chi2(2));
    EXPECT_TRUE(rp.passed) << theta << " " << rp.message;
  }
  EtaTransmission t(1.5f);
  Chi2Result rt = chi2_test(t, direction_at(0.4), fast_chi2(3));
  EXPECT_TRUE(rt.passed) << rt.message;
  EXPECT_EQ(rt.cos_min, -1.0);
  EXPECT_EQ(rt.cos_max, 0.0);
}

TEST(Chi2Harness, WrongSamplerFails) {
  Lambert bad({0.5f, 0.5f, 0.5f}, /*uniform_sampling_bug=*/true);
  Chi2Result r = chi2_test(bad, direction_at(0.3), fast_chi2(4));
  EXPECT_FALSE(r.passed) << r.message;
  EXPECT_LT(r.p_value, 1e-6);
}

// A pdf() 1% too large everywhere: the samples still follow its shape, so only the
// normalisation check can catch it (its slack at 2e5 samples is 1e-3 + 3 * 0.1 / sqrt(2e5)).
TEST(Chi2Harness, OverNormalisedPdfFails) {
  class Scaled : public Lambert {
  public:
    Scaled() : Lambert({0.5f, 0.5f, 0.5f}) {}
    float pdf(const Vec3& wo, const Vec3& wi) const override {
      return 1.01f * Lambert::pdf(wo, wi);
    }
  } bad;
  Chi2Result r = chi2_test(bad, direction_at(0.3), fast_chi2(6));
  EXPECT_FALSE(r.passed);
  EXPECT_NE(r.message.find("integrates to 1.01"), std::string::npos) << r.message;
}

TEST(Chi2Harness, PhongSampledWithWrongExponentFails) {
  // Samples from exponent 20 judged against the pdf of exponent 24: a 20% error in the width.
  class Mismatch : public Phong {
  public:
    Mismatch() : Phong(24, 1), sampler_(20, 1) {}
    std::optional<BsdfSample> sample(const Vec3& wo, const Vec3& u, Transport m) const override {
      return sampler_.sample(wo, u, m);
    }
    Phong sampler_;
  } bad;
  Chi2Result r = chi2_test(bad, direction_at(0.5), fast_chi2(5));
  EXPECT_FALSE(r.passed) << r.message;
}

TEST(ConsistencyHarness, CorrectLobesAreConsistent) {
  Lambert l({0.2f, 0.4f, 0.9f});
  ConsistencyResult r = check_consistency(l, direction_at(0.4), 20000, 7);
  EXPECT_TRUE(r.ok()) << r.first_failure;
  EXPECT_EQ(r.valid, 20000u);
  Phong p(50, 0.7f);
  ConsistencyResult rp = check_consistency(p, direction_at(1.2), 20000, 8);
  EXPECT_TRUE(rp.ok()) << rp.first_failure;
  EXPECT_GT(rp.valid, 10000u);
  EXPECT_LT(rp.max_weight_rel_err, 1e-5);
}

TEST(ConsistencyHarness, WrongWeightIsCaught) {
  Lambert bad({0.5f, 0.5f, 0.5f}, false, /*weight_bug=*/1.001f);
  ConsistencyResult r = check_consistency(bad, direction_at(0.4), 1000, 7);
  EXPECT_FALSE(r.ok());
  EXPECT_EQ(r.weight_mismatch, 1000u);
  EXPECT_NEAR(r.max_weight_rel_err, 0.001 / 1.001, 1e-5);
}

TEST(AlbedoHarness, LambertAlbedoIsRho) {
  Lambert l({0.2f, 0.5f, 0.8f});
  for (double theta : {0.0, 0.8, 1.5}) {
    QuadratureResult q = albedo_quadrature(l, direction_at(theta));
    EXPECT_NEAR(q.integral.r, 0.2, 1e-4);
    EXPECT_NEAR(q.integral.g, 0.5, 1e-4);
    EXPECT_NEAR(q.integral.b, 0.8, 1e-4);
    AlbedoEstimate mc = albedo_mc(l, direction_at(theta), 10000, 3);
    EXPECT_NEAR(mc.mean.g, 0.5, 1e-6); // cosine sampling: every weight is rho
  }
}

TEST(AlbedoHarness, PhongNormalisation) {
  // At normal incidence the normalised Phong lobe's albedo is exactly ks:
  // (n+2)/(2 pi) * 2 pi * int_0^{pi/2} cos^(n+1) sin = 1. n = 2000 exercises the adaptivity.
  for (float n : {1.0f, 20.0f, 2000.0f}) {
    Phong p(n, 0.75f);
    QuadratureResult q = albedo_quadrature(p, {0, 0, 1});
    EXPECT_NEAR(q.integral.r, 0.75, 1e-3) << n << " evals " << q.evals;
  }
}

TEST(AlbedoHarness, MonteCarloAgreesWithQuadratureAtFourSigma) {
  Phong p(10, 1.0f);
  Vec3 wo = direction_at(1.1);
  QuadratureResult q = albedo_quadrature(p, wo);
  AlbedoEstimate mc = albedo_mc(p, wo, 200000, 11);
  EXPECT_LT(q.integral.r, 0.999); // part of the lobe falls below the horizon
  EXPECT_NEAR(mc.mean.r, q.integral.r, 4 * mc.std_error.r + 1e-4);
}

TEST(ReciprocityHarness, ReciprocalLobesPass) {
  Lambert l({0.3f, 0.6f, 0.9f});
  EXPECT_TRUE(check_reciprocity(l, 1.0, 20000, 1).ok());
  Phong p(40, 1.0f);
  ReciprocityResult rp = check_reciprocity(p, 1.0, 20000, 2);
  EXPECT_TRUE(rp.ok()) << rp.first_failure;
  EtaTransmission t(1.5f);
  ReciprocityResult rt = check_reciprocity(t, 1.5, 20000, 3);
  EXPECT_TRUE(rt.ok()) << rt.first_failure;
  EXPECT_GT(rt.checked, 19000u);
}

TEST(ReciprocityHarness, MissingEtaSquaredIsCaught) {
  EtaTransmission bad(1.5f, /*drop_eta=*/true);
  ReciprocityResult r = check_reciprocity(bad, 1.5, 2000, 3);
  EXPECT_FALSE(r.ok());
  EXPECT_GT(r.violations, 800u); // every pair that crosses the interface (about half)
}

TEST(StressHarness, WellBehavedLobesSurvive) {
  Lambert l({1, 1, 1});
  Phong p(1e4f, 1.0f);
  EtaTransmission t(1.5f);
  for (const LobeView* lobe : {static_cast<const LobeView*>(&l), static_cast<const LobeView*>(&p),
                               static_cast<const LobeView*>(&t)}) {
    StressResult r;
    stress_grid(*lobe, 1.5, r);
    stress_invalid_inputs(*lobe, r);
    stress_random(*lobe, 20000, 5, r);
    EXPECT_TRUE(r.ok()) << r.first_failure;
    EXPECT_EQ(r.unsampled_mass, 0u);
    EXPECT_GT(r.calls, 60000u);
  }
}

TEST(StressHarness, InfinityAtTheHorizonIsCaught) {
  Phong bad(-1.5f, 1.0f); // cos^-1.5 diverges where the lobe meets cos(alpha) = 0
  StressResult r;
  stress_grid(bad, 1.0, r);
  EXPECT_FALSE(r.ok());
  EXPECT_GT(r.invalid_outputs, 0u);
}
