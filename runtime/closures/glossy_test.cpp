// Phong, Blinn-Phong, Ward, sheen and toon: normalisation closed forms, energy bounds by
// double-precision quadrature, reciprocity, and sample/eval consistency.
#include "closures.h"
#include "glossy.h"
#include "sheen.h"
#include "test_util.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <tuple>

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

// The Charlie distribution and its projected area, computed here in double precision.
double charlie_d(double cos_m, double r) {
  double sin_m = std::sqrt(std::max(0.0, 1.0 - cos_m * cos_m));
  return (2.0 + 1.0 / r) * std::pow(sin_m, 1.0 / r) / (2.0 * kPiD);
}
double charlie_projected_area(double mu, double r) {
  Vec3 wo = dir_cos(mu);
  return test::integrate_sphere(
      [&](const Vec3& m) {
        return m.z > 0.0f ? charlie_d(m.z, r) * std::max(0.0, double(dot(wo, m))) : 0.0;
      },
      2048, 512);
}

TEST(Sheen, ProjectedAreaIsTheDistributionsOwn) {
  for (float r : {0.01f, 0.03f, 0.2f, 0.5f, 1.0f}) {
    Sheen s = Sheen::make(Vec3{1, 1, 1}, r);
    // Normal incidence: int D cos = 1 (D is normalised). Grazing, in closed form:
    // P(0) = (2 + 1/r)/pi int_0^pi/2 sin^(1/r + 2), a Wallis integral.
    double n = 1.0 / r + 2.0;
    double p0 = (2.0 + 1.0 / r) / kPiD * std::sqrt(kPiD) / 2.0 *
                std::exp(std::lgamma((n + 1.0) / 2.0) - std::lgamma(n / 2.0 + 1.0));
    EXPECT_NEAR(s.projected_area(1.0f), 1.0, 2e-4) << r;
    EXPECT_NEAR(s.projected_area(0.0f), p0, 2e-3 * p0) << r; // bilinear in t: may only exceed
    EXPECT_GE(s.projected_area(0.0f), p0 * (1.0 - 1e-6)) << r;
    for (double mu : {0.93, 0.7, 0.35, 0.08}) {
      double exact = charlie_projected_area(mu, r);
      double table = s.projected_area(static_cast<float>(mu));
      EXPECT_NEAR(table, exact, 2e-3 * exact) << r << " " << mu;
      // Never below the exact masking (quadrature error of the reference ~1e-5).
      EXPECT_GE(table, exact * (1.0 - 3e-5)) << r << " " << mu;
    }
  }
}

TEST(Sheen, EvalIsHeightCorrelatedSmith) {
  for (float r : {0.05f, 0.5f}) {
    Params p("sheen_bsdf");
    p.set("roughness", r).set("albedo", 0.5f);
    for (auto [mo, mi, phi] : {std::tuple{0.8, 0.3, 2.5}, {0.2, 0.15, 0.7}, {0.05, 0.6, 3.0}}) {
      Vec3 wo = dir_cos(mo), wi = dir_cos(mi, phi);
      double lo = charlie_projected_area(wo.z, r) / wo.z - 1.0;
      double li = charlie_projected_area(wi.z, r) / wi.z - 1.0;
      double h = length(wo + wi);
      double f = charlie_d((wo.z + wi.z) / h, r) / (4.0 * wo.z * wi.z * (1.0 + lo + li));
      EXPECT_NEAR(eval(p.id(), p.data(), wo, wi).value.x, 0.5 * f * wi.z, 3e-3 * 0.5 * f * wi.z)
          << r << " " << mo << " " << mi;
    }
  }
}

TEST(Sheen, EnergyBoundedAndTabulatedAlbedo) {
  for (float r : {0.01f, 0.1f, 0.5f, 1.0f}) {
    Params p("sheen_bsdf");
    p.set("roughness", r);
    for (double mu : {1.0, 0.5, 0.087, 0.0014}) {
      double q = albedo_by_quadrature(p, dir_cos(mu), 1024);
      EXPECT_LE(q, 1.0) << r << " " << mu;
      double a = albedo(p.id(), p.data(), dir_cos(mu)).x;
      EXPECT_GE(a, q - 1e-3) << r << " " << mu; // never under-attenuates a layered base
      EXPECT_LE(a, q + 5e-3) << r << " " << mu;
    }
    // Height-correlated Smith: towards grazing the masking of wo dominates G2, and the albedo
    // tends to the visible-normal integral of G1, which is 1.
    double g = albedo_by_quadrature(p, dir_cos(1e-4), 1024);
    EXPECT_GT(g, 0.99) << r;
    EXPECT_LE(g, 1.0 + 1e-4) << r;
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
