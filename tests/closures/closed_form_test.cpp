// Closed-form expectations, each computed here from its published formula in double precision
// (never from the library's code): Lambert eval and albedo, the modified Phong normalisation,
// Oren-Nayar's qualitative model and its sigma = 0 limit, the EON furnace, exact dielectric
// and conductor Fresnel through delta and near-delta lobes, and the lossless furnace of the
// energy-compensated microfacet lobes.
#include "albedo.h"
#include "closure_lobe.h"
#include "configs.h"
#include "microfacet_dist.h"
#include "rng.h"
#include "stats.h"
#include "suite.h"

#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <vector>

using namespace lobe;
using namespace lobe::verify;
using namespace lobe::verify::suite;

namespace {

bool implemented(const char* key) {
  int id = registry::id_of(key);
  return id >= 0 && closures::has_implementation(id);
}
#define REQUIRE_CLOSURE(key)                                                                       \
  if (!implemented(key)) GTEST_SKIP() << key << " has no implementation yet"

// Exact dielectric Fresnel reflectance for unpolarised light, relative IOR eta = n_t / n_i.
double fresnel_dielectric(double cos_i, double eta) {
  double s2t = (1 - cos_i * cos_i) / (eta * eta);
  if (s2t >= 1) return 1;
  double ct = std::sqrt(1 - s2t);
  double rs = (cos_i - eta * ct) / (cos_i + eta * ct);
  double rp = (eta * cos_i - ct) / (eta * cos_i + ct);
  return 0.5 * (rs * rs + rp * rp);
}

// Exact conductor Fresnel with complex IOR n - ik (incident medium IOR 1).
double fresnel_conductor(double cos_i, double n, double k) {
  std::complex<double> eta(n, -k);
  std::complex<double> ct = std::sqrt(1.0 - (1.0 - cos_i * cos_i) / (eta * eta));
  std::complex<double> rs = (cos_i - eta * ct) / (cos_i + eta * ct);
  std::complex<double> rp = (eta * cos_i - ct) / (eta * cos_i + ct);
  return 0.5 * (std::norm(rs) + std::norm(rp));
}

const double kAngles[] = {0, 20, 45, 70, 85};

TEST(QuickClosedForm, FresnelReferenceValues) {
  // Sanity of the test's own formulas: ((eta-1)/(eta+1))^2 at normal incidence, 1 beyond TIR.
  EXPECT_NEAR(fresnel_dielectric(1.0, 1.5), 0.04, 1e-12);
  EXPECT_NEAR(fresnel_dielectric(0.5, 1.0 / 1.5), 1.0, 1e-12);
  EXPECT_NEAR(fresnel_conductor(1.0, 0.2, 3.9), (0.8 * 0.8 + 3.9 * 3.9) / (1.2 * 1.2 + 3.9 * 3.9),
              1e-12);
}

TEST(QuickClosedForm, LambertEvalAndAlbedo) {
  REQUIRE_CLOSURE("diffuse");
  ClosureLobe l(closures::Params("diffuse"));
  Pcg32 rng(3);
  for (int k = 0; k < 100; ++k) {
    Vec3 wo = uniform_sphere(rng.next_double() * 0.5, rng.next_double());
    Vec3 wi = uniform_sphere(rng.next_double() * 0.5, rng.next_double());
    EXPECT_NEAR(l.eval(wo, wi, Transport::Radiance).value.y, wi.z / M_PI, 1e-6);
  }
  for (double th : kAngles) {
    Vec3 wo = direction_at(th * M_PI / 180);
    EXPECT_NEAR(albedo_quadrature(l, wo).integral.g, 1.0, 1e-4) << th;
  }
}

TEST(QuickClosedForm, TranslucentAlbedoIsRho) {
  REQUIRE_CLOSURE("translucent_bsdf");
  closures::Params p("translucent_bsdf");
  p.set("albedo", Vec3{0.2f, 0.5f, 0.7f});
  ClosureLobe l(p);
  Vec3 wo = direction_at(0.6);
  QuadratureResult q = albedo_quadrature(l, wo);
  EXPECT_NEAR(q.integral.r, 0.2, 1e-4);
  EXPECT_NEAR(q.integral.b, 0.7, 1e-4);
  Vec3 wi{0.3f, 0.0f, -std::sqrt(1 - 0.09f)};
  EXPECT_NEAR(l.eval(wo, wi, Transport::Radiance).value.y, 0.5 * std::fabs(wi.z) / M_PI, 1e-6);
}

TEST(QuickClosedForm, PhongNormalisation) {
  // (n+2)/(2 pi) * 2 pi * int cos^(n+1) sin = 1 at normal incidence, for every n.
  REQUIRE_CLOSURE("phong");
  for (float n : {1.0f, 20.0f, 200.0f}) {
    closures::Params p("phong");
    p.set("exponent", n);
    ClosureLobe l(p);
    EXPECT_NEAR(albedo_quadrature(l, {0, 0, 1}).integral.g, 1.0, 2e-3) << n;
  }
}

// Oren-Nayar (1994) qualitative model in its angle form.
double oren_nayar_f(double sigma, const Vec3& wo, const Vec3& wi) {
  double s2 = sigma * sigma, A = 1 - 0.5 * s2 / (s2 + 0.33), B = 0.45 * s2 / (s2 + 0.09);
  double ti = std::acos(wi.z), to = std::acos(wo.z);
  double dphi = std::atan2(wi.y, wi.x) - std::atan2(wo.y, wo.x);
  double alpha = std::max(ti, to), beta = std::min(ti, to);
  return (A + B * std::max(0.0, std::cos(dphi)) * std::sin(alpha) * std::tan(beta)) / M_PI;
}

TEST(QuickClosedForm, OrenNayarFormulaAndBounds) {
  REQUIRE_CLOSURE("oren_nayar");
  Pcg32 rng(5);
  for (float sigma : {0.0f, 0.3f, 1.0f}) {
    closures::Params p("oren_nayar");
    p.set("sigma", sigma);
    ClosureLobe l(p);
    for (int k = 0; k < 200; ++k) {
      Vec3 wo = uniform_sphere(rng.next_double() * 0.49, rng.next_double());
      Vec3 wi = uniform_sphere(rng.next_double() * 0.49, rng.next_double());
      double expect = oren_nayar_f(sigma, wo, wi) * wi.z;
      EXPECT_NEAR(l.eval(wo, wi, Transport::Radiance).value.y, expect, 2e-5 + 1e-4 * expect)
          << sigma;
    }
    for (double th : kAngles) {
      double a = albedo_quadrature(l, direction_at(th * M_PI / 180)).integral.g;
      EXPECT_LE(a, 1.0 + 1e-4) << sigma << " " << th;
      if (sigma == 0) {
        EXPECT_NEAR(a, 1.0, 1e-4);
      }
    }
  }
}

TEST(QuickClosedForm, EnergyPreservingOrenNayarFurnace) {
  REQUIRE_CLOSURE("oren_nayar_diffuse_bsdf");
  for (float r : {0.25f, 0.5f, 1.0f}) {
    closures::Params p("oren_nayar_diffuse_bsdf");
    p.set("roughness", r).set("energy_compensation", 1);
    ClosureLobe l(p);
    for (double th : kAngles)
      EXPECT_NEAR(albedo_quadrature(l, direction_at(th * M_PI / 180)).integral.g, 1.0, 2e-3)
          << r << " " << th;
  }
}

TEST(QuickClosedForm, DielectricFresnelOfDeltaMirror) {
  REQUIRE_CLOSURE("reflection");
  for (float eta : {1.5f, 2.417f}) {
    closures::Params p("reflection");
    p.set("eta", eta);
    ClosureLobe l(p);
    for (double th : kAngles) {
      Vec3 wo = direction_at(th * M_PI / 180);
      auto s = l.sample(wo, {0.3f, 0.4f, 0.5f}, Transport::Radiance);
      ASSERT_TRUE(s) << th;
      EXPECT_TRUE(s->flags & kLobeSpecular);
      EXPECT_NEAR(s->wi.x, -wo.x, 1e-6);
      EXPECT_NEAR(s->wi.z, wo.z, 1e-6);
      EXPECT_NEAR(s->weight.y, fresnel_dielectric(wo.z, eta), 1e-5) << eta << " " << th;
    }
  }
}

TEST(QuickClosedForm, ConductorFresnelAtZeroRoughness) {
  // Roughness 0 is a delta lobe (BSDF_NOTES.md): its weight is the exact complex Fresnel.
  REQUIRE_CLOSURE("conductor_bsdf");
  closures::Params p("conductor_bsdf");
  const double n[3] = {0.2, 0.9, 1.1}, k[3] = {3.9, 2.4, 2.2};
  p.set("roughness_x", 0.0f).set("roughness_y", 0.0f);
  p.set("ior", Vec3{0.2f, 0.9f, 1.1f}).set("extinction", Vec3{3.9f, 2.4f, 2.2f});
  ClosureLobe l(p);
  for (double th : kAngles) {
    Vec3 wo = direction_at(th * M_PI / 180);
    auto s = l.sample(wo, {0.3f, 0.4f, 0.5f}, Transport::Radiance);
    ASSERT_TRUE(s) << th;
    ASSERT_TRUE(s->flags & kLobeSpecular) << "roughness 0 should be a delta lobe";
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(s->weight[c], fresnel_conductor(wo.z, n[c], k[c]), 2e-4) << th << " " << c;
  }
}

TEST(QuickClosedForm, LosslessMicrofacetFurnace) {
  // Fresnel = 1 and energy compensation on: albedo >= 0.99 at every roughness and angle.
  std::vector<ClosureConfig> cs = lossless_configs(kSettings.level);
  if (cs.empty()) GTEST_SKIP() << "no energy-compensated conductor implemented yet";
  QuadratureOptions qo;
  qo.max_evals = kSettings.quadrature_evals;
  for (const ClosureConfig& c : cs) {
    ClosureLobe l(c.params);
    for (const Incident& inc : c.incident) {
      QuadratureResult q = albedo_quadrature(l, inc.wo, Transport::Importance, qo);
      AlbedoEstimate mc = albedo_mc(l, inc.wo, kSettings.albedo_samples, 3, Transport::Importance);
      EXPECT_GE(q.integral.g + q.error_estimate, 0.99) << c.name << " " << inc.name;
      EXPECT_LE(q.integral.g, 1.0 + 2e-3 + q.error_estimate) << c.name << " " << inc.name;
      EXPECT_GE(mc.mean.g + 4 * mc.std_error.g, 0.99) << c.name << " " << inc.name;
    }
  }
}

// Beckmann visible-normal sampling against D_wo(m) = G1(wo) max(0, wo.m) D(m) / wo.z written
// here in double precision: in stretched slopes (u, v) = -(m.x / (ax m.z), m.y / (ay m.z)) the
// density is max(0, wo.z - ax u wo.x - ay v wo.y) exp(-u^2 - v^2) / (pi wo.z) G1(wo), so the
// histogram of sampled normals over a slope grid is compared cell by cell (chi-square, cells
// below 5 expected pooled), independently of the library's pdf(). Covers the cases where the
// Newton inversion is hardest: grazing incidence (cos 0.0014) and small alpha.
TEST(QuickClosedForm, BeckmannVisibleNormalSampling) {
  struct Case {
    double ax, ay;
    Vec3 wo;
  };
  const Vec3 grazing = normalize(Vec3{0.5f, 0.5f, 0.001f});
  const Case cases[] = {{0.05, 0.05, grazing},
                        {0.2, 0.05, grazing},
                        {0.5, 0.5, grazing},
                        {0.05, 0.05, Vec3{0.5f, 0.0f, 0.8660254f}},
                        {0.2, 0.05, Vec3{0.0f, 0.8660254f, 0.5f}}};
  const int n = 36;
  const double lim = 4.5, h = 2 * lim / n;
  const uint64_t samples = 400000;
  for (const Case& c : cases) {
    closures::MicrofacetDistribution d =
        closures::MicrofacetDistribution::make(float(c.ax), float(c.ay), true);
    const double wx = c.wo.x, wy = c.wo.y, wz = c.wo.z;
    auto density = [&](double u, double v) {
      return std::fmax(0.0, wz - c.ax * u * wx - c.ay * v * wy) * std::exp(-u * u - v * v) / M_PI;
    };
    // Cell integrals by 8x8 Gauss-Legendre on 4x4 sub-cells (the kink line is resolved).
    static const double gx[8] = {-0.9602898564975363, -0.7966664774136267, -0.5255324099163290,
                                 -0.1834346424956498, 0.1834346424956498,  0.5255324099163290,
                                 0.7966664774136267,  0.9602898564975363};
    static const double gw[8] = {0.1012285362903763, 0.2223810344533745, 0.3137066458778873,
                                 0.3626837833783620, 0.3626837833783620, 0.3137066458778873,
                                 0.2223810344533745, 0.1012285362903763};
    std::vector<double> expected(n * n + 1, 0.0), observed(n * n + 1, 0.0);
    double inside = 0;
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        double sum = 0, s = h / 4;
        for (int sj = 0; sj < 4; ++sj)
          for (int si = 0; si < 4; ++si)
            for (int b = 0; b < 8; ++b)
              for (int a = 0; a < 8; ++a) {
                double u = -lim + i * h + (si + 0.5 + 0.5 * gx[a]) * s;
                double v = -lim + j * h + (sj + 0.5 + 0.5 * gx[b]) * s;
                sum += gw[a] * gw[b] * 0.25 * s * s * density(u, v);
              }
        expected[j * n + i] = sum;
        inside += sum;
      }
    // Normalisation 1 / (G1 wo.z): the projected area of visible microfacets, in closed form
    // (Smith, Beckmann): wo.z (1 + Lambda), Lambda = (erf(a) - 1)/2 + exp(-a^2)/(2 a sqrt pi).
    double a = wz / std::sqrt(c.ax * c.ax * wx * wx + c.ay * c.ay * wy * wy);
    double lambda = 0.5 * (std::erf(a) - 1) + std::exp(-a * a) / (2 * a * std::sqrt(M_PI));
    double norm = wz * (1 + lambda);
    for (double& e : expected) e /= norm;
    expected[n * n] = std::fmax(0.0, 1.0 - inside / norm); // tails beyond |u|, |v| > 4.5
    EXPECT_NEAR(inside / norm, 1.0, 1e-5) << "reference normalisation, ax " << c.ax;

    Pcg32 rng(77);
    for (uint64_t k = 0; k < samples; ++k) {
      Vec3 u3 = rng.next_vec3();
      Vec3 m = d.sample_visible_beckmann(c.wo, u3.x, u3.y);
      ASSERT_TRUE(m.z > 0.0f) << "sampled normal below the surface";
      double u = -double(m.x) / (c.ax * m.z), v = -double(m.y) / (c.ay * m.z);
      int i = int(std::floor((u + lim) / h)), j = int(std::floor((v + lim) / h));
      bool in = i >= 0 && i < n && j >= 0 && j < n;
      observed[in ? j * n + i : n * n] += 1;
    }
    double stat = 0, pool_o = 0, pool_e = 0;
    int cells = 0;
    for (size_t k = 0; k < expected.size(); ++k) {
      double e = expected[k] * samples;
      if (e < 5) {
        pool_o += observed[k], pool_e += e;
        continue;
      }
      stat += (observed[k] - e) * (observed[k] - e) / e;
      ++cells;
    }
    if (pool_e > 0) stat += (pool_o - pool_e) * (pool_o - pool_e) / pool_e, ++cells;
    double p = chi2_survival(stat, cells - 1);
    EXPECT_GT(p, 1e-4) << "Beckmann VNDF ax " << c.ax << " ay " << c.ay << " wo.z " << wz
                       << ": chi2 " << stat << " dof " << cells - 1 << ", pooled obs " << pool_o
                       << " exp " << pool_e;
  }
}

} // namespace
