// Environment table: the direction mapping round-trips, the sampling pdf integrates to one
// over the sphere and matches sample(), and Monte Carlo estimates of the irradiance of a
// known environment are right.
#include "environment.h"
#include "sampling.h"
#include "sky.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace lobe;
using namespace lobe::render;

namespace {
EnvironmentLight gradient_env(float rotation) {
  // Radiance 1 + 3 * max(y, 0)^2: bright towards +Y.
  return EnvironmentLight::from_function(
      [](const Vec3& d) {
        float k = 1 + 3 * std::max(d.y, 0.0f) * std::max(d.y, 0.0f);
        return Color3{k, k * 0.5f, 0.25f};
      },
      64, 32, rotation);
}
} // namespace

TEST(Environment, UvMappingRoundTrips) {
  EnvironmentLight env = gradient_env(30);
  RandomStream s(0, 0, 0);
  for (int i = 0; i < 200; ++i) {
    Vec3 d = square_to_uniform_sphere(s.next(), s.next());
    float u, v;
    env.dir_to_uv(d, u, v);
    Vec3 back = env.uv_to_dir(u, v);
    EXPECT_NEAR(dot(back, d), 1.0f, 1e-5);
  }
  // Row 0 is straight up; the image centre looks down -Z (without rotation).
  EnvironmentLight plain = gradient_env(0);
  EXPECT_NEAR(plain.uv_to_dir(0.3f, 0.0f).y, 1.0f, 1e-6);
  Vec3 c = plain.uv_to_dir(0.5f, 0.5f);
  EXPECT_NEAR(c.z, -1.0f, 1e-6);
}

TEST(Environment, PdfIntegratesToOneAndMatchesSample) {
  EnvironmentLight env = gradient_env(10);
  // Uniform-sphere Monte Carlo of the pdf's integral.
  RandomStream s(5, 0, 0);
  double sum = 0;
  const int n = 200000;
  for (int i = 0; i < n; ++i) sum += env.pdf(square_to_uniform_sphere(s.next(), s.next()));
  EXPECT_NEAR(sum / n * 4 * M_PI, 1.0, 0.01);
  for (int i = 0; i < 500; ++i) {
    float pdf;
    Vec3 d = env.sample(s.next(), s.next(), pdf);
    ASSERT_GT(pdf, 0);
    EXPECT_NEAR(env.pdf(d), pdf, 2e-3 * pdf);
  }
}

TEST(Environment, TableSampleWithNormalReturnsTheTexelAndEvalPdfAgrees) {
  EnvironmentLight env = gradient_env(25);
  const Vec3 n{0, 1, 0};
  RandomStream s(2, 7, 3);
  for (int i = 0; i < 500; ++i) {
    float p, q;
    Color3 L;
    Vec3 d = env.sample(n, s.next(), s.next(), p, L);
    ASSERT_GT(p, 0);
    EXPECT_NEAR(env.pdf(d, n), p, 2e-3 * p);
    Color3 e = env.eval_pdf(d, n, q);
    EXPECT_FLOAT_EQ(q, env.pdf(d, n));
    EXPECT_FLOAT_EQ(e.x, env.eval(d).x);
    // The texel sampled is the one the direction maps back to (up to texel-edge rounding).
    EXPECT_NEAR(L.x, e.x, 0.05f * e.x);
  }
}

TEST(Environment, ImportanceSampledIrradianceMatchesClosedForm) {
  // Irradiance at an upward-facing point: integral over the upper hemisphere of
  // (1 + 3 cos^2) cos dw = pi + 3 * 2pi/4 = 2.5 pi (red channel).
  EnvironmentLight env = gradient_env(0);
  RandomStream s(9, 0, 0);
  double sum = 0;
  const int n = 100000;
  for (int i = 0; i < n; ++i) {
    float pdf;
    Vec3 d = env.sample(s.next(), s.next(), pdf);
    if (d.y > 0 && pdf > 0) sum += env.eval(d).x * d.y / pdf;
  }
  // The table is piecewise constant over 64x32 texels: allow 1.5% for tabulation.
  EXPECT_NEAR(sum / n, 2.5 * M_PI, 0.015 * 2.5 * M_PI);
}

TEST(Environment, OrientedTablesIntegrateToOneAndMatchTheirSamples) {
  // For normals along each axis (the tight tables), tilted ones (the 26 directions' wide
  // tables) and none: the light-sample density integrates to one over the sphere, each sample
  // reports the density pdf(d, n) gives at its direction, and no sample lies far behind the
  // surface (the wide tables reach 90 + 28 degrees from their direction, itself within 28 of
  // the normal; cells add up to one row of 11.25 degrees here).
  EnvironmentLight env = gradient_env(30);
  const Vec3 normals[] = {{1, 0, 0},
                          {-1, 0, 0},
                          {0, 1, 0},
                          {0, -1, 0},
                          {0, 0, 1},
                          {0, 0, -1},
                          {0.6f, 0.8f, 0},
                          {-0.48f, 0.6f, -0.64f},
                          normalize(Vec3{0.05f, 1, 0.02f}),
                          {0, 0, 0}};
  RandomStream s(4, 2, 9);
  for (const Vec3& n : normals) {
    SCOPED_TRACE(testing::Message() << "n = " << n.x << " " << n.y << " " << n.z);
    double sum = 0;
    const int n_mc = 200000;
    for (int i = 0; i < n_mc; ++i) sum += env.pdf(square_to_uniform_sphere(s.next(), s.next()), n);
    EXPECT_NEAR(sum / n_mc * 4 * M_PI, 1.0, 0.02);
    int behind = 0, off = 0;
    for (int i = 0; i < 2000; ++i) {
      float p;
      Color3 L;
      Vec3 d = env.sample(n, s.next(), s.next(), p, L);
      ASSERT_GT(p, 0);
      // The direction maps back into the sampled cell but for rounding at a cell's edge.
      off += !(std::abs(env.pdf(d, n) - p) <= 2e-3f * p);
      behind += dot(d, n) < -std::sin(float(M_PI) * (56 + 12) / 180);
    }
    EXPECT_LE(off, 10); // 0.5%
    EXPECT_EQ(behind, is_zero(n) ? behind : 0);
  }
}

TEST(Environment, OrientedLightSamplesKeepTheEstimateAndCutItsVariance) {
  // Irradiance at a point from the gradient environment (red: 1 + 3 cos^2, so 2.5 pi over the
  // upper hemisphere for an upward normal, as above), estimated as the renderer does: one
  // light sample and one cosine-weighted direction, combined by the power heuristic. The light
  // samples come from the normal's oriented table (for +Y the tight one, for a tilted normal
  // a wide one) or the whole-sphere table (a zero normal): the estimates agree, and the
  // oriented ones have less variance (the whole-sphere table spends about half its samples
  // behind the surface).
  EnvironmentLight env = gradient_env(0);
  auto estimate = [&](const Vec3& n, const Vec3& n_light, double& mean, double& var) {
    RandomStream s(6, 3, 2);
    double sum = 0, sum2 = 0;
    const int n_mc = 200000;
    for (int i = 0; i < n_mc; ++i) {
      double x = 0;
      float pl;
      Color3 L;
      Vec3 d = env.sample(n_light, s.next(), s.next(), pl, L);
      if (float c = dot(d, n); pl > 0 && c > 0)
        x += L.x * c / pl * power_heuristic(pl, c / float(M_PI));
      Vec3 b = Frame(n).to_world(sample_cosine_hemisphere(s.next(), s.next()));
      float pb = dot(b, n) / float(M_PI);
      if (pb > 0) x += env.eval(b).x * dot(b, n) / pb * power_heuristic(pb, env.pdf(b, n_light));
      sum += x, sum2 += x * x;
    }
    mean = sum / n_mc;
    var = sum2 / n_mc - mean * mean;
  };
  for (const Vec3& n : {Vec3{0, 1, 0}, normalize(Vec3{0.5f, 0.7f, -0.3f})}) {
    SCOPED_TRACE(testing::Message() << "n = " << n.x << " " << n.y << " " << n.z);
    double m_axis, v_axis, m_sphere, v_sphere;
    estimate(n, n, m_axis, v_axis);
    estimate(n, Vec3{}, m_sphere, v_sphere);
    // The table is piecewise constant over 64x32 texels: 1.5% for tabulation, as above.
    if (n.y == 1) {
      EXPECT_NEAR(m_axis, 2.5 * M_PI, 0.015 * 2.5 * M_PI);
      EXPECT_NEAR(m_sphere, 2.5 * M_PI, 0.015 * 2.5 * M_PI);
    }
    EXPECT_NEAR(m_axis, m_sphere, 0.005 * m_sphere);
    // A wide table's cone is broad (28 degrees): less gain than an axis' tight one, still some.
    EXPECT_LT(v_axis, (n.y == 1 ? 0.5 : 0.9) * v_sphere) << v_axis / v_sphere;
    // And it leaves no direction above the surface without light samples: none is left to
    // the BSDF's samples alone.
    RandomStream s(1, 1, 1);
    int holes = 0;
    for (int i = 0; i < 20000; ++i) {
      Vec3 d = square_to_uniform_sphere(s.next(), s.next());
      holes += dot(d, n) > 0.01f && !(env.pdf(d, n) > 0);
    }
    EXPECT_EQ(holes, 0);
  }
}

TEST(Environment, ConstantIsExact) {
  // A constant table of 64 x 32 texels: near the equator the pdf is uniform over the sphere up
  // to the sin(theta) variation inside one row (a fraction of a percent).
  EnvironmentLight env(std::vector<float>(64 * 32 * 3, 0.5f), 64, 32, 0);
  EXPECT_TRUE(env.is_constant());
  EXPECT_NEAR(env.pdf(normalize(Vec3{0.3f, 0.01f, 0.8f})), 1 / (4 * M_PI), 2e-3 / (4 * M_PI));
  EXPECT_FLOAT_EQ(env.eval({1, 0, 0}).y, 0.5f);
}

TEST(Environment, ConstantSamplerPdfsAreClosedFormsAndIntegrateToOne) {
  // The constant fast path: uniform over the sphere without a normal (pdf 1/(4 pi)), cosine-
  // weighted about a normal n with one (pdf max(cos, 0)/pi); both integrate to one and the pdf
  // each sample reports is the closed form at its direction.
  EnvironmentLight env(std::vector<float>(3, 0.7f), 1, 1, 0);
  ASSERT_TRUE(env.is_constant());
  const Vec3 n = normalize(Vec3{0.3f, -0.5f, 0.8f});
  RandomStream s(3, 1, 4);
  double sum_u = 0, sum_c = 0, above = 0;
  const int n_mc = 200000;
  for (int i = 0; i < n_mc; ++i) {
    Vec3 d = square_to_uniform_sphere(s.next(), s.next()); // Monte Carlo over the sphere
    sum_u += env.pdf(d);
    sum_c += env.pdf(d, n);
  }
  EXPECT_NEAR(sum_u / n_mc * 4 * M_PI, 1.0, 1e-6);
  EXPECT_NEAR(sum_c / n_mc * 4 * M_PI, 1.0, 0.01); // cos/pi over the sphere: standard error 0.4%
  double cos_sum = 0;
  for (int i = 0; i < 20000; ++i) {
    float pu, pc;
    Vec3 du = env.sample(s.next(), s.next(), pu);
    EXPECT_NEAR(length(du), 1.0f, 1e-5);
    EXPECT_FLOAT_EQ(pu, float(1 / (4 * M_PI)));
    Color3 L;
    Vec3 dc = env.sample(n, s.next(), s.next(), pc, L);
    EXPECT_FLOAT_EQ(L.y, 0.7f);
    EXPECT_NEAR(length(dc), 1.0f, 1e-5);
    float c = dot(dc, n);
    above += c >= 0;
    cos_sum += c;
    EXPECT_NEAR(pc, std::max(c, 0.0f) / M_PI, 1e-5);
    EXPECT_NEAR(env.pdf(dc, n), pc, 1e-6);
  }
  EXPECT_EQ(above, 20000); // never below the surface
  // E[cos] under the cosine density: integral of cos^2/pi over the hemisphere = 2/3.
  EXPECT_NEAR(cos_sum / 20000, 2.0 / 3.0, 0.01);
  EXPECT_FLOAT_EQ(env.eval(normalize(Vec3{-1, 2, 3})).x, 0.7f);
}

TEST(Environment, ConstantIrradianceIsPiTimesRadiance) {
  // Irradiance of a constant radiance L on a surface: pi L, estimated from either sampler.
  EnvironmentLight env(std::vector<float>(3, 0.7f), 1, 1, 0);
  const Vec3 n = normalize(Vec3{-0.2f, 0.9f, 0.1f});
  RandomStream s(8, 2, 1);
  double sum_u = 0, sum_c = 0;
  const int n_mc = 100000;
  for (int i = 0; i < n_mc; ++i) {
    float p;
    Vec3 d = env.sample(s.next(), s.next(), p);
    sum_u += env.eval(d).x * std::max(0.0f, dot(d, n)) / p;
    Color3 L;
    d = env.sample(n, s.next(), s.next(), p, L);
    if (p > 0) sum_c += L.x * dot(d, n) / p;
  }
  EXPECT_NEAR(sum_u / n_mc, M_PI * 0.7, 0.01 * M_PI * 0.7);
  // Cosine sampling cancels the cosine: every sample is exactly pi L.
  EXPECT_NEAR(sum_c / n_mc, M_PI * 0.7, 1e-4);
}

TEST(Sky, SunDiskDeliversItsIrradiance) {
  // Integrate the sky's luminance times cos over the sun's cone: the disk gives kSunIrradiance.
  Vec3 sun = normalize(Vec3{0.3f, 0.8f, 0.2f});
  float diam = 2.0f, cos_r = std::cos(0.5f * diam * float(M_PI) / 180);
  Frame f(sun);
  RandomStream s(1, 1, 1);
  double sum = 0;
  const int n = 20000;
  for (int i = 0; i < n; ++i) {
    Vec3 d = f.to_world(square_to_uniform_cone(s.next(), s.next(), cos_r));
    sum += luminance(procedural_sky(d, sun, diam)) * dot(d, sun);
  }
  double solid = 2 * M_PI * (1 - cos_r);
  // The glow adds a little on top of the disk: at most a few percent.
  EXPECT_GT(sum / n * solid, kSunIrradiance * 0.99);
  EXPECT_LT(sum / n * solid, kSunIrradiance * 1.05);
}
