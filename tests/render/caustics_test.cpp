// Caustics of the environment by light paths (integrator.h, PathTracer::trace_light). The light
// paths and the camera's share the caustic paths by MIS weights that sum to one, so in
// expectation the image is the camera's paths' alone: checked block by block against renders
// with the light paths off (an independent estimator of the same integral, which the furnace
// and analytic suites test), with the box and the tent pixel filter (the camera's density,
// and so the weights, hold the filter's). The scene: a smooth glass sphere focusing a sky's
// sun onto a matte floor, beside a plastic sphere (a glossy coat on a diffuse base) that sees
// the caustic on the floor and gets its own through the glass: both of the light paths'
// connections (at the surface the light lands on, and after one bounce more).
// Also: the light paths run only where the scene has such caustics and the options allow (a
// clamp keeps them: they carry the caustics of glass a clamp alone cuts off);
// they cut the error of the caustics at equal samples; the image stays independent of the
// thread count.
#include "render_test_util.h"

#include <vector>

using namespace lobe;
using namespace lobe::render;

namespace {

std::string caustic_scene(bool glass = true) {
  return R"({
  "camera": {"eye": [0, 2.6, 3.2], "look_at": [0, 0.3, 0], "fov": 38},
  "materials": {"floor": {"shader": "matte", "params": {"Cs": 0.8}},
                "glass": {"shader": ")" +
         std::string(glass ? "glass" : "matte") + R"("},
                "coat": {"shader": "plastic", "params": {"Cs": [0.6, 0.5, 0.4], "roughness": 0.3}}},
  "shapes": [{"type": "quad", "corner": [-4, 0, 4], "edge_x": [8, 0, 0], "edge_y": [0, 0, -8],
              "material": "floor"},
             {"type": "sphere", "center": [0.45, 0.55, 0], "radius": 0.45, "material": "glass"},
             {"type": "sphere", "center": [-0.6, 0.35, 0.35], "radius": 0.35, "material": "coat"}],
  "environment": {"type": "sky", "sun_direction": [-0.45, 0.8, -0.35], "sun_size": 20,
                  "resolution": 128}
})";
}

// A closed room lit only through a glass sphere set in a hole of its ceiling: every light path
// into it is a caustic, so the floor under the sphere is the light paths' first connection and
// the walls, lit from the floor, their second.
const char* kLensRoom = R"({
  "camera": {"eye": [0, 0.9, 0.9], "look_at": [0, 0.35, -0.6], "fov": 70},
  "materials": {"wall": {"shader": "matte", "params": {"Cs": 0.8}},
                "glass": {"shader": "glass"}},
  "shapes": [{"type": "quad", "corner": [-1, 0, 1], "edge_x": [2, 0, 0], "edge_y": [0, 0, -2],
              "material": "wall"},
             {"type": "quad", "corner": [-1, 0, -1], "edge_x": [2, 0, 0], "edge_y": [0, 1.5, 0],
              "material": "wall"},
             {"type": "quad", "corner": [-1, 0, 1], "edge_x": [0, 0, -2], "edge_y": [0, 1.5, 0],
              "material": "wall"},
             {"type": "quad", "corner": [1, 0, 1], "edge_x": [0, 0, -2], "edge_y": [0, 1.5, 0],
              "material": "wall"},
             {"type": "quad", "corner": [-1, 0, 1], "edge_x": [2, 0, 0], "edge_y": [0, 1.5, 0],
              "material": "wall"},
             {"type": "quad", "corner": [-1, 1.5, -1], "edge_x": [2, 0, 0], "edge_y": [0, 0, 0.7],
              "material": "wall"},
             {"type": "quad", "corner": [-1, 1.5, 0.3], "edge_x": [2, 0, 0], "edge_y": [0, 0, 0.7],
              "material": "wall"},
             {"type": "quad", "corner": [-1, 1.5, -0.3], "edge_x": [0.7, 0, 0], "edge_y": [0, 0, 0.6],
              "material": "wall"},
             {"type": "quad", "corner": [0.3, 1.5, -0.3], "edge_x": [0.7, 0, 0], "edge_y": [0, 0, 0.6],
              "material": "wall"},
             {"type": "sphere", "center": [0, 1.5, 0], "radius": 0.45, "material": "glass"}],
  "environment": {"type": "sky", "sun_direction": [0.25, 1, 0.15], "sun_size": 25,
                  "resolution": 128}
})";

constexpr int kW = 32, kH = 24;

// Per block of `size` x `size` pixels and channel: the mean over `images` and the standard
// error of that mean from their spread.
struct Blocks {
  std::vector<double> mean, error;
};

Blocks blocks(const std::vector<image::Image>& images, int size) {
  const int bx = kW / size, by = kH / size;
  Blocks b;
  b.mean.assign(size_t(bx) * by * 3, 0);
  b.error.assign(b.mean.size(), 0);
  std::vector<std::vector<double>> per(images.size(), std::vector<double>(b.mean.size(), 0));
  for (size_t i = 0; i < images.size(); ++i)
    for (int y = 0; y < kH; ++y)
      for (int x = 0; x < kW; ++x)
        for (int c = 0; c < 3; ++c)
          per[i][(size_t(y / size) * bx + x / size) * 3 + c] +=
              images[i].pixels[(size_t(y) * kW + x) * images[i].nchannels() + c] /
              double(size * size);
  const double n = double(images.size());
  for (size_t k = 0; k < b.mean.size(); ++k) {
    double s = 0, s2 = 0;
    for (const auto& p : per) s += p[k], s2 += p[k] * p[k];
    b.mean[k] = s / n;
    b.error[k] = std::sqrt(std::max(0.0, s2 / n - b.mean[k] * b.mean[k]) / (n - 1));
  }
  return b;
}

std::vector<image::Image> renders(const RenderScene& s, RenderOptions opt, int seeds,
                                  uint64_t first_seed, uint64_t* light_paths = nullptr) {
  std::vector<image::Image> out;
  for (int i = 0; i < seeds; ++i) {
    opt.seed = first_seed + uint64_t(i);
    auto r = test::render(s, kW, kH, opt);
    if (light_paths) *light_paths += r.stats.counters.light_paths;
    out.push_back(std::move(r.img));
  }
  return out;
}

struct Comparison {
  std::string json;
  scene::PixelFilter filter = scene::PixelFilter::Box;
  float light_paths = 0.5f; // a camera sample
  int max_depth = 8;
  int block = 4; // pixels
};

// Renders with the light paths off (12 seeds of 128 samples) and with them on (12 of 32),
// MIS-weighted or alone, and compares block by block: within 4.5 standard errors, and the
// image's mean within 1%.
void expect_same_image_in_expectation(const Comparison& t) {
  auto s = test::setup_scene(t.json, kW, kH);
  ASSERT_TRUE(s);
  RenderOptions opt;
  opt.pixel_filter = t.filter;
  opt.aovs = false;
  opt.max_depth = t.max_depth;
  opt.spp = 128;
  opt.light_paths = 0;
  Blocks camera = blocks(renders(*s, opt, 12, 100), t.block);
  for (bool alone : {false, true}) {
    opt.spp = 32;
    opt.light_paths = t.light_paths;
    opt.light_paths_only = alone;
    uint64_t traced = 0;
    Blocks both = blocks(renders(*s, opt, 12, 200, &traced), t.block);
    EXPECT_EQ(traced, uint64_t(12 * t.light_paths * 32 * kW * kH));
    double worst = 0, sum_camera = 0, sum_both = 0;
    for (size_t k = 0; k < camera.mean.size(); ++k) {
      double sigma = std::hypot(camera.error[k], both.error[k]) + 1e-4 * camera.mean[k];
      double z = std::abs(both.mean[k] - camera.mean[k]) / sigma;
      worst = std::max(worst, z);
      EXPECT_LT(z, 4.5) << (alone ? "light paths alone" : "MIS") << ": block " << k / 3
                        << " channel " << k % 3 << ": " << both.mean[k] << " with light paths, "
                        << camera.mean[k] << " without";
      sum_camera += camera.mean[k], sum_both += both.mean[k];
    }
    EXPECT_NEAR(sum_both / sum_camera, 1.0, 0.01) << (alone ? "light paths alone" : "MIS");
    testing::Test::RecordProperty(alone ? "worst_z_alone" : "worst_z_mis", std::to_string(worst));
  }
}

} // namespace

TEST(Caustics, LightPathsRunOnlyWhereTheSceneHasCausticsAndTheOptionsAllow) {
  auto s = test::setup_scene(caustic_scene(), kW, kH);
  ASSERT_TRUE(s);
  ASSERT_EQ(s->caustic_targets().size(), 1u); // the glass sphere
  EXPECT_EQ(s->caustic_targets()[0].shape, 1);
  EXPECT_NEAR(s->caustic_targets()[0].radius, 0.45, 0.001);
  RenderOptions opt;
  opt.spp = 2;
  opt.aovs = false;
  EXPECT_EQ(test::render(*s, kW, kH, opt).stats.counters.light_paths, uint64_t(0.1 * 2 * kW * kH));
  opt.light_paths = 0;
  EXPECT_EQ(test::render(*s, kW, kH, opt).stats.counters.light_paths, 0u);
  opt.light_paths = 1;
  opt.clamp = 10; // the camera's share clamped, the light paths' not: they run
  EXPECT_EQ(test::render(*s, kW, kH, opt).stats.counters.light_paths, uint64_t(2 * kW * kH));
  opt.clamp = 0;
  opt.strategy = Strategy::BsdfOnly;
  EXPECT_EQ(test::render(*s, kW, kH, opt).stats.counters.light_paths, 0u);
  // Fewer than one light path in all (0.1 a sample of 2 x 2 pixels at 1 sample): none, and
  // the camera's paths keep the caustics whole (the image is theirs, bit for bit).
  auto tiny = test::setup_scene(caustic_scene(), 2, 2);
  ASSERT_TRUE(tiny);
  opt.spp = 1;
  opt.light_paths = 0.1f;
  auto some = test::render(*tiny, 2, 2, opt);
  EXPECT_EQ(some.stats.counters.light_paths, 0u);
  opt.light_paths = 0;
  auto none = test::render(*tiny, 2, 2, opt);
  EXPECT_EQ(some.img.pixels, none.img.pixels);
  opt.spp = 2;
  // No delta lobes anywhere: no targets, no light paths.
  auto matte = test::setup_scene(caustic_scene(false), kW, kH);
  ASSERT_TRUE(matte);
  EXPECT_TRUE(matte->caustic_targets().empty());
  opt.strategy = Strategy::Mis;
  EXPECT_EQ(test::render(*matte, kW, kH, opt).stats.counters.light_paths, 0u);
}

TEST(Caustics, ImageIsTheCameraPathsInExpectationBoxFilter) {
  expect_same_image_in_expectation({caustic_scene(), scene::PixelFilter::Box});
}

TEST(Caustics, ImageIsTheCameraPathsInExpectationTentFilter) {
  expect_same_image_in_expectation({caustic_scene(), scene::PixelFilter::Tent});
}

// Every path into the room is a caustic: the light paths' second connection (the walls, lit
// from the floor) carries much of the image. At most four bounces, so that every path is one
// of the light paths' two kinds (light bouncing on in the room makes rare bright samples of
// the camera's paths that a test of this size cannot average out), and blocks of 8 pixels.
TEST(Caustics, RoomLitThroughALensInExpectation) {
  expect_same_image_in_expectation({kLensRoom, scene::PixelFilter::Box, 2, 4, 8});
}

TEST(Caustics, LightPathsCutTheErrorAtEqualSamples) {
  auto s = test::setup_scene(caustic_scene(), kW, kH);
  ASSERT_TRUE(s);
  RenderOptions opt;
  opt.aovs = false;
  opt.spp = 2048;
  opt.seed = 7;
  image::Image ref = test::render(*s, kW, kH, opt).img;
  opt.spp = 16;
  double with = 0, without = 0;
  for (uint64_t seed = 1; seed <= 4; ++seed) {
    opt.seed = seed;
    opt.light_paths = 0.1f;
    with += rel_mse(test::render(*s, kW, kH, opt).img, ref);
    opt.light_paths = 0;
    without += rel_mse(test::render(*s, kW, kH, opt).img, ref);
  }
  EXPECT_LT(with, 0.6 * without) << "relMSE at 16 spp, sum of 4 seeds";
}

TEST(Caustics, ThreadCountDoesNotChangeTheImage) {
  auto s = test::setup_scene(caustic_scene(), kW, kH);
  ASSERT_TRUE(s);
  RenderOptions opt;
  opt.pixel_filter = scene::PixelFilter::Tent;
  opt.spp = 8;
  opt.light_paths = 1;
  opt.seed = 3;
  auto a = test::expect_same_bits_on_1_and_2_threads(*s, kW, kH, opt);
  EXPECT_GT(a.stats.counters.splats, 0u);
}

// The light film: a splat's value is shared among pixels by the filter's weights (the box's
// one pixel; the tent's four, (1 - |dx|)(1 - |dy|) about their centres, summing to one), each
// times the light path's power-heuristic weight there, (r/h)^2 / (1 + (r/h)^2) for the ratio r
// of the two techniques' densities at filter weight 1.
TEST(Caustics, LightFilmSharesASplatByFilterAndWeight) {
  LightFilm box(4, 3, scene::PixelFilter::Box);
  box.splat(2.25f, 1.5f, {1, 2, 4});
  EXPECT_NEAR(box.sum(1 * 4 + 2).x, 1, 1e-5);
  EXPECT_NEAR(box.sum(1 * 4 + 2).z, 4, 1e-5);
  EXPECT_EQ(box.sum(1 * 4 + 1).x, 0);
  box.splat(0.5f, 0.5f, {1, 1, 1}, 2.0f); // weight 4 / 5
  EXPECT_NEAR(box.sum(0).y, 0.8, 1e-5);

  LightFilm tent(4, 3, scene::PixelFilter::Tent);
  tent.splat(2.25f, 1.8f, {1, 1, 1}); // centres 1.5 and 2.5 across, 1.5 and 2.5 down
  const double wx[] = {0.25, 0.75}, wy[] = {0.7, 0.3};
  double total = 0;
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 2; ++x) {
      double v = tent.sum(size_t(1 + y) * 4 + size_t(1 + x)).x;
      EXPECT_NEAR(v, wx[x] * wy[y], 1e-5) << x << " " << y;
      total += v;
    }
  EXPECT_NEAR(total, 1, 1e-5);
  LightFilm weighed(4, 3, scene::PixelFilter::Tent);
  weighed.splat(2.25f, 1.8f, {1, 1, 1}, 0.5f);
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 2; ++x) {
      double h = wx[x] * wy[y], q = 0.5 / h;
      EXPECT_NEAR(weighed.sum(size_t(1 + y) * 4 + size_t(1 + x)).x, h * q * q / (1 + q * q), 1e-5);
    }
  // Off the film: nothing, and no fault.
  weighed.splat(-3, 40, {1, 1, 1});
  weighed.splat(NAN, 1, {1, 1, 1});
  // Densities far apart: weights 0 and 1, never NaN; sums saturate, never wrap round.
  LightFilm far(1, 1, scene::PixelFilter::Box);
  far.splat(0.5f, 0.5f, {1, 1, 1}, 1e-30f);
  EXPECT_EQ(far.sum(0).x, 0);
  far.splat(0.5f, 0.5f, {1, 1, 1}, 1e30f);
  EXPECT_NEAR(far.sum(0).x, 1, 1e-6);
  for (int i = 0; i < 4; ++i) far.splat(0.5f, 0.5f, {1e30f, 1e30f, 1e30f});
  EXPECT_GT(far.sum(0).x, 1e12f);
  EXPECT_TRUE(std::isfinite(far.sum(0).x));
}

// Past 64 targets one sphere holds them all (a line's density is then one test): 80 glass
// beads in a row, the sphere round them from the first bead's far side to the last's.
TEST(Caustics, ManyTargetsShareOneSphere) {
  std::string shapes;
  for (int i = 0; i < 80; ++i)
    shapes += R"({"type": "sphere", "center": [)" + std::to_string(-4 + 0.1 * i) +
              R"(, 0.05, 0], "radius": 0.05, "material": "g"},)";
  auto s = test::setup_scene(R"({"camera": {"eye": [0, 2, 3], "look_at": [0, 0, 0], "fov": 40},
    "materials": {"g": {"shader": "glass"}},
    "shapes": [)" + shapes.substr(0, shapes.size() - 1) +
                                 R"(], "environment": {"type": "sky", "resolution": 32}})",
                             kW, kH);
  ASSERT_TRUE(s);
  ASSERT_EQ(s->caustic_targets().size(), 1u);
  EXPECT_EQ(s->caustic_targets()[0].shape, -1);
  EXPECT_NEAR(s->caustic_targets()[0].radius, 0.1 * 80 / 2, 0.01);
  EXPECT_NEAR(s->caustic_targets()[0].center.x, -4 - 0.05 + 0.1 * 80 / 2, 0.01);
  EXPECT_TRUE(s->is_caustic_target(0));
  EXPECT_TRUE(s->is_caustic_target(79));
}

// A clamp keeps the light paths: in the room lit through its lens, where every path is a
// caustic, a clamp of 0.2 alone takes most of the light (the camera's paths reach the sky
// through the glass after two bounces, past the clamp's reach), and with the light paths the
// image stays within 3% of the unclamped one.
TEST(Caustics, AClampLeavesTheLightPathsCaustics) {
  auto s = test::setup_scene(kLensRoom, kW, kH);
  ASSERT_TRUE(s);
  RenderOptions opt;
  opt.aovs = false;
  opt.max_depth = 4;
  opt.spp = 64;
  opt.light_paths = 2;
  auto mean = [&](const RenderOptions& o) {
    double m = 0, e = 0, sum = 0;
    auto r = test::render(*s, kW, kH, o);
    for (int c = 0; c < 3; ++c) test::mean_and_error(r.img, c, m, e), sum += m;
    return sum / 3;
  };
  double unclamped = mean(opt);
  opt.clamp = 0.2f;
  double clamped = mean(opt);
  opt.light_paths = 0;
  double clamped_alone = mean(opt);
  EXPECT_NEAR(clamped / unclamped, 1.0, 0.03) << clamped_alone / unclamped;
  EXPECT_LT(clamped_alone, 0.5 * unclamped);
}
