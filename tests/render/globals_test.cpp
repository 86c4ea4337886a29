// What materials receive: globals a material does not read are not computed (left zero), and
// screen derivatives, when read, match the pixel footprint (pixel angle x distance); plus the
// geometry paths not covered elsewhere: a triangle mesh with vertex normals in the furnace, and
// a lat-long environment map file.
#include "image.h"
#include "native_materials.h"
#include "render_test_util.h"

#include "closures.h"
#include "lobe/context.h"

#include <atomic>
#include <cstring>
#include <filesystem>
#include <fstream>

#include <new>
#include <unistd.h>

using namespace lobe;
using namespace lobe::render;

namespace {

// A diffuse material with a chosen globals_read() mask that records what it was given.
class ProbeMaterial final : public Material {
public:
  explicit ProbeMaterial(uint64_t reads) : reads_(reads) {}
  void shade(ShaderGlobals& sg) const override {
    if (!is_zero(sg.dPdu)) tangents_seen++;
    if (sg.raytype == kRayCamera && !is_zero(sg.dPdx)) {
      camera_hits++;
      float l = length(sg.dPdx);
      float expected = pixel_angle * length(sg.P - eye);
      if (std::abs(l - expected) <= 0.02f * expected) footprint_ok++;
    }
    closures::Params p("diffuse");
    p.set("N", sg.N);
    void* mem = sg.context->allocate(sizeof(ClosureComponent) + p.size());
    auto* c = new (mem) ClosureComponent;
    c->id = p.id();
    c->weight = {0.5f, 0.5f, 0.5f};
    std::memcpy(c->params(), p.data(), p.size());
    sg.Ci = c;
  }
  uint64_t globals_read() const override { return reads_; }
  bool read_output(const ShadingContext&, const std::string&, const std::string&,
                   std::vector<float>&) const override {
    return false;
  }
  const CompileStats& stats() const override { return stats_; }

  mutable std::atomic<int> tangents_seen{0}, camera_hits{0}, footprint_ok{0};
  float pixel_angle = 0;
  Vec3 eye;

private:
  uint64_t reads_;
  CompileStats stats_;
};

const char* kWall = R"({
  "camera": {"eye": [0, 0, 4], "look_at": [0, 0, 0], "fov": 40},
  "materials": {"m": {"shader": "probe"}},
  "shapes": [{"type": "quad", "corner": [-3, -3, 0], "edge_x": [6, 0, 0], "edge_y": [0, 6, 0],
              "material": "m"}],
  "lights": [{"type": "point", "position": [0, 0, 3], "intensity": 1}]
})";

std::shared_ptr<ProbeMaterial> render_probe(uint64_t reads) {
  auto probe = std::make_shared<ProbeMaterial>(reads);
  std::string err;
  auto desc = scene::parse_json_scene(kWall, "wall.json", err);
  EXPECT_TRUE(desc) << err;
  RenderScene s;
  EXPECT_EQ(s.setup(
                *desc, [&](const scene::MaterialDesc&, std::string&) { return probe; }, 32, 32),
            "");
  probe->pixel_angle = s.camera().pixel_spread();
  probe->eye = s.camera().position();
  RenderOptions opt;
  opt.spp = 2;
  opt.max_depth = 2;
  test::render(s, 32, 32, opt);
  return probe;
}

} // namespace

TEST(Globals, UnreadGlobalsAreNotComputed) {
  auto p = render_probe(global_bit("N"));
  EXPECT_EQ(p->tangents_seen.load(), 0);
  EXPECT_EQ(p->camera_hits.load(), 0); // no dPdx either
}

TEST(Globals, ReadDerivativesMatchThePixelFootprint) {
  auto p = render_probe(global_bit("N") | global_bit("dPdx") | global_bit("dPdu"));
  EXPECT_GT(p->tangents_seen.load(), 0);
  ASSERT_GT(p->camera_hits.load(), 32 * 32);
  // The wall faces the camera; near the centre the footprint is pixel angle x distance.
  EXPECT_GT(p->footprint_ok.load(), p->camera_hits.load() / 4);
}

TEST(Geometry, MeshSphereWithVertexNormalsInFurnace) {
  // An icosphere-like UV sphere written as OBJ with exact vertex normals: Lambert albedo 0.5
  // in a uniform environment renders to 0.5 (shading normals differ from the facets').
  auto path = std::filesystem::temp_directory_path() /
              ("lobe_globals_test_" + std::to_string(::getpid()) + ".sphere.obj");
  {
    std::ofstream obj(path);
    const int nu = 24, nv = 12;
    for (int j = 0; j <= nv; ++j)
      for (int i = 0; i <= nu; ++i) {
        double th = M_PI * j / nv, ph = 2 * M_PI * i / nu;
        double x = std::sin(th) * std::cos(ph), y = std::cos(th), z = std::sin(th) * std::sin(ph);
        obj << "v " << x << " " << y << " " << z << "\nvn " << x << " " << y << " " << z << "\n";
      }
    for (int j = 0; j < nv; ++j)
      for (int i = 0; i < nu; ++i) {
        int a = j * (nu + 1) + i + 1, b = a + 1, c = a + nu + 1, d = c + 1;
        obj << "f " << a << "//" << a << " " << b << "//" << b << " " << d << "//" << d << "\n";
        obj << "f " << a << "//" << a << " " << d << "//" << d << " " << c << "//" << c << "\n";
      }
  }
  std::string json = R"({"camera": {"eye": [0, 0, 4], "look_at": [0, 0, 0], "fov": 10},
    "materials": {"m": {"shader": "matte", "params": {"Cs": 0.5}}},
    "shapes": [{"type": "mesh", "file": ")" +
                     path.string() + R"(", "material": "m"}],
    "environment": {"type": "constant", "color": 1}})";
  auto s = test::setup_scene(json, 16, 16);
  ASSERT_TRUE(s);
  RenderOptions opt;
  opt.spp = 32;
  auto r = test::render(*s, 16, 16, opt);
  double mean, err;
  test::mean_and_error(r.img, 0, mean, err);
  // A convex mesh with smooth normals: paths can re-hit the mesh near the silhouette where
  // shading and facet normals disagree, so allow 1% besides the noise.
  EXPECT_NEAR(mean, 0.5, 4 * err + 0.005);
}

// 0.5 * transparent() + 0.5 * diffuse(N): lossless, so the furnace renders to 1.
class HalfTransparent final : public Material {
public:
  void shade(ShaderGlobals& sg) const override {
    closures::Params d("diffuse");
    d.set("N", sg.N);
    closures::Params t("transparent");
    auto *a = make(sg, d), *b = make(sg, t);
    void* mem = sg.context->allocate(sizeof(ClosureAdd));
    auto* sum = new (mem) ClosureAdd;
    sum->id = kClosureAdd;
    sum->a = a;
    sum->b = b;
    sg.Ci = sum;
  }
  uint64_t globals_read() const override { return global_bit("N"); }
  bool read_output(const ShadingContext&, const std::string&, const std::string&,
                   std::vector<float>&) const override {
    return false;
  }
  const CompileStats& stats() const override { return stats_; }

private:
  static ClosureComponent* make(ShaderGlobals& sg, const closures::Params& p) {
    void* mem = sg.context->allocate(sizeof(ClosureComponent) + p.size());
    auto* c = new (mem) ClosureComponent;
    c->id = p.id();
    c->weight = {0.5f, 0.5f, 0.5f};
    std::memcpy(c->params(), p.data(), p.size());
    return c;
  }
  CompileStats stats_;
};

TEST(Transparency, HalfTransparentLambertIsLosslessInFurnace) {
  std::string err;
  auto desc = scene::parse_json_scene(R"({"camera": {"eye": [0, 0, 4], "look_at": [0, 0, 0],
    "fov": 12}, "materials": {"m": {"shader": "x"}},
    "shapes": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "m"}],
    "environment": {"type": "constant", "color": 1}})",
                                      "t.json", err);
  ASSERT_TRUE(desc) << err;
  auto mat = std::make_shared<HalfTransparent>();
  RenderScene s;
  ASSERT_EQ(s.setup(
                *desc, [&](const scene::MaterialDesc&, std::string&) { return mat; }, 16, 16),
            "");
  RenderOptions opt;
  opt.spp = 32;
  opt.max_depth = 64;
  auto r = test::render(s, 16, 16, opt);
  double mean, e;
  test::mean_and_error(r.img, 0, mean, e);
  EXPECT_NEAR(mean, 1.0, 4 * e + 2e-4);
}

TEST(Environment, LatLongMapFileLightsTheScene) {
  // A constant 0.25 map written as EXR: a white Lambert sphere renders to 0.25.
  auto path = (std::filesystem::temp_directory_path() /
               ("lobe_globals_test_" + std::to_string(::getpid()) + ".env.exr"))
                  .string();
  image::Image env(32, 16, {"R", "G", "B"});
  for (float& v : env.pixels) v = 0.25f;
  ASSERT_EQ(image::write_image(path, env), "");
  std::string json = R"({"camera": {"eye": [0, 0, 4], "look_at": [0, 0, 0], "fov": 12},
    "materials": {"m": {"shader": "matte", "params": {"Cs": 1}}},
    "shapes": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "m"}],
    "environment": {"type": "map", "file": ")" +
                     path + R"(", "rotation": 30}})";
  auto s = test::setup_scene(json, 16, 16);
  ASSERT_TRUE(s);
  RenderOptions opt;
  opt.spp = 16;
  auto r = test::render(*s, 16, 16, opt);
  double mean, err;
  test::mean_and_error(r.img, 2, mean, err);
  EXPECT_NEAR(mean, 0.25, 4 * err + 1e-4);
}

TEST(Environment, MissingMapIsALocatedError) {
  std::string err;
  auto desc = scene::parse_json_scene(
      R"({"environment": {"type": "map", "file": "/nonexistent/sky.hdr"}})", "e.json", err);
  ASSERT_TRUE(desc) << err;
  RenderScene s;
  std::string e = s.setup(*desc, native_compiler(), 4, 4);
  EXPECT_NE(e.find("e.json: /environment"), std::string::npos) << e;
  EXPECT_NE(e.find("/nonexistent/sky.hdr"), std::string::npos) << e;
}

// trace() from a shader reaches the Embree scene (SceneServices::trace): a sphere of radius
// 0.5 at height 2 over a floor, traced from the floor's centre. Distances are closed forms.
TEST(Services, TraceHitsTheSceneGeometry) {
  auto s = test::setup_scene(R"({
    "shapes": [{"type": "quad", "corner": [-3, 0, 3], "edge_x": [6, 0, 0], "edge_y": [0, 0, -6]},
               {"type": "sphere", "center": [0, 2, 0], "radius": 0.5}]
  })",
                             8, 8);
  ASSERT_TRUE(s);
  ShaderGlobals sg{};
  sg.Ng = sg.N = {0, 1, 0};
  const RendererServices& rs = s->services();
  TraceHit h;
  TraceOptions opt;
  Vec3 o{0, 0, 0}, z{0, 0, 0};
  ASSERT_TRUE(rs.trace(sg, opt, o, z, z, {0, 3, 0}, z, z, h)); // |R| = 3: still unit distances
  EXPECT_NEAR(h.hitdist, 1.5f, 1e-4f);
  EXPECT_NEAR(h.P.y, 1.5f, 1e-4f);
  EXPECT_NEAR(h.N.y, -1.0f, 1e-4f);
  EXPECT_NEAR(h.Ng.y, -1.0f, 1e-4f);
  opt.maxdist = 1.4f; // ends short of the sphere
  EXPECT_FALSE(rs.trace(sg, opt, o, z, z, {0, 1, 0}, z, z, h));
  opt.maxdist = 10;
  opt.mindist = 1.6f; // starts inside it: the far side, at height 2.5
  ASSERT_TRUE(rs.trace(sg, opt, o, z, z, {0, 1, 0}, z, z, h));
  EXPECT_NEAR(h.hitdist, 2.5f, 1e-4f);
  opt.mindist = 0;
  // Sideways, past the sphere's edge at x = 0.5 + a little: nothing; a ray down from above
  // the floor lands on it (the floor does not hide rays that leave it upwards).
  EXPECT_FALSE(rs.trace(sg, opt, {0.51f, 0, 0}, z, z, {0, 1, 0}, z, z, h));
  ShaderGlobals above{};
  ASSERT_TRUE(rs.trace(above, opt, {1, 1, 1}, z, z, {0, -2, 0}, z, z, h));
  EXPECT_NEAR(h.hitdist, 1.0f, 1e-4f);
  EXPECT_NEAR(h.P.y, 0.0f, 1e-4f);
}
