// Phong, Blinn-Phong, Ward, sheen and toon: normalisation closed forms, energy bounds by
// double-precision quadrature, reciprocity, and sample/eval consistency.
#include "closures.h"
#include "glossy.h"
#include "test_util.h"

#include <gtest/gtest.h>

namespace lobe::closures {
namespace {

using test::albedo_by_quadrature;
using test::dir_cos;
constexpr double kPiD = 3.14159265358979323846;

TEST(Phong, NormalisationAndValue) {
  Params p("phong");
  p.set("exponent", 10.0f);
  // At normal incidence the lobe is centred on N: (n+2)/2pi int cos^(n+1) = 1.
  EXPECT_NEAR(albedo_by_quadrature(p, Vec3{0, 0, 1}, 768), 1.0, 2e-3);
  EXPECT_NEAR(albedo(p.id(), p.data(), Vec3{0, 0, 1}).x, 1.0f, 1e-6f);
  EXPECT_LT(albedo_by_quadrature(p, dir_cos(0.3), 512), 1.0);
  Vec3 wi = dir_cos(0.8);
  EXPECT_NEAR(eval(p.id(), p.data(), Vec3{0, 0, 1}, wi).value.x,
              12.0 / (2 * kPiD) * std::pow(0.8, 10) * 0.8, 1e-5);
}

TEST(BlinnPhong, DistributionNormalisedAndEnergyBounded) {
  for (float n : {1.0f, 20.0f, 200.0f}) {
    BlinnPhong b = BlinnPhong::make(n);
    double s = test::integrate_sphere(
        [&](const Vec3& m) { return double(b.D(m)) * std::max(0.0f, m.z); }, 1024, 64);
    EXPECT_NEAR(s, 1.0, 5e-3) << n;
    Params p("blinn_phong");
    p.set("exponent", n);
    for (double mu : {1.0, 0.5, 0.1})
      EXPECT_LE(albedo_by_quadrature(p, dir_cos(mu), 512), 1.0 + 1e-3);
  }
}

TEST(Ward, EnergyBoundedReciprocalAndByHand) {
  Params p("ward");
  p.set("ax", 0.3f).set("ay", 0.1f);
  for (double mu : {1.0, 0.5, 0.1}) EXPECT_LE(albedo_by_quadrature(p, dir_cos(mu), 512), 1.0);
  Vec3 a = dir_cos(0.7, 0.3), b = dir_cos(0.4, 2.9);
  EXPECT_NEAR(eval(p.id(), p.data(), a, b).value.x / b.z,
              eval(p.id(), p.data(), b, a).value.x / a.z, 1e-5);
  // wo = wi = N: h = (0,0,2), f = 4 / (pi ax ay 16).
  EXPECT_NEAR(eval(p.id(), p.data(), Vec3{0, 0, 1}, Vec3{0, 0, 1}).value.x,
              4.0 / (kPiD * 0.03 * 16.0), 1e-3);
}

TEST(Sheen, EnergyBounded) {
  for (float r : {0.1f, 0.5f, 1.0f}) {
    Params p("sheen_bsdf");
    p.set("roughness", r);
    for (double mu : {1.0, 0.5, 0.05}) {
      double q = albedo_by_quadrature(p, dir_cos(mu), 512);
      EXPECT_LE(q, 1.0) << r << " " << mu;
      EXPECT_NEAR(albedo(p.id(), p.data(), dir_cos(mu)).x, q, 0.02 + 0.05 * q) << r << " " << mu;
    }
  }
}

TEST(Toon, EnergyBoundedByEstimate) {
  for (int bands : {1, 3, 8}) {
    for (float soft : {0.0f, 0.2f}) {
      Params p("toon");
      p.set("albedo", 1.0f)
          .set("specular", 0.3f)
          .set("shininess", 30.0f)
          .set("bands", bands)
          .set("softness", soft);
      for (double mu : {1.0, 0.5, 0.1}) {
        double q = albedo_by_quadrature(p, dir_cos(mu), 512);
        EXPECT_LE(q, 1.0);
        EXPECT_LE(q, albedo(p.id(), p.data(), dir_cos(mu)).x + 1e-3);
      }
    }
  }
}

TEST(GlossyFamily, SampleWeightIsValueOverPdf) {
  const char* keys[] = {"phong",      "blinn_phong",         "ward",          "sheen_bsdf", "toon",
                        "oren_nayar", "burley_diffuse_bsdf", "conductor_bsdf"};
  for (const char* key : keys) {
    Params p(key);
    if (std::string(key) == "phong" || std::string(key) == "blinn_phong") p.set("exponent", 15.0f);
    if (std::string(key) == "ward") p.set("ax", 0.2f).set("ay", 0.4f);
    if (std::string(key) == "conductor_bsdf") p.set("roughness_x", 0.3f).set("roughness_y", 0.1f);
    Vec3 wo = dir_cos(0.6, 0.2);
    int ok = 0;
    for (int k = 0; k < 32; ++k) {
      Vec3 u{(k + 0.5f) / 32.0f, std::fmod(0.618034f * k, 1.0f), std::fmod(0.41f * k, 1.0f)};
      auto s = sample(p.id(), p.data(), wo, u);
      if (!s) continue;
      ++ok;
      BsdfEval e = eval(p.id(), p.data(), wo, s->wi);
      ASSERT_GT(e.pdf, 0.0f) << key;
      EXPECT_NEAR(s->pdf, e.pdf, 1e-4f * e.pdf) << key;
      EXPECT_NEAR(s->weight.y, e.value.y / e.pdf, 1e-4f * (1.0f + s->weight.y)) << key;
    }
    EXPECT_GT(ok, 16) << key;
  }
}

} // namespace
} // namespace lobe::closures
