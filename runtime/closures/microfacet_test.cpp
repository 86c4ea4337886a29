// Microfacet and Fresnel closed forms: normalisation of D, Smith G1, the visible-normal
// identity, exact Fresnel values worked out by hand, Kulla-Conty tables re-derived by an
// independent double-precision quadrature, and the delta lobes.
#include "closures.h"
#include "energy.h"
#include "fresnel.h"
#include "microfacet_dist.h"
#include "test_util.h"

#include <gtest/gtest.h>

#include <complex>

namespace lobe::closures {
namespace {

using test::albedo_by_quadrature;
using test::dir_cos;
constexpr double kPiD = 3.14159265358979323846;

// Quadrature over the upper hemisphere with theta refined near the pole (for peaky lobes).
template <class G> double integrate_hemisphere(G&& g, int nt = 2048, int np = 256) {
  double sum = 0.0;
  for (int i = 0; i < nt; ++i) {
    double t0 = kPiD / 2 * std::pow(double(i) / nt, 2),
           t1 = kPiD / 2 * std::pow(double(i + 1) / nt, 2);
    double th = 0.5 * (t0 + t1);
    for (int j = 0; j < np; ++j) {
      double ph = (j + 0.5) * 2 * kPiD / np;
      sum += g(test::dir(th, ph)) * std::sin(th) * (t1 - t0) * (2 * kPiD / np);
    }
  }
  return sum;
}

struct DistCase {
  float ax, ay;
  bool beckmann;
};
const DistCase kDists[] = {{0.1f, 0.1f, false},  {0.5f, 0.5f, false}, {1.0f, 1.0f, false},
                           {0.2f, 0.05f, false}, {0.1f, 0.1f, true},  {0.5f, 0.5f, true},
                           {0.3f, 0.6f, true}};

TEST(Microfacet, ProjectedAreaOfDIsOne) {
  for (const DistCase& c : kDists) {
    auto d = MicrofacetDistribution::make(c.ax, c.ay, c.beckmann);
    double s = integrate_hemisphere([&](const Vec3& m) { return double(d.D(m)) * m.z; });
    EXPECT_NEAR(s, 1.0, 2e-3) << c.ax << " " << c.ay << " " << c.beckmann;
  }
}

// int G1(wo) max(0, wo.m) D(m) dm = wo.z: Lambda must match D.
TEST(Microfacet, VisibleNormalsIntegrateToCosine) {
  for (const DistCase& c : kDists) {
    auto d = MicrofacetDistribution::make(c.ax, c.ay, c.beckmann);
    for (double mu : {0.9, 0.4, 0.1}) {
      Vec3 wo = dir_cos(mu, 0.7);
      double s = integrate_hemisphere(
          [&](const Vec3& m) { return double(d.G1(wo)) * std::max(0.0f, dot(wo, m)) * d.D(m); });
      EXPECT_NEAR(s, mu, 3e-3) << c.ax << " " << c.beckmann << " " << mu;
    }
  }
}

TEST(Microfacet, SmithG1ClosedForms) {
  auto ggx = MicrofacetDistribution::make(0.5f, 0.5f, false);
  Vec3 w = dir_cos(0.5); // tan^2 = 3
  EXPECT_NEAR(ggx.G1(w), 2.0 / (1.0 + std::sqrt(1.0 + 0.25 * 3.0)), 1e-6);
  EXPECT_EQ(ggx.G1(Vec3{0, 0, 1}), 1.0f);
  EXPECT_EQ(ggx.G1(Vec3{1, 0, 0}), 0.0f);
  auto bk = MicrofacetDistribution::make(0.5f, 0.5f, true);
  double a = 1.0 / (0.5 * std::sqrt(3.0));
  double lam = 0.5 * (std::erf(a) - 1.0) + std::exp(-a * a) / (2.0 * a * std::sqrt(kPiD));
  EXPECT_NEAR(bk.G1(w), 1.0 / (1.0 + lam), 1e-6);
  EXPECT_EQ(bk.G1(Vec3{1, 0, 0}), 0.0f);
}

TEST(Microfacet, GgxPeakHasNoCancellation) {
  // At m = n, D = 1 / (pi a^2) exactly, even for a = 3e-4.
  auto d = MicrofacetDistribution::make(3e-4f, 3e-4f, false);
  EXPECT_NEAR(d.D(Vec3{0, 0, 1}) * kPiD * 9e-8, 1.0, 1e-5);
}

TEST(Fresnel, DielectricByHand) {
  EXPECT_NEAR(fresnel_dielectric(1.0f, 1.5f), 0.04, 1e-6);
  // 45 degrees into glass: sin t = 0.7071/1.5, rs = -0.303337, rp = 0.092019.
  EXPECT_NEAR(fresnel_dielectric(std::sqrt(0.5f), 1.5f),
              0.5 * (0.303337 * 0.303337 + 0.092019 * 0.092019), 1e-5);
  EXPECT_EQ(fresnel_dielectric(0.5f, 1.0f / 1.5f), 1.0f); // 60 degrees from inside: TIR
  EXPECT_NEAR(fresnel_dielectric(0.3f, 1.0f), 0.0, 1e-7);
  EXPECT_EQ(fresnel_dielectric(0.0f, 1.5f), 1.0f);
}

TEST(Fresnel, ConductorMatchesComplexFormula) {
  // Normal incidence: ((n-1)^2 + k^2) / ((n+1)^2 + k^2) = 9.64 / 10.44 for n = 0.2, k = 3.
  EXPECT_NEAR(fresnel_conductor(1.0f, 0.2f, 3.0f), 9.64 / 10.44, 1e-5);
  for (double c : {0.8, 0.5, 0.1}) {
    std::complex<double> eta(0.2, 3.0);
    std::complex<double> ct = std::sqrt(1.0 - (1.0 - c * c) / (eta * eta));
    double rs = std::norm((c - eta * ct) / (c + eta * ct));
    double rp = std::norm((eta * c - ct) / (eta * c + ct));
    EXPECT_NEAR(fresnel_conductor(float(c), 0.2f, 3.0f), 0.5 * (rs + rp), 1e-5) << c;
  }
  // k = 0 reduces to the dielectric formula.
  EXPECT_NEAR(fresnel_conductor(0.6f, 1.5f, 0.0f), fresnel_dielectric(0.6f, 1.5f), 1e-6);
}

TEST(Fresnel, ConductorHemisphericalAverage) {
  // F_avg = 2 int F mu dmu, by a 4e4-point midpoint rule over the complex formula above.
  struct Metal {
    float n, k;
  };
  for (Metal m : {Metal{0.18f, 3.42f},
                  {1.37f, 1.77f},
                  {1.66f, 9.22f},
                  {0.05f, 4.0f},
                  {2.9f, 3.0f},
                  {3.1f, 3.3f},
                  {1.5f, 0.0f}}) {
    std::complex<double> eta(m.n, m.k);
    double want = 0.0;
    const int n = 40000;
    for (int i = 0; i < n; ++i) {
      double c = (i + 0.5) / n;
      std::complex<double> ct = std::sqrt(1.0 - (1.0 - c * c) / (eta * eta));
      double rs = std::norm((c - eta * ct) / (c + eta * ct));
      double rp = std::norm((eta * c - ct) / (eta * c + ct));
      want += 2.0 * c * 0.5 * (rs + rp) / n;
    }
    Vec3 got = fresnel_average([&](float c) { return splat(fresnel_conductor(c, m.n, m.k)); });
    EXPECT_NEAR(got.x, want, 3e-4) << m.n << " " << m.k;
  }
  // F = 1 averages to 1 exactly (the lossless conductor's compensation relies on it).
  EXPECT_NEAR(fresnel_average([](float) { return splat(1.0f); }).y, 1.0f, 1e-6f);
}

TEST(Fresnel, Schlick) {
  Vec3 f = fresnel_schlick(0.5f, splat(0.04f), splat(1.0f), 5.0f);
  EXPECT_NEAR(f.x, 0.04 + 0.96 * 0.03125, 1e-6);
  EXPECT_NEAR(fresnel_schlick(0.5f, splat(0.0f), splat(1.0f), 2.0f).y, 0.25, 1e-6);
}

// Independent GGX in double: E(mu) = int D G2 / (4 mu) over wi.
double ggx_albedo_reference(double alpha, double mu) {
  auto lambda = [&](const Vec3& w) {
    double t2 = (double(w.x) * w.x + double(w.y) * w.y) / (double(w.z) * w.z);
    return 0.5 * (std::sqrt(1.0 + alpha * alpha * t2) - 1.0);
  };
  Vec3 wo = dir_cos(mu);
  return integrate_hemisphere([&](const Vec3& wi) {
    Vec3 h = normalize(wo + wi);
    double c2 = double(h.z) * h.z;
    double d = alpha * alpha / (kPiD * std::pow(c2 * (alpha * alpha - 1.0) + 1.0, 2));
    return d / (1.0 + lambda(wo) + lambda(wi)) / (4.0 * mu);
  });
}

TEST(EnergyTables, RederiveGgxEntries) {
  for (int j : {10, 20, 31}) {
    for (int i : {8, 16, 31}) {
      double alpha = j / 31.0, mu = i / 31.0;
      EXPECT_NEAR(kEnergyE[0][j][i], ggx_albedo_reference(alpha, mu), 3e-3) << j << " " << i;
    }
  }
}

TEST(EnergyTables, BeckmannEntriesMatchLobeQuadrature) {
  Params p("microfacet");
  p.set("distribution", "beckmann")
      .set("xalpha", 20.0f / 31.0f)
      .set("yalpha", 20.0f / 31.0f)
      .set("eta", 1.0f)
      .set("refract", 0);
  // Fresnel 1 through generalized_schlick with f0 = f90 = 1 and compensation off.
  Params g("generalized_schlick_bsdf");
  g.set("distribution", "beckmann")
      .set("roughness_x", 20.0f / 31.0f)
      .set("roughness_y", 20.0f / 31.0f)
      .set("transmission_tint", 0.0f)
      .set("energy_compensation", 0);
  double q = albedo_by_quadrature(g, dir_cos(16.0 / 31.0), 512);
  EXPECT_NEAR(kEnergyE[1][20][16], q, 3e-3);
}

TEST(Microfacet, KullaContyRestoresEnergyForWhiteFresnel) {
  for (const char* dist : {"ggx", "beckmann"}) {
    Params g("generalized_schlick_bsdf");
    g.set("distribution", dist)
        .set("roughness_x", 0.8f)
        .set("roughness_y", 0.8f)
        .set("transmission_tint", 0.0f);
    for (double mu : {0.9, 0.5, 0.2}) {
      double q = albedo_by_quadrature(g, dir_cos(mu), 512);
      EXPECT_NEAR(q, 1.0, 1.5e-2) << dist << " " << mu;
      EXPECT_NEAR(albedo(g.id(), g.data(), dir_cos(mu)).x, q, 2e-2);
    }
  }
}

TEST(Microfacet, ConductorAlbedoBelowOne) {
  Params c("conductor_bsdf");
  c.set("roughness_x", 0.3f)
      .set("roughness_y", 0.3f)
      .set("ior", Vec3{0.2f, 0.4f, 1.5f})
      .set("extinction", Vec3{3.0f, 2.5f, 1.8f});
  double q = albedo_by_quadrature(c, dir_cos(0.6), 512);
  EXPECT_LT(q, 1.0);
  EXPECT_GT(q, 0.8);
}

TEST(Microfacet, SampleWeightMatchesEval) {
  Params d("dielectric_bsdf");
  d.set("roughness_x", 0.3f)
      .set("roughness_y", 0.3f)
      .set("ior", 1.5f)
      .set("transmission_tint", 1.0f);
  for (float mu : {0.8f, -0.8f, 0.2f, -0.3f}) {
    Vec3 wo = dir_cos(mu, 0.4);
    int n_transmit = 0;
    for (int k = 0; k < 16; ++k) {
      Vec3 u{(k + 0.5f) / 16.0f, std::fmod(0.618f * k, 1.0f), std::fmod(0.377f * k + 0.1f, 1.0f)};
      auto s = sample(d.id(), d.data(), wo, u);
      if (!s) continue;
      BsdfEval e = eval(d.id(), d.data(), wo, s->wi);
      ASSERT_GT(e.pdf, 0.0f);
      EXPECT_NEAR(s->pdf, e.pdf, 1e-3f * e.pdf);
      EXPECT_NEAR(s->weight.x, e.value.x / e.pdf, 1e-3f * (1.0f + s->weight.x));
      n_transmit += (s->flags & kLobeTransmit) ? 1 : 0;
    }
    if (mu > 0) {
      EXPECT_GT(n_transmit, 8) << mu;
    } // mostly refraction into glass
  }
}

TEST(Specular, MirrorAndRefraction) {
  Params r("reflection");
  Vec3 wo = dir_cos(0.6, 0.3);
  auto s = sample(r.id(), r.data(), wo, {0.3f, 0.3f, 0.3f});
  ASSERT_TRUE(s);
  EXPECT_NEAR(s->wi.x, -wo.x, 1e-6f);
  EXPECT_NEAR(s->wi.z, wo.z, 1e-6f);
  EXPECT_NEAR(s->weight.y, 1.0f, 1e-6f);
  EXPECT_EQ(s->flags, unsigned(kLobeReflect | kLobeSpecular));
  EXPECT_EQ(eval(r.id(), r.data(), wo, s->wi).value.x, 0.0f);

  Params t("refraction");
  t.set("eta", 1.5f);
  auto st = sample(t.id(), t.data(), Vec3{0, 0, 1}, {0.5f, 0.5f, 0.5f});
  ASSERT_TRUE(st);
  EXPECT_NEAR(st->wi.z, -1.0f, 1e-6f);
  EXPECT_NEAR(st->weight.x, (1.0 - 0.04) / 2.25, 1e-5); // radiance: / eta^2
  auto si = sample(t.id(), t.data(), Vec3{0, 0, 1}, {0.5f, 0.5f, 0.5f}, Transport::Importance);
  EXPECT_NEAR(si->weight.x, 1.0 - 0.04, 1e-5);
  // From inside beyond the critical angle: no refraction and reflection is off -> no sample.
  EXPECT_FALSE(sample(t.id(), t.data(), dir_cos(-0.3), {0.5f, 0.5f, 0.5f}).has_value());
}

TEST(Specular, DielectricTirReflectsWithWeightOne) {
  Params d("dielectric_bsdf");
  d.set("ior", 1.5f).set("transmission_tint", 1.0f); // roughness 0: delta
  auto s = sample(d.id(), d.data(), dir_cos(-0.3), {0.5f, 0.5f, 0.9f});
  ASSERT_TRUE(s);
  EXPECT_LT(s->wi.z, 0.0f);
  EXPECT_NEAR(s->weight.x, 1.0f, 1e-6f);
  EXPECT_TRUE(s->flags & kLobeSpecular);
}

TEST(Specular, IndexMatchedPassesThrough) {
  Params d("dielectric_bsdf");
  d.set("ior", 1.00001f)
      .set("transmission_tint", 1.0f)
      .set("roughness_x", 0.5f)
      .set("roughness_y", 0.5f);
  Vec3 wo = dir_cos(0.7, 1.0);
  auto s = sample(d.id(), d.data(), wo, {0.2f, 0.7f, 0.4f});
  ASSERT_TRUE(s);
  EXPECT_NEAR(s->wi.x, -wo.x, 1e-6f);
  EXPECT_NEAR(s->wi.z, -wo.z, 1e-6f);
  EXPECT_NEAR(s->weight.x, 1.0f, 1e-6f);
}

} // namespace
} // namespace lobe::closures
