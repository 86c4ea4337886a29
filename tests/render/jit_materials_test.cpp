// The stdlib shaders compiled by the JIT behave like their native C++ twins: each material's
// white-furnace value (a sphere in a uniform environment of radiance 1) agrees between the two
// backends within 4 combined standard errors (and matte albedo rho renders to rho).
#include "material_backend.h"
#include "render_test_util.h"

#include "lobe/bsdf.h"
#include "lobe/context.h"

#include <tbb/parallel_for.h>

using namespace lobe;
using namespace lobe::render;

namespace {

double furnace_mean(const std::string& material, const MaterialCompiler& compile, double& err) {
  std::string json = R"({
    "camera": {"eye": [0, 0, 4], "look_at": [0, 0, 0], "fov": 12},
    "materials": {"m": )" +
                     material + R"(},
    "shapes": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "m"}],
    "environment": {"type": "constant", "color": 1}
  })";
  std::string e;
  auto desc = scene::parse_json_scene(json, "jit.json", e);
  EXPECT_TRUE(desc) << e;
  RenderScene s;
  e = s.setup(*desc, compile, 16, 16);
  EXPECT_EQ(e, "");
  if (!e.empty()) return -1;
  RenderOptions opt;
  opt.spp = 32;
  opt.max_depth = 32;
  auto r = test::render(s, 16, 16, opt);
  double mean;
  test::mean_and_error(r.img, 1, mean, err);
  return mean;
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
    descs[size_t(i)].name = "m" + std::to_string(i);
    descs[size_t(i)].where = "test";
    descs[size_t(i)].group.layers.push_back(
        {i % 2 ? "matte" : "plastic", "l", {{"float", "Cs", std::to_string(0.1 * (i + 1))}}});
  }
  std::vector<std::shared_ptr<const Material>> mats(n);
  std::vector<std::string> errors(n);
  tbb::parallel_for(0, n, [&](int i) { mats[size_t(i)] = compile(descs[size_t(i)], errors[size_t(i)]); });
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
