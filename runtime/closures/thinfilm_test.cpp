// Thin-film Fresnel (fresnel_thin_film and the thinfilm_* keywords): thickness 0 is exactly
// the film-less lobe; closed forms (quarter- and half-wave layers at normal incidence, a film
// matching the substrate); an independent std::complex<double> Airy reference at oblique
// incidence on a conductor; energy (reflection + transmission = 1) for a dielectric.
#include "closures.h"
#include "fresnel.h"
#include "test_util.h"

#include <gtest/gtest.h>

#include <cmath>
#include <complex>

namespace lobe::closures {
namespace {

using cd = std::complex<double>;

// Airy reflectance of ambient n1 / film (n2, d) / substrate n3 for one polarisation, double.
double airy_ref(double c1, double n1, double n2, cd n3, double d, double lambda, bool p_pol) {
  double s2 = n1 * n1 * (1 - c1 * c1);
  cd c2 = std::sqrt(cd(1.0) - s2 / (n2 * n2)), c3 = std::sqrt(cd(1.0) - s2 / (n3 * n3));
  auto r = [&](cd na, cd ca, cd nb, cd cb) {
    return p_pol ? (nb * ca - na * cb) / (nb * ca + na * cb)
                 : (na * ca - nb * cb) / (na * ca + nb * cb);
  };
  cd r12 = r(n1, c1, n2, c2), r23 = r(n2, c2, n3, c3);
  cd e = std::exp(cd(0, 1) * (4 * M_PI * n2 * d / lambda) * c2);
  return std::norm((r12 + r23 * e) / (1.0 + r12 * r23 * e));
}
double airy_unpolarised(double c1, double n1, double n2, cd n3, double d, double lambda) {
  return 0.5 *
         (airy_ref(c1, n1, n2, n3, d, lambda, false) + airy_ref(c1, n1, n2, n3, d, lambda, true));
}

TEST(ThinFilm, QuarterAndHalfWaveClosedForms) {
  // Normal incidence on glass (1.5): a quarter-wave layer of index sqrt(1.5) at 550 nm cancels
  // reflection, R = ((n1 n3 - n2^2)/(n1 n3 + n2^2))^2 = 0; a half-wave layer is absent,
  // R = ((1 - 1.5)/(1 + 1.5))^2 = 0.04.
  float n2 = std::sqrt(1.5f);
  EXPECT_NEAR(fresnel_thin_film(1.0f, 1.0f, n2, {1.5f, 0.0f}, 550.0f / (4 * n2), 550.0f), 0.0f,
              1e-6f);
  EXPECT_NEAR(fresnel_thin_film(1.0f, 1.0f, 2.0f, {1.5f, 0.0f}, 550.0f / (2 * 2.0f), 550.0f), 0.04f,
              1e-5f);
  // Quarter wave of index 2 on glass: ((1.5 - 4)/(1.5 + 4))^2.
  EXPECT_NEAR(fresnel_thin_film(1.0f, 1.0f, 2.0f, {1.5f, 0.0f}, 550.0f / 8.0f, 550.0f),
              std::pow(2.5 / 5.5, 2), 1e-5);
  // A film with the substrate's index is invisible at any angle and thickness.
  for (float c : {0.2f, 0.7f, 1.0f})
    EXPECT_NEAR(fresnel_thin_film(c, 1.0f, 1.5f, {1.5f, 0.0f}, 333.0f, 450.0f),
                fresnel_dielectric(c, 1.5f), 1e-6f);
}

TEST(ThinFilm, MatchesDoubleReferenceOnConductorAndFromInside) {
  for (double c : {0.9, 0.5, 0.15})
    for (double d : {120.0, 380.0}) {
      cd gold(0.47, 2.83);
      EXPECT_NEAR(fresnel_thin_film(float(c), 1.0f, 1.33f, {0.47f, 2.83f}, float(d), 550.0f),
                  airy_unpolarised(c, 1.0, 1.33, gold, d, 550.0), 2e-4)
          << c << " " << d;
      // From inside glass (1.5) through a 1.33 film into air, including total internal reflection.
      EXPECT_NEAR(fresnel_thin_film(float(c), 1.5f, 1.33f, {1.0f, 0.0f}, float(d), 650.0f),
                  airy_unpolarised(c, 1.5, 1.33, cd(1.0), d, 650.0), 2e-4)
          << c << " " << d;
    }
}

TEST(ThinFilm, ZeroThicknessIsExactlyTheFilmlessLobe) {
  for (const char* key : {"dielectric_bsdf", "conductor_bsdf", "generalized_schlick_bsdf"}) {
    Params a(key), b(key);
    a.set("roughness_x", 0.3f).set("roughness_y", 0.3f);
    b.set("roughness_x", 0.3f).set("roughness_y", 0.3f).set("thinfilm_ior", 1.9f);
    b.set("thinfilm_thickness", 0.0f);
    for (double mo : {0.8, -0.5})
      for (double mi : {0.6, -0.3}) {
        Vec3 wo = test::dir_cos(mo, 0.1), wi = test::dir_cos(mi, 2.9);
        BsdfEval ea = eval(a.id(), a.data(), wo, wi), eb = eval(b.id(), b.data(), wo, wi);
        EXPECT_EQ(ea.value, eb.value) << key;
        EXPECT_EQ(ea.pdf, eb.pdf) << key;
      }
  }
}

TEST(ThinFilm, SmoothDielectricUsesFilmFresnelAndConservesEnergy) {
  // A smooth dielectric with a film: the mirror weight is the film reflectance per channel
  // (650/550/450 nm) and reflection + transmission (importance) is 1.
  Params p("dielectric_bsdf");
  p.set("ior", 1.5f).set("thinfilm_thickness", 300.0f).set("thinfilm_ior", 1.33f);
  Vec3 wo = test::dir_cos(0.6, 0.0);
  auto r = sample(p.id(), p.data(), wo, {0.5f, 0.5f, 0.0f}, Transport::Importance);
  auto t = sample(p.id(), p.data(), wo, {0.5f, 0.5f, 0.999f}, Transport::Importance);
  ASSERT_TRUE(r && t);
  ASSERT_TRUE(r->wi.z > 0 && t->wi.z < 0);
  const float lambda[3] = {650, 550, 450};
  for (int ch = 0; ch < 3; ++ch) {
    double R = airy_unpolarised(0.6, 1.0, 1.33, cd(1.5), 300.0, lambda[ch]);
    EXPECT_NEAR((&r->weight.x)[ch] * r->pdf, R, 1e-4) << ch;
    EXPECT_NEAR((&t->weight.x)[ch] * t->pdf, 1.0 - R, 1e-4) << ch;
  }
}

} // namespace
} // namespace lobe::closures
