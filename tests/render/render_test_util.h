// Helpers shared by the render test suites: set up a scene from JSON text with the native
// materials, render it, and summarise pixels.
#pragma once

#include "native_materials.h"
#include "renderer.h"
#include "scene.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>

namespace lobe::render::test {

struct Rendered {
  image::Image img;
  RenderStats stats;
};

inline std::unique_ptr<RenderScene> setup_scene(const std::string& json, int w, int h) {
  std::string err;
  auto desc = scene::parse_json_scene(json, "test.json", err);
  EXPECT_TRUE(desc.has_value()) << err;
  if (!desc) return nullptr;
  auto s = std::make_unique<RenderScene>();
  std::string e = s->setup(*desc, native_compiler(), w, h);
  EXPECT_EQ(e, "");
  return e.empty() ? std::move(s) : nullptr;
}

inline Rendered render(const RenderScene& s, int w, int h, RenderOptions opt) {
  Rendered r;
  r.img = render_image(s, w, h, opt, nullptr, nullptr, &r.stats);
  return r;
}

// Renders `opt` on 1 thread, then on 2, and expects the same bits; returns the first render.
inline Rendered expect_same_bits_on_1_and_2_threads(const RenderScene& s, int w, int h,
                                                    RenderOptions opt) {
  opt.threads = 1;
  Rendered a = render(s, w, h, opt);
  opt.threads = 2;
  Rendered b = render(s, w, h, opt);
  EXPECT_EQ(a.img.pixels, b.img.pixels) << "1 and 2 threads";
  return a;
}

// Mean and standard error of the mean of channel c over all pixels.
inline void mean_and_error(const image::Image& img, int c, double& mean, double& err) {
  double s = 0, s2 = 0;
  size_t n = size_t(img.width) * img.height;
  for (size_t p = 0; p < n; ++p) {
    double v = img.pixels[p * img.nchannels() + c];
    s += v, s2 += v * v;
  }
  mean = s / double(n);
  double var = std::max(0.0, s2 / double(n) - mean * mean);
  err = std::sqrt(var / double(n));
}

} // namespace lobe::render::test
