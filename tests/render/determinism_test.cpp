// Determinism and convergence:
//  - the image depends only on scene, samples and seed: 1 and 2 threads give identical bits;
//  - a different seed gives a different image (the seed is used);
//  - consistency: relMSE against a converged reference falls at least as fast as 1/N, so
//    doubling the samples at least halves it (ratio above 1.5, averaged over 4 seeds to tame the
//    noise of the estimate). Paths draw Owen-scrambled Sobol numbers, whose error falls faster
//    than independent sampling's where the integrand is smooth in the stratified dimensions (up
//    to N^-1.5 in relMSE for a 2-D one: a ratio of 2.8); above 4 would mean the reference and the
//    renders share samples.
#include "render_test_util.h"

#include <cstring>

using namespace lobe;
using namespace lobe::render;

namespace {

// A small scene with every kind of light: sky, point, spot and an emissive quad.
const char* kScene = R"({
  "camera": {"eye": [0, 1.5, 4], "look_at": [0, 0.5, 0], "fov": 40},
  "materials": {"floor": {"shader": "matte", "params": {"Cs": 0.7}},
                "ball": {"shader": "matte", "params": {"Cs": [0.8, 0.3, 0.2]}},
                "lamp": {"shader": "emitter", "params": {"power": 3}}},
  "shapes": [{"type": "quad", "corner": [-5, 0, 5], "edge_x": [10, 0, 0], "edge_y": [0, 0, -10],
              "material": "floor"},
             {"type": "sphere", "center": [0, 0.5, 0], "radius": 0.5, "material": "ball"},
             {"type": "quad", "corner": [-0.5, 2, -0.5], "edge_x": [0, 0, 1], "edge_y": [1, 0, 0],
              "material": "lamp"}],
  "lights": [{"type": "point", "position": [2, 2, 1], "intensity": 3},
             {"type": "spot", "position": [-2, 3, 1], "look_at": [0, 0, 0], "intensity": 10}],
  "environment": {"type": "sky", "resolution": 64}
})";

} // namespace

TEST(Determinism, ThreadCountDoesNotChangeTheImage) {
  const int w = 40, h = 30;
  auto s = test::setup_scene(kScene, w, h);
  ASSERT_TRUE(s);
  RenderOptions opt;
  opt.spp = 4;
  opt.seed = 11;
  auto a = test::expect_same_bits_on_1_and_2_threads(*s, w, h, opt);
  opt.seed = 12;
  auto c = test::render(*s, w, h, opt);
  EXPECT_NE(std::memcmp(a.img.pixels.data(), c.img.pixels.data(), a.img.pixels.size() * 4), 0);
}

TEST(Consistency, ErrorHalvesWhenSamplesDouble) {
  const int w = 24, h = 18;
  auto s = test::setup_scene(kScene, w, h);
  ASSERT_TRUE(s);
  RenderOptions opt;
  opt.spp = 1024;
  opt.seed = 1000;
  auto ref = test::render(*s, w, h, opt);
  double err[3] = {0, 0, 0};
  const int spp[3] = {4, 8, 16};
  for (int seed = 0; seed < 4; ++seed)
    for (int k = 0; k < 3; ++k) {
      opt.spp = spp[k];
      opt.seed = uint64_t(seed);
      err[k] += rel_mse(test::render(*s, w, h, opt).img, ref.img);
    }
  for (int k = 0; k < 2; ++k) {
    double ratio = err[k] / err[k + 1];
    EXPECT_GT(ratio, 1.5) << spp[k] << " -> " << spp[k + 1];
    EXPECT_LT(ratio, 4.0) << spp[k] << " -> " << spp[k + 1];
  }
}

TEST(Cancel, StopsEarlyAndKeepsFinishedSamples) {
  const int w = 32, h = 32;
  auto s = test::setup_scene(kScene, w, h);
  ASSERT_TRUE(s);
  RenderOptions opt;
  opt.spp = 64;
  opt.threads = 1;
  std::atomic<bool> cancel{false};
  RenderStats st;
  // Cancel once a quarter of the work is reported done.
  auto img = render_image(
      *s, w, h, opt, &cancel,
      [&](uint64_t d, uint64_t t) {
        if (d * 4 >= t) cancel = true;
      },
      &st);
  EXPECT_TRUE(st.cancelled);
  EXPECT_LT(st.samples, uint64_t(w) * h * 64);
  EXPECT_GE(st.samples, uint64_t(w) * h); // the first pass (1 spp) covered the whole image
  double mean, e;
  test::mean_and_error(img, 1, mean, e);
  EXPECT_GT(mean, 0.01);
}
