// Closed-form direct lighting on a Lambertian plane (albedo rho):
//  - point light of intensity I at distance r, angle theta from the normal:
//      L = rho / pi * I cos(theta) / r^2;
//  - a spherical emitter of radiance Le and radius R wholly above the horizon of a point,
//    centre at distance d and angle theta: irradiance pi Le (R/d)^2 cos(theta), so
//      L = rho Le R^2 cos(theta) / d^2 (exact, all three light-transport strategies);
//  - a square emitter of radiance Le parallel to the plane: L = rho Le F, F the view factor
//    of the square from the point (the corner formula, added and subtracted), close above it
//    (0.3) and a centimetre above it (the floor beside a panel, lit at grazing angles).
// The square light's samples themselves are checked against the same view factor (their
// irradiance), and a centimetre from it their weights against its solid angle.
// Expected pixel values average the closed form over a 6x6 grid inside each pixel (the
// renderer jitters uniformly over the pixel), computed here in double precision. Tolerance
// per pixel: 0.5% plus 4 standard errors of the pixel-jitter noise (the spread of the closed
// form inside the pixel over sqrt(spp)); the sphere-light case also checks the image total.
#include "render_test_util.h"

#include <algorithm>
#include <utility>

#include "camera.h"
#include "geometry.h"
#include "lights.h"
#include "sampling.h"

using namespace lobe;
using namespace lobe::render;

namespace {

const int kW = 24, kH = 16;

// Average of f over the plane hits of pixel (x, y); false if any sub-ray misses the plane
// or passes within `exclude` of `sphere_c`.
template <class F>
bool pixel_expectation(const Camera& cam, int x, int y, F f, double& out, Vec3 sphere_c = {},
                       double exclude = 0, double* sd = nullptr) {
  double sum = 0, sum2 = 0;
  for (int j = 0; j < 6; ++j)
    for (int i = 0; i < 6; ++i) {
      Ray r = cam.generate(x + (i + 0.5f) / 6, y + (j + 0.5f) / 6, 0.5f, 0.5f);
      if (exclude > 0) {
        Vec3 oc = sphere_c - r.org;
        double b = dot(oc, r.dir), c = dot(oc, oc) - exclude * exclude;
        if (b * b - c > 0) return false;
      }
      if (r.dir.y >= 0) return false;
      double t = -r.org.y / r.dir.y;
      double v = f(r.org + r.dir * float(t));
      sum += v, sum2 += v * v;
    }
  out = sum / 36;
  if (sd) *sd = std::sqrt(std::max(0.0, sum2 / 36 - out * out));
  return true;
}

// A matte plane (rho 0.6, y = 0) seen from (0, 3, 4), lit only by `light_json` (one entry of
// "lights"), rendered at 64 spp with direct light only; every pixel whose footprint lies on the
// plane must match `radiance` (the closed form at a plane point) within 0.5%, 4 standard
// deviations of the closed form over the pixel, and `floor`. Returns the pixels checked with
// a non-zero and with a zero expectation.
template <class F>
std::pair<int, int> check_lit_plane(const std::string& light_json, F radiance, double floor) {
  const std::string json = R"({
    "camera": {"eye": [0, 3, 4], "look_at": [0, 0, 0], "fov": 50},
    "materials": {"m": {"shader": "matte", "params": {"Cs": 0.6}}},
    "shapes": [{"type": "quad", "corner": [-50, 0, 50], "edge_x": [100, 0, 0],
                "edge_y": [0, 0, -100], "material": "m"}],
    "lights": [)" + light_json +
                           "]}";
  auto s = test::setup_scene(json, kW, kH);
  EXPECT_TRUE(s);
  if (!s) return {0, 0};
  RenderOptions opt;
  opt.spp = 64;
  opt.max_depth = 1;
  auto r = test::render(*s, kW, kH, opt);
  int lit = 0, dark = 0;
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      double expected, sd;
      if (!pixel_expectation(s->camera(), x, y, radiance, expected, {}, 0, &sd)) continue;
      (expected > 0 ? lit : dark)++;
      double tol = 0.005 * expected + 4 * sd / std::sqrt(double(opt.spp)) + floor;
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(r.img.pixel(x, y)[c], expected, tol) << x << "," << y;
    }
  return {lit, dark};
}

} // namespace

TEST(Analytic, LambertPlaneUnderPointLight) {
  const double rho = 0.6, I = 20;
  const Vec3 light{0.5f, 2.0f, -0.3f};
  auto f = [&](const Vec3& p) {
    Vec3 d = light - p;
    double r2 = dot(d, d), cos_t = d.y / std::sqrt(r2);
    return rho / M_PI * I * cos_t / r2;
  };
  auto [lit, dark] =
      check_lit_plane(R"({"type": "point", "position": [0.5, 2, -0.3], "intensity": 20})", f, 0.0);
  EXPECT_GT(lit + dark, kW * kH / 2);
}

// A spot light pointing straight down at a Lambertian plane: inside the cone the closed form
// of the point light, times the smoothstep edge between cone_angle - falloff_angle and
// cone_angle (measured from the spot axis at the light); outside the cone, black.
TEST(Analytic, LambertPlaneUnderSpotLight) {
  const double rho = 0.6, I = 20, cone = 30, falloff = 10;
  const Vec3 light{0.0f, 2.0f, 0.0f};
  auto f = [&](const Vec3& p) {
    Vec3 d = light - p;
    double r2 = dot(d, d), cos_t = d.y / std::sqrt(r2);
    double a = std::acos(std::min(1.0, cos_t)) * 180 / M_PI; // angle from the axis
    double t =
        std::clamp((std::cos(a * M_PI / 180) - std::cos(cone * M_PI / 180)) /
                       (std::cos((cone - falloff) * M_PI / 180) - std::cos(cone * M_PI / 180)),
                   0.0, 1.0);
    return rho / M_PI * I * cos_t / r2 * t * t * (3 - 2 * t);
  };
  // (floor 1e-4: a pixel straddling the cone edge whose 6x6 grid of points all fall outside.)
  auto [inside, outside] = check_lit_plane(
      R"({"type": "spot", "position": [0, 2, 0], "look_at": [0, 0, 0], "intensity": 20,
          "cone_angle": 30, "falloff_angle": 10})",
      f, 1e-4);
  EXPECT_GT(inside, 20);
  EXPECT_GT(outside, 20);
}

class SphereLight : public ::testing::TestWithParam<Strategy> {};

TEST_P(SphereLight, LambertPlaneUnderSphericalEmitter) {
  const double rho = 0.5, Le = 4, R = 0.3;
  const Vec3 c{0, 1.2f, 0};
  const std::string json = R"({
    "camera": {"eye": [0, 2.5, 4], "look_at": [0, 0, 0], "fov": 45},
    "materials": {"m": {"shader": "matte", "params": {"Cs": 0.5}},
                  "e": {"shader": "emitter", "params": {"power": 4}}},
    "shapes": [{"type": "quad", "corner": [-50, 0, 50], "edge_x": [100, 0, 0],
                "edge_y": [0, 0, -100], "material": "m"},
               {"type": "sphere", "center": [0, 1.2, 0], "radius": 0.3, "material": "e"}]
  })";
  auto s = test::setup_scene(json, kW, kH);
  ASSERT_TRUE(s);
  RenderOptions opt;
  // BSDF sampling finds the small emitter rarely: many more samples for the same noise.
  opt.spp = GetParam() == Strategy::BsdfOnly ? 2048 : 128;
  opt.max_depth = 1;
  opt.strategy = GetParam();
  auto r = test::render(*s, kW, kH, opt);
  // Compare the image mean over checked pixels (noise averages out) and each pixel loosely.
  double sum_e = 0, sum_r = 0;
  int checked = 0;
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      double expected;
      auto f = [&](const Vec3& p) {
        Vec3 d = c - p;
        double d2 = dot(d, d), cos_t = d.y / std::sqrt(d2);
        return rho * Le * R * R * cos_t / d2;
      };
      if (!pixel_expectation(s->camera(), x, y, f, expected, c, R * 1.5)) continue;
      ++checked;
      sum_e += expected;
      sum_r += r.img.pixel(x, y)[1];
      if (GetParam() != Strategy::BsdfOnly) {
        EXPECT_NEAR(r.img.pixel(x, y)[1], expected, 0.25 * expected + 0.01) << x << "," << y;
      }
    }
  ASSERT_GT(checked, kW * kH / 2);
  EXPECT_NEAR(sum_r / sum_e, 1.0, GetParam() == Strategy::BsdfOnly ? 0.04 : 0.02);
}

INSTANTIATE_TEST_SUITE_P(Strategies, SphereLight,
                         ::testing::Values(Strategy::Mis, Strategy::LightOnly, Strategy::BsdfOnly));

namespace {

// View factor from a point to the rectangle [0, a] x [0, b] of a parallel plane at height h
// above the corner (the classic corner formula; odd in a and in b, so rectangles anywhere in
// the plane add and subtract corner pieces):
// F = 1/(2 pi) [A/sqrt(1+A^2) atan(B/sqrt(1+A^2)) + B/sqrt(1+B^2) atan(A/sqrt(1+B^2))].
double corner_view_factor(double a, double b, double h) {
  double A = a / h, B = b / h, sa = std::sqrt(1 + A * A), sb = std::sqrt(1 + B * B);
  return (A / sa * std::atan(B / sa) + B / sb * std::atan(A / sb)) / (2 * kPi);
}

// The view factor of the square [-r, r]^2 of a parallel plane at height h from (x, z).
double square_view_factor(double r, double x, double z, double h) {
  return corner_view_factor(r - x, r - z, h) - corner_view_factor(-r - x, r - z, h) -
         corner_view_factor(r - x, -r - z, h) + corner_view_factor(-r - x, -r - z, h);
}

// A square light [-0.25, 0.25]^2 at y = 1 (testrender's Cornell box has one a centimetre
// under its ceiling), in a LightSet of its own.
struct SquareLight {
  std::vector<scene::Shape> shapes;
  Geometry geo;
  LightSet lights;
  SquareLight() {
    scene::Shape q;
    q.kind = scene::Shape::Kind::Quad;
    q.corner = {-0.25f, 1, -0.25f};
    q.edge_x = {0.5f, 0, 0};
    q.edge_y = {0, 0, 0.5f};
    shapes.push_back(q);
    EXPECT_EQ(geo.build(shapes), "");
    lights.build(geo, {}, {{0, 1}}, nullptr);
  }
};

} // namespace

TEST(AreaLightSampling, IrradianceOfASquareIsTheViewFactorsClosedForm) {
  // From points under the light (centre, beside it, far off to the side) and a centimetre
  // above it (its back): the mean of cos / pdf over samples is the irradiance of a unit
  // radiance, pi F; pdf_area() gives back each sample's density. The point 101 away is
  // sampled by area (lights.h), the others by solid angle.
  SquareLight s;
  struct Case {
    Vec3 p, n;
  } cases[] = {{{0, 0.99f, 0}, {0, 1, 0}},       {{0.1f, 0.99f, 0.2f}, {0, 1, 0}},
               {{0.6f, 0.9f, -0.1f}, {0, 1, 0}}, {{0, 0, 0}, {0, 1, 0}},
               {{0.1f, -100, 0.05f}, {0, 1, 0}}, {{0.05f, 1.01f, 0}, {0, -1, 0}}};
  RandomStream rng(3, 0, 9);
  for (const Case& c : cases) {
    double expected = kPi * square_view_factor(0.25, c.p.x, c.p.z, std::abs(1.0 - c.p.y));
    const int n = 20000;
    double sum = 0, sum2 = 0;
    for (int i = 0; i < n; ++i) {
      LightSample ls;
      ASSERT_TRUE(s.lights.sample(c.p, c.n, rng.next(), rng.next(), rng.next(), ls));
      ASSERT_EQ(ls.kind, LightSample::Kind::Area);
      EXPECT_NEAR(s.lights.pdf_area(c.p, ls.surface), ls.pdf, 1e-4 * ls.pdf);
      double v = std::max(0.0f, dot(c.n, ls.wi)) / ls.pdf;
      sum += v, sum2 += v * v;
    }
    double mean = sum / n, se = std::sqrt(std::max(0.0, sum2 / n - mean * mean) / n);
    EXPECT_NEAR(mean, expected, 4.5 * se + 1e-6 * expected) << c.p.x << "," << c.p.y;
  }
}

TEST(AreaLightSampling, WeightsStayBelowTheSolidAngleCloseToALight) {
  // A centimetre from the light, sampling by area gives weights cos cos' A / d^2 up to 2500
  // (A = 0.25, d = 0.01); by solid angle each weight cos / pdf is at most the solid angle.
  SquareLight s;
  RandomStream rng(5, 0, 1);
  for (Vec3 p : {Vec3{0, 1.01f, 0}, Vec3{0.2f, 0.99f, 0.2f}, Vec3{0.3f, 1.002f, 0}}) {
    Vec3 n{0, p.y > 1 ? -1.0f : 1.0f, 0};
    double omega = 0;
    float max_w = 0;
    for (int i = 0; i < 4000; ++i) {
      LightSample ls;
      ASSERT_TRUE(s.lights.sample(p, n, rng.next(), rng.next(), rng.next(), ls));
      omega = 1 / double(ls.pdf);
      max_w = std::max(max_w, std::max(0.0f, dot(n, ls.wi)) / ls.pdf);
    }
    EXPECT_LE(max_w, omega * (1 + 1e-5));
    EXPECT_LE(omega, 2 * kPi);
  }
}

namespace {

// A matte plane (rho 0.5, y = 0) lit only by a square emitter of radiance Le = 4, the square
// [-half, half]^2 at `height`, seen by `camera` (JSON), direct light only, `spp` samples by
// `strategy`. Every pixel whose footprint lies on the plane and passes no nearer than `clear`
// to the emitter's centre must match L = rho Le F (F: square_view_factor) within 10%, 4
// standard deviations of L over the pixel and `floor` (BSDF sampling alone: the sum only);
// the checked pixels' sum within `sum_tol`.
void check_square_light(const std::string& camera, float half, float height, float clear, int spp,
                        Strategy strategy, double floor, double sum_tol) {
  const double rho = 0.5, Le = 4;
  const std::string json = R"({"camera": )" + camera + R"(,
    "materials": {"m": {"shader": "matte", "params": {"Cs": 0.5}},
                  "e": {"shader": "emitter", "params": {"power": 4}}},
    "shapes": [{"type": "quad", "corner": [-50, 0, 50], "edge_x": [100, 0, 0],
                "edge_y": [0, 0, -100], "material": "m"},
               {"type": "quad", "corner": [)" +
                           std::to_string(-half) + ", " + std::to_string(height) + ", " +
                           std::to_string(-half) + R"(], "edge_x": [)" + std::to_string(2 * half) +
                           R"(, 0, 0],
                "edge_y": [0, 0, )" +
                           std::to_string(2 * half) +
                           R"(], "material": "e"}]
  })";
  auto s = test::setup_scene(json, kW, kH);
  ASSERT_TRUE(s);
  RenderOptions opt;
  opt.spp = spp;
  opt.max_depth = 1;
  opt.strategy = strategy;
  auto r = test::render(*s, kW, kH, opt);
  auto f = [&](const Vec3& p) { return rho * Le * square_view_factor(half, p.x, p.z, height); };
  double sum_e = 0, sum_r = 0;
  int checked = 0;
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      double expected, sd;
      if (!pixel_expectation(s->camera(), x, y, f, expected, {0, height, 0}, clear, &sd)) continue;
      ++checked;
      sum_e += expected;
      sum_r += r.img.pixel(x, y)[1];
      double tol = 0.1 * expected + 4 * sd / std::sqrt(double(spp)) + floor;
      if (strategy != Strategy::BsdfOnly) {
        EXPECT_NEAR(r.img.pixel(x, y)[1], expected, tol) << x << "," << y;
      }
    }
  ASSERT_GT(checked, kW * kH / 2);
  EXPECT_NEAR(sum_r / sum_e, 1.0, sum_tol);
}

} // namespace

class QuadLight : public ::testing::TestWithParam<Strategy> {};

// A square emitter (side 1) 0.3 above the plane, close enough that sampling it by area would
// spread its weights over three orders of magnitude.
TEST_P(QuadLight, LambertPlaneUnderSquareEmitter) {
  bool bsdf = GetParam() == Strategy::BsdfOnly;
  check_square_light(R"({"eye": [0, 2.5, 4], "look_at": [0, 0, 0], "fov": 45})", 0.5f, 0.3f, 0.75f,
                     bsdf ? 1024 : 128, GetParam(), 0.005, bsdf ? 0.03 : 0.01);
}

// The floor beside a light panel a centimetre above it, seen from above: lit through the
// panel's underside at grazing angles. A shadow ray aimed from the floor point itself rather
// than from its offset origin meets the panel's plane short of the sampled point and the
// panel shadows itself (lights alone: the floor came out black there; with MIS, too dark).
// BSDF sampling alone finds the panel too rarely here for a test of this size (and casts no
// shadow rays).
class GrazingQuadLight : public ::testing::TestWithParam<Strategy> {};

TEST_P(GrazingQuadLight, FloorBesideAPanelJustAboveIt) {
  check_square_light(R"({"eye": [0, 3, 0], "look_at": [0, 0, 0], "up": [0, 0, -1], "fov": 40})",
                     0.25f, 0.01f, 0.36f, 256, GetParam(), 1e-4, 0.02);
}

INSTANTIATE_TEST_SUITE_P(Strategies, QuadLight,
                         ::testing::Values(Strategy::Mis, Strategy::LightOnly, Strategy::BsdfOnly));
INSTANTIATE_TEST_SUITE_P(Strategies, GrazingQuadLight,
                         ::testing::Values(Strategy::Mis, Strategy::LightOnly));
