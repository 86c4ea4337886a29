// Closed-form direct lighting on a Lambertian plane (albedo rho):
//  - point light of intensity I at distance r, angle theta from the normal:
//      L = rho / pi * I cos(theta) / r^2;
//  - a spherical emitter of radiance Le and radius R wholly above the horizon of a point,
//    centre at distance d and angle theta: irradiance pi Le (R/d)^2 cos(theta), so
//      L = rho Le R^2 cos(theta) / d^2 (exact, all three light-transport strategies).
// Expected pixel values average the closed form over a 6x6 grid inside each pixel (the
// renderer jitters uniformly over the pixel), computed here in double precision. Tolerance
// per pixel: 0.5% plus 4 standard errors of the pixel-jitter noise (the spread of the closed
// form inside the pixel over sqrt(spp)); the sphere-light case also checks the image total.
#include "render_test_util.h"

#include <algorithm>
#include <utility>

#include "camera.h"

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
