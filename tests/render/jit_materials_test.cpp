// The stdlib shaders compiled by the JIT behave like their native C++ twins: each material's
// white-furnace value (a sphere in a uniform environment of radiance 1) agrees between the two
// backends within 4 combined standard errors (and matte albedo rho renders to rho).
#include "material_backend.h"
#include "render_test_util.h"

#include "lobe/bsdf.h"
#include "lobe/context.h"

#include <tbb/parallel_for.h>

#include <unistd.h>

#include <cstring>
#include <filesystem>
#include <fstream>

using namespace lobe;
using namespace lobe::render;

namespace {

// Renders a JSON scene at w x h and returns the mean of the green channel (and its error).
double render_mean(const std::string& json, const MaterialCompiler& compile, int w, int h, int spp,
                   int depth, double& err) {
  std::string e;
  auto desc = scene::parse_json_scene(json, "jit.json", e);
  EXPECT_TRUE(desc) << e;
  if (!desc) return -1;
  RenderScene s;
  e = s.setup(*desc, compile, w, h);
  EXPECT_EQ(e, "");
  if (!e.empty()) return -1;
  RenderOptions opt;
  opt.spp = spp;
  opt.max_depth = depth;
  auto r = test::render(s, w, h, opt);
  double mean;
  test::mean_and_error(r.img, 1, mean, err);
  return mean;
}

double furnace_mean(const std::string& material, const MaterialCompiler& compile, double& err) {
  std::string json = R"({
    "camera": {"eye": [0, 0, 4], "look_at": [0, 0, 0], "fov": 12},
    "materials": {"m": )" +
                     material + R"(},
    "shapes": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "m"}],
    "environment": {"type": "constant", "color": 1}
  })";
  return render_mean(json, compile, 16, 16, 32, 32, err);
}

} // namespace

TEST(JitMaterials, StdlibShadersMatchNativeTwins) {
  if (!MaterialBackend::jit_available()) GTEST_SKIP() << "this build has no JIT";
  MaterialBackend jit("jit");
  const char* materials[] = {
      R"({"shader": "matte", "params": {"Cs": 0.35}})",
      R"({"shader": "matte", "params": {"Cs": 1, "roughness": 0.8}})",
      R"({"shader": "plastic", "params": {"Cs": [0.2, 0.5, 0.8]}})",
      R"({"shader": "metal", "params": {"preset": "copper", "roughness": 0.4}})",
      R"({"shader": "glass", "params": {"ior": 1.33}})",
      R"({"shader": "brushed_metal"})",
      R"({"shader": "mirror", "params": {"Cs": 0.9}})",
  };
  for (const char* m : materials) {
    double ej, en;
    double vj = furnace_mean(m, jit.compiler(), ej);
    double vn = furnace_mean(m, native_compiler(), en);
    EXPECT_NEAR(vj, vn, 4 * std::sqrt(ej * ej + en * en) + 2e-4) << m;
  }
  double e;
  double v = furnace_mean(R"({"shader": "matte", "params": {"Cs": 0.35}})", jit.compiler(), e);
  EXPECT_NEAR(v, 0.35, 4 * e + 1e-6);
  EXPECT_TRUE(jit.warnings().empty());
}

// Materials compile in parallel (RenderScene::setup runs the compiler on oneTBB workers; the
// backend no longer serialises ShadingSystem::compile): distinct materials compiled at once
// each come out right.
TEST(JitMaterials, ManyMaterialsCompileConcurrently) {
  if (!MaterialBackend::jit_available()) GTEST_SKIP() << "this build has no JIT";
  MaterialBackend jit("jit");
  MaterialCompiler compile = jit.compiler();
  const int n = 8;
  std::vector<scene::MaterialDesc> descs(n);
  for (int i = 0; i < n; ++i) {
    descs[size_t(i)].name = std::string("m").append(std::to_string(i)); // GCC 12 -Wrestrict
    descs[size_t(i)].where = "test";
    descs[size_t(i)].group.layers.push_back(
        {i % 2 ? "matte" : "plastic", "l", {{"float", "Cs", std::to_string(0.1 * (i + 1))}}});
  }
  std::vector<std::shared_ptr<const Material>> mats(n);
  std::vector<std::string> errors(n);
  tbb::parallel_for(0, n,
                    [&](int i) { mats[size_t(i)] = compile(descs[size_t(i)], errors[size_t(i)]); });
  for (int i = 0; i < n; ++i) {
    ASSERT_TRUE(mats[size_t(i)]) << errors[size_t(i)];
    if (i % 2 == 0) continue; // plastic's albedo includes the coat
    ShadingContext ctx;
    ShaderGlobals sg{};
    sg.N = sg.Ng = {0, 0, 1};
    sg.I = {0, 0, -1};
    sg.dPdu = {1, 0, 0};
    sg.context = &ctx;
    mats[size_t(i)]->shade(sg);
    Bsdf b;
    b.build(sg.Ci, {0, 0, 1}, {0, 0, 1});
    EXPECT_NEAR(b.albedo({0, 0, 1}).x, 0.1 * (i + 1), 1e-6) << i;
  }
}

// With JIT materials, lighting a point through an emitter's own shader must not disturb the
// closure of the point being lit (their parameter blocks live in the shading context's arena).
// A matte floor under a spherical emitter and a constant sky: MIS, light-only and BSDF-only
// sampling estimate the same image, and the JIT and native backends agree. (Before the light
// was shaded in a context of its own, MIS came out about 3% dark here.)
TEST(JitMaterials, AreaLightShadingLeavesTheLitClosureIntact) {
  if (!MaterialBackend::jit_available()) GTEST_SKIP() << "this build has no JIT";
  // Two lamps: the stdlib emitter, the same everywhere (Material::kUniform), whose emission
  // the light samples take from set-up; and one that tests P, so that each light sample
  // shades it (the case this test was written for). Both emit power * Cs.
  std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("lobe_lamp_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  std::string varying = (dir / "p_lamp.osl").string();
  std::ofstream(varying) << R"(
surface p_lamp(color Cs = 1, float power = 1) {
  Ci = (P[1] > -100 ? power : 0) * Cs * emission();
}
)";
  for (const std::string& lamp : {std::string("emitter"), varying}) {
    const bool uniform = lamp == "emitter";
    const std::string json = R"({
    "camera": {"eye": [0, 3, 6], "look_at": [0, 0, 0], "fov": 40},
    "materials": {"floor": {"shader": "matte", "params": {"Cs": 0.5}},
                  "lamp": {"shader": ")" +
                             lamp +
                             R"(", "params": {"Cs": 1, "power": 20}}},
    "shapes": [{"type": "quad", "corner": [-4, 0, 4], "edge_x": [8, 0, 0], "edge_y": [0, 0, -8],
                "material": "floor"},
               {"type": "sphere", "center": [0, 1.5, 0], "radius": 0.3, "material": "lamp"}],
    "environment": {"type": "constant", "color": 0.2}
  })";
    MaterialBackend jit("jit");
    auto image_of = [&](const MaterialCompiler& compile, Strategy st, bool native = false) {
      std::string e;
      auto desc = scene::parse_json_scene(json, "lamp.json", e);
      EXPECT_TRUE(desc) << e;
      RenderScene s;
      EXPECT_EQ(s.setup(*desc, compile, 32, 32), "");
      EXPECT_EQ(s.uniform_emission(1) != nullptr, uniform) << lamp << (native ? ", native" : "");
      RenderOptions opt;
      opt.spp = 64;
      opt.max_depth = 4;
      opt.strategy = st;
      return test::render(s, 32, 32, opt).img;
    };
    // Mean of the per-pixel difference of two images (red) and its standard error: the
    // image's own structure cancels, the sampling noise remains.
    auto difference = [](const image::Image& a, const image::Image& b, double& err) {
      double s = 0, s2 = 0;
      size_t n = size_t(a.width) * a.height;
      for (size_t p = 0; p < n; ++p) {
        double d = double(a.pixels[p * a.nchannels()]) - b.pixels[p * b.nchannels()];
        s += d, s2 += d * d;
      }
      double m = s / double(n);
      err = std::sqrt(std::max(0.0, s2 / double(n) - m * m) / double(n));
      return m;
    };
    image::Image mis = image_of(jit.compiler(), Strategy::Mis);
    image::Image light = image_of(jit.compiler(), Strategy::LightOnly);
    image::Image bsdf = image_of(jit.compiler(), Strategy::BsdfOnly);
    double mean, err, e1, e2, e3, d_native = 0;
    test::mean_and_error(mis, 0, mean, err);
    double d_light = difference(mis, light, e1), d_bsdf = difference(mis, bsdf, e2);
    if (uniform) // the native library has no twin of the varying lamp
      d_native = difference(mis, image_of(native_compiler(), Strategy::Mis, true), e3);
    EXPECT_LT(std::fabs(d_light), 4 * e1 + 1e-4) << "MIS vs light sampling, " << lamp;
    EXPECT_LT(std::fabs(d_bsdf), 4 * e2 + 1e-4) << "MIS vs BSDF sampling, " << lamp;
    // Same seed, same closures (the kernels are bit-identical to the native library): the
    // two backends differ only by float rounding in the shaders.
    EXPECT_LT(std::fabs(d_native), 1e-3 * mean) << "JIT vs native, " << lamp;
    std::printf("%s: mean %.5f; MIS - light %.5f +- %.5f, MIS - BSDF %.5f +- %.5f, JIT - native "
                "%.2g\n",
                uniform ? "uniform lamp" : "varying lamp", mean, d_light, e1, d_bsdf, e2, d_native);
  }
  std::filesystem::remove_all(dir);
}

// A shape's "userdata" reaches `lockgeom = 0` parameters of its material, and getattribute
// sees the camera: in the white furnace a Lambert sphere renders to its albedo, so the image
// mean tells which value the shader got.
TEST(JitMaterials, ShapeUserDataAndCameraAttributes) {
  if (!MaterialBackend::jit_available()) GTEST_SKIP() << "this build has no JIT";
  std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("lobe_ud_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  std::string shader = (dir / "ud_matte.osl").string();
  std::ofstream(shader) << R"(
surface ud_matte(color Cs = 0.75 [[ int lockgeom = 0 ]], float locked = 1) {
  float fov = 0;
  int res[2] = {0, 0};
  string proj = "";
  int ok = getattribute("camera:fov", fov) && getattribute("camera:resolution", res) &&
           getattribute("camera:projection", proj);
  float k = (ok && fov == 8 && res[0] == 16 && res[1] == 8 && proj == "perspective") ? 1 : 0.5;
  Ci = k * locked * Cs * diffuse(N);
}
)";
  MaterialBackend jit("jit");
  auto mean_of = [&](const std::string& params, const std::string& userdata, double& err) {
    std::string json = R"({
      "camera": {"eye": [0, 0, 4], "look_at": [0, 0, 0], "fov": 8},
      "materials": {"m": {"shader": ")" +
                       shader + R"(", "params": {)" + params + R"(}}},
      "shapes": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "m",
                  "userdata": {)" +
                       userdata + R"(}}],
      "environment": {"type": "constant", "color": 1}
    })";
    return render_mean(json, jit.compiler(), 16, 8, 16, 8, err);
  };
  double e, m;
  m = mean_of("", "", e); // the default, and the camera matched (else half of it)
  EXPECT_NEAR(m, 0.75, 4 * e + 1e-6);
  m = mean_of(R"("Cs": 0.5)", "", e);
  EXPECT_NEAR(m, 0.5, 4 * e + 1e-6);
  // User data beats the instance value; a grey number is a colour; the same samples give the
  // same image as the instance value 0.25 would.
  double ud = mean_of(R"("Cs": 0.5)", R"("Cs": [0.25, 0.25, 0.25])", e);
  EXPECT_NEAR(ud, 0.25, 4 * e + 1e-6);
  EXPECT_DOUBLE_EQ(mean_of(R"("Cs": 0.25)", "", e), ud);
  EXPECT_DOUBLE_EQ(mean_of("", R"("Cs": 0.25)", e), ud);
  // A parameter without lockgeom = 0 never takes user data; a value of the wrong shape is
  // not used.
  m = mean_of("", R"("locked": 0.1)", e);
  EXPECT_NEAR(m, 0.75, 4 * e + 1e-6);
  m = mean_of("", R"("Cs": [0.1, 0.2])", e);
  EXPECT_NEAR(m, 0.75, 4 * e + 1e-6);
  std::filesystem::remove_all(dir);
}

// The closure kernels compute the native library's bits (jit_kernels_test), so when a shape
// switches from native closures to its kernels cannot show in the image: the built-in
// preview's materials (diffuse, oren-nayar, layered dielectric, conductor, glass) render to
// the same pixels with kernels off, compiled at set-up, and compiled in the background while
// the render runs; finish_kernels() then counts the kernels that came into use.
TEST(JitMaterials, KernelModesRenderTheSamePixels) {
  if (!MaterialBackend::jit_available()) GTEST_SKIP() << "this build has no JIT";
  const std::string json = R"({
    "camera": {"eye": [0, 2, 7], "look_at": [0, 0.5, 0], "fov": 35},
    "materials": {"matte": {"shader": "matte", "params": {"Cs": 0.6, "roughness": 0.5}},
                  "plastic": {"shader": "plastic", "params": {"Cs": 0.3}},
                  "metal": {"shader": "metal"},
                  "glass": {"shader": "glass"}},
    "shapes": [{"type": "quad", "corner": [-4, 0, 4], "edge_x": [8, 0, 0], "edge_y": [0, 0, -8],
                "material": "matte"},
               {"type": "sphere", "center": [-1.5, 0.6, 0], "radius": 0.6, "material": "plastic"},
               {"type": "sphere", "center": [0, 0.6, 0], "radius": 0.6, "material": "metal"},
               {"type": "sphere", "center": [1.5, 0.6, 0], "radius": 0.6, "material": "glass"}],
    "environment": {"type": "constant", "color": 0.8}
  })";
  ::setenv("LOBE_CACHE_DIR", "off", 1); // every kernel compiled here, none read from a cache
  MaterialBackend jit("jit");
  auto render_with = [&](KernelMode mode, int& kernels) {
    std::string e;
    auto desc = scene::parse_json_scene(json, "modes.json", e);
    EXPECT_TRUE(desc) << e;
    RenderScene s;
    s.set_kernel_mode(mode);
    EXPECT_EQ(s.setup(*desc, jit.compiler(), 48, 32), "");
    RenderOptions opt;
    opt.spp = 16;
    opt.max_depth = 6;
    image::Image img = test::render(s, 48, 32, opt).img;
    EXPECT_TRUE(s.finish_kernels().empty());
    kernels = s.stats().closure_kernels;
    return img;
  };
  int k_native = -1, k_setup = -1, k_background = -1;
  image::Image native = render_with(KernelMode::Native, k_native);
  image::Image setup = render_with(KernelMode::AtSetup, k_setup);
  image::Image background = render_with(KernelMode::Background, k_background);
  ::unsetenv("LOBE_CACHE_DIR");
  EXPECT_EQ(k_native, 0);
  EXPECT_EQ(k_setup, 4); // the four materials, each with BSDF closures
  std::printf("kernels in use: at set-up %d, in the background %d\n", k_setup, k_background);
  EXPECT_GE(k_background, 0);
  EXPECT_LE(k_background, 4);
  ASSERT_EQ(native.pixels.size(), setup.pixels.size());
  ASSERT_EQ(native.pixels.size(), background.pixels.size());
  size_t differ_setup = 0, differ_background = 0;
  for (size_t i = 0; i < native.pixels.size(); ++i) {
    differ_setup += std::memcmp(&native.pixels[i], &setup.pixels[i], sizeof(float)) != 0;
    differ_background += std::memcmp(&native.pixels[i], &background.pixels[i], sizeof(float)) != 0;
  }
  EXPECT_EQ(differ_setup, 0u);
  EXPECT_EQ(differ_background, 0u);
}

// A value for a parameter the shader lacks: the native twins answer as the JIT does, an error
// worded as the JIT's note, or, for a testrender XML scene (unknown_params_ignored), ignored;
// a value that does not fit is refused in the JIT's words (group::fit_instance_value).
TEST(JitMaterials, NativeTwinsReadInstanceValuesAsTheJit) {
  ShaderGroup g;
  g.layers.push_back({"matte", "m", {}});
  g.layers[0].values.push_back(InstanceValue{"float", "shininess", "3"});
  std::string error;
  EXPECT_EQ(make_native_material(g, error), nullptr);
  EXPECT_EQ(error.rfind("layer 'm': shader 'matte' has no parameter 'shininess' (its "
                        "parameters: ",
                        0),
            0u)
      << error;
  error.clear();
  EXPECT_NE(make_native_material(g, error, true), nullptr) << error;
  g.layers[0].values[0] = InstanceValue{"color", "Cs", "red"};
  EXPECT_EQ(make_native_material(g, error, true), nullptr);
  EXPECT_EQ(error, "layer 'm': value 'red' does not fit parameter 'Cs' of type color");
}
