// Closed-form checks of the diffuse family: Lambert's value and sampling weight, Oren-Nayar,
// Fujii/EON and Burley directional albedos against double-precision quadrature.
#include "closures.h"
#include "test_util.h"

#include <gtest/gtest.h>

namespace lobe::closures {
namespace {

using test::albedo_by_quadrature;
using test::dir_cos;
constexpr double kPiD = 3.14159265358979323846;

TEST(Diffuse, LambertValueIsCosOverPi) {
  Params p("diffuse");
  Vec3 wo = dir_cos(0.3, 1.0), wi = dir_cos(0.8, 2.5);
  BsdfEval e = eval(p.id(), p.data(), wo, wi);
  EXPECT_NEAR(e.value.x, 0.8 / kPiD, 1e-6);
  EXPECT_NEAR(e.value.z, 0.8 / kPiD, 1e-6);
  EXPECT_NEAR(e.pdf, 0.8 / kPiD, 1e-6);
  EXPECT_EQ(eval(p.id(), p.data(), wo, dir_cos(-0.5)).value.x, 0.0f); // below: no reflection
  EXPECT_NEAR(albedo_by_quadrature(p, wo), 1.0, 1e-4);
  EXPECT_NEAR(albedo(p.id(), p.data(), wo).y, 1.0f, 1e-6f);
}

TEST(Diffuse, LambertSampleWeightIsOne) {
  Params p("diffuse");
  Vec3 wo = dir_cos(0.6);
  for (float u : {0.0f, 0.13f, 0.5f, 0.77f, 0.999f}) {
    auto s = sample(p.id(), p.data(), wo, {u, 1.0f - u, 0.5f});
    ASSERT_TRUE(s.has_value()) << u;
    EXPECT_NEAR(s->weight.x, 1.0f, 1e-5f);
    EXPECT_GT(s->wi.z, 0.0f);
    EXPECT_NEAR(s->pdf, s->wi.z / kPiD, 1e-5);
    EXPECT_EQ(s->flags, unsigned(kLobeDiffuse | kLobeReflect));
  }
}

TEST(Diffuse, TwoSidedAndTranslucent) {
  Params p("diffuse");
  // Viewed from below the normal, the lobe mirrors: reflection on the lower side.
  EXPECT_NEAR(eval(p.id(), p.data(), dir_cos(-0.5), dir_cos(-0.7)).value.x, 0.7 / kPiD, 1e-6);
  Params t("translucent_bsdf");
  t.set("albedo", Vec3{0.5f, 0.25f, 1.0f});
  BsdfEval e = eval(t.id(), t.data(), dir_cos(0.5), dir_cos(-0.4));
  EXPECT_NEAR(e.value.x, 0.5 * 0.4 / kPiD, 1e-6);
  EXPECT_NEAR(e.value.y, 0.25 * 0.4 / kPiD, 1e-6);
  EXPECT_EQ(eval(t.id(), t.data(), dir_cos(0.5), dir_cos(0.4)).value.x, 0.0f);
  EXPECT_NEAR(albedo_by_quadrature(t, dir_cos(0.5)), 0.5, 1e-4);
}

TEST(Diffuse, DegenerateNormalGivesNothing) {
  Params p("diffuse");
  p.set("N", Vec3{0, 0, 0});
  EXPECT_EQ(eval(p.id(), p.data(), dir_cos(0.5), dir_cos(0.5)).value.x, 0.0f);
  EXPECT_FALSE(sample(p.id(), p.data(), dir_cos(0.5), {0.3f, 0.3f, 0.3f}).has_value());
  p.set("N", Vec3{NAN, 0, 1});
  EXPECT_EQ(eval(p.id(), p.data(), dir_cos(0.5), dir_cos(0.5)).pdf, 0.0f);
}

TEST(Diffuse, OrenNayarZeroSigmaIsLambert) {
  Params p("oren_nayar");
  p.set("sigma", 0.0f);
  EXPECT_NEAR(eval(p.id(), p.data(), dir_cos(0.3, 0.0), dir_cos(0.9, 0.2)).value.x, 0.9 / kPiD,
              1e-6);
}

// Closed-form directional albedo A + B G(mu)/pi against quadrature of the lobe.
TEST(Diffuse, OrenNayarAlbedoMatchesQuadrature) {
  for (float sigma : {0.3f, 1.0f}) {
    for (double mu : {0.95, 0.5, 0.1}) {
      Params p("oren_nayar");
      p.set("sigma", sigma);
      double q = albedo_by_quadrature(p, dir_cos(mu), 384);
      EXPECT_NEAR(albedo(p.id(), p.data(), dir_cos(mu)).x, q, 2e-3) << sigma << " " << mu;
      EXPECT_LE(q, 1.0 + 1e-3);
    }
  }
}

TEST(Diffuse, FujiiAndEonAlbedo) {
  for (int comp : {0, 1}) {
    for (float r : {0.5f, 1.0f}) {
      for (double mu : {0.9, 0.4, 0.1}) {
        Params p("oren_nayar_diffuse_bsdf");
        p.set("roughness", r).set("energy_compensation", comp);
        double q = albedo_by_quadrature(p, dir_cos(mu), 384);
        EXPECT_NEAR(albedo(p.id(), p.data(), dir_cos(mu)).x, q, 2e-3) << comp << r << mu;
        if (comp)
          EXPECT_NEAR(q, 1.0, 3e-3) << "EON with albedo 1 preserves energy";
        else
          EXPECT_LT(q, 1.0);
      }
    }
  }
}

TEST(Diffuse, BurleyEnergyAtMostOneAndReciprocal) {
  Params p("burley_diffuse_bsdf");
  p.set("roughness", 1.0f);
  for (double mu : {1.0, 0.5, 0.05}) EXPECT_LE(albedo_by_quadrature(p, dir_cos(mu)), 1.0);
  Vec3 a = dir_cos(0.3, 0.4), b = dir_cos(0.7, 2.0);
  float fab = eval(p.id(), p.data(), a, b).value.x / b.z;
  float fba = eval(p.id(), p.data(), b, a).value.x / a.z;
  EXPECT_NEAR(fab, fba, 1e-6f);
  // Roughness 0: F90 = 0, f = rho/pi (1 - (1-c_i)^5)(1 - (1-c_o)^5), checked at one point.
  p.set("roughness", 0.0f);
  double fi = 1 - std::pow(1 - 0.7, 5), fo = 1 - std::pow(1 - 0.3, 5);
  EXPECT_NEAR(eval(p.id(), p.data(), a, b).value.x, fi * fo * 0.7 / kPiD, 1e-6);
}

} // namespace
} // namespace lobe::closures
