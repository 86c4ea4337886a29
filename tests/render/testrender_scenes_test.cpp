// OSL testrender scenes (tests/render/testrender/*.xml, with their own shaders) rendered by
// `lobe render` and compared with OSL 1.13's testrender: the image mean of each channel must
// lie within 3% of testrender's at the same resolution and samples (the scene's
// <Option aa="int 4"/>: 16 per pixel). testrender is not run here: its means are recorded
// below with the command that made them. Every reference was also rendered with aa 24-32;
// those converged means differ from the ones below by under 0.7%, so the 3% is for real
// differences in the picture, not testrender's noise.
//
// References (from a folder holding the scene and the shaders compiled with OSL's oslc
// (`oslc -o tr_sky_bg.oso tr-sky-bg.osl`, as the name each file declares), one line each):
//   testrender --res 80 60 cornell.xml cornell.exr && oiiotool cornell.exr --printstats
//   testrender --res 80 60 sky.xml sky.exr && oiiotool sky.exr --printstats
//   testrender --res 80 60 glass.xml glass.exr && oiiotool glass.exr --printstats
//   sed 's/"diffuse"/"FAMILY"/' furnace.xml > f.xml && testrender --res 32 32 f.xml f.exr
//       && oiiotool f.exr --printstats
#include "run_command.h"

#include "image.h"

#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>

namespace fs = std::filesystem;

namespace {

using lobe::testing::CmdResult;
using lobe::testing::run_cmd;

const fs::path kScenes = LOBE_TESTRENDER_SCENES;

// A fresh folder holding copies of the scenes' shaders.
fs::path temp_dir(const std::string& name) {
  fs::path d = lobe::testing::temp_dir("testrender", name);
  for (const auto& e : fs::directory_iterator(kScenes))
    if (e.path().extension() == ".osl") fs::copy_file(e.path(), d / e.path().filename());
  return d;
}

std::string read_file(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

struct Means {
  double r = -1, g = -1, b = -1;
};

// Renders `scene` with `lobe render -q ARGS` to an EXR and returns the mean of R, G, B.
Means render_means(const fs::path& scene, const std::string& args, const fs::path& dir,
                   std::string* output = nullptr) {
  fs::path out = dir / (scene.stem().string() + ".exr");
  CmdResult r = run_cmd(std::string(LOBE_EXE) + " render -q " + scene.string() + " " + args +
                        " -o " + out.string());
  if (output) *output = r.out;
  EXPECT_EQ(r.status, 0) << r.out;
  Means m;
  lobe::image::Image img;
  if (!lobe::image::read_image(out.string(), img).empty()) return m;
  double sum[3] = {0, 0, 0};
  int ch[3] = {img.channel("R"), img.channel("G"), img.channel("B")};
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x)
      for (int c = 0; c < 3; ++c) sum[c] += img.pixel(x, y)[ch[c]];
  double n = double(img.width) * img.height;
  return {sum[0] / n, sum[1] / n, sum[2] / n};
}

void expect_within(const Means& got, const Means& want, double rel, const std::string& what) {
  EXPECT_NEAR(got.r, want.r, rel * want.r) << what << " R";
  EXPECT_NEAR(got.g, want.g, rel * want.g) << what << " G";
  EXPECT_NEAR(got.b, want.b, rel * want.b) << what << " B";
}

} // namespace

// Camera by eye + dir with testrender's field of view, the light a quad sampled through
// is_light, bounces and samples from <Option>.
TEST(TestrenderScenes, CornellBox) {
  fs::path d = temp_dir("cornell");
  Means m = render_means(kScenes / "cornell.xml", "--res 80 60", d);
  expect_within(m, {0.131775, 0.101094, 0.061567}, 0.03, "cornell");
}

// A background shader found by the name its file declares, at resolution 1; the sky lights a
// floor and a ball.
TEST(TestrenderScenes, SkyBackgroundByDeclaredName) {
  fs::path d = temp_dir("sky");
  Means m = render_means(kScenes / "sky.xml", "--res 80 60", d);
  expect_within(m, {0.535226, 0.520969, 0.528236}, 0.03, "sky");
}

// N and Ng face the viewer, as testrender gives them: from inside a sphere every point is
// seen from the back, and tr_facing emits (dot(N, I) < 0, dot(Ng, I) < 0, backfacing()),
// which testrender renders (1, 1, 1) at every pixel (`testrender --res 16 16 facing.xml`).
TEST(TestrenderScenes, NormalsFaceTheViewer) {
  fs::path d = temp_dir("facing");
  Means m = render_means(kScenes / "facing.xml", "--res 16 16", d);
  EXPECT_EQ(m.r, 1.0);
  EXPECT_EQ(m.g, 1.0);
  EXPECT_EQ(m.b, 1.0);
}

// Smooth glass as OSL's shaders write it (1/ior from inside, N facing the viewer) over a
// floor under a graded sky: refraction() reads eta across the side N faces, as testrender's
// does. Reading it as the object's inside over outside from both sides (Lobe before) traps
// the light in the ball: image mean 0.39 instead of 0.61.
TEST(TestrenderScenes, GlassBallWithOslsEtaConvention) {
  fs::path d = temp_dir("glass");
  Means m = render_means(kScenes / "glass.xml", "--res 80 60", d);
  expect_within(m, {0.607446, 0.593773, 0.609304}, 0.03, "glass");
}

// testrender's pixel filter: a tent two pixels wide, so a sharp vertical edge on the boundary
// between columns 7 and 8 of a 16-wide image leaves 1/8 of the bright side in column 7 and 7/8
// in column 8 (the tent's weight beyond half a pixel: the integral of 1 - x over [1/2, 1]).
// testrender prints exactly those (`testrender --res 16 4 -aa 32 edge.xml edge.exr`: row 1
// 0 x7, 0.1250, 0.8750, 1 x7); `--filter box` (the JSON scenes' default) gives 0 and 1.
TEST(TestrenderScenes, TentPixelFilterAsTestrender) {
  fs::path d = temp_dir("edge");
  for (const char* filter : {"", "--filter box"}) {
    fs::path out = d / "edge.exr";
    CmdResult r = run_cmd(std::string(LOBE_EXE) + " render -q " + (kScenes / "edge.xml").string() +
                          " --res 16 4 --spp 256 " + filter + " -o " + out.string());
    ASSERT_EQ(r.status, 0) << r.out;
    lobe::image::Image img;
    ASSERT_TRUE(lobe::image::read_image(out.string(), img).empty());
    int R = img.channel("R");
    for (int y = 0; y < 4; ++y) {
      float bright = img.pixel(15, y)[R];
      ASSERT_NEAR(bright, 1.0f, 1e-3f) << y;
      bool tent = *filter == 0;
      EXPECT_NEAR(img.pixel(6, y)[R], 0.0f, 1e-4f) << filter << " " << y;
      EXPECT_NEAR(img.pixel(7, y)[R], tent ? 0.125f : 0.0f, 0.01f) << filter << " " << y;
      EXPECT_NEAR(img.pixel(8, y)[R], tent ? 0.875f : 1.0f, 0.01f) << filter << " " << y;
      EXPECT_NEAR(img.pixel(9, y)[R], 1.0f, 1e-3f) << filter << " " << y;
    }
  }
}

namespace {
struct FurnaceCase {
  const char* family;
  double mean; // testrender's (grey: R = G = B)
};

// Renders furnace.xml with `family` in place of diffuse and compares with testrender's mean.
void expect_furnace(const FurnaceCase* cases, size_t count, const std::string& dir_name) {
  fs::path d = temp_dir(dir_name);
  std::string text = read_file(kScenes / "furnace.xml");
  ASSERT_NE(text.find("\"diffuse\""), std::string::npos);
  for (size_t i = 0; i < count; ++i) {
    const FurnaceCase& c = cases[i];
    std::string t = text;
    t.replace(t.find("\"diffuse\""), 9, std::string("\"") + c.family + "\"");
    fs::path scene = d / (std::string("furnace_") + c.family + ".xml");
    std::ofstream(scene) << t;
    Means m = render_means(scene, "--res 32 32", d);
    expect_within(m, {c.mean, c.mean, c.mean}, 0.03, c.family);
  }
}
} // namespace

// White furnace, one closure family at a time (grey 0.9 tint, roughness 0.3, ior 1.5; from
// inside, tr_closure passes 1/ior as OSL's glass shaders do, N facing the viewer).
TEST(TestrenderScenes, FurnacePerClosureFamily) {
  const FurnaceCase cases[] = {
      {"diffuse", 0.899076},
      {"oren_nayar", 0.814881},
      {"translucent", 0.810122},
      {"microfacet_ggx", 0.032580},
      {"microfacet_beckmann", 0.036774},
      {"reflection", 0.036173},
      {"refraction", 0.746237},
      {"dielectric", 0.810559},
      {"transparent", 0.810059},
      {"microfacet_ggx_refract", 0.648732},
  };
  expect_furnace(cases, std::size(cases), "furnace");
}

// A closure that does not render as testrender's (closure code, not the scene reader):
// measured on this scene, Lobe's ward gives 0.815 where testrender gives 0.685 (testrender's
// Ward loses about a sixth of the energy at roughness 0.3; Lobe's is energy-conserving).
// Run with --gtest_also_run_disabled_tests.
TEST(TestrenderScenes, DISABLED_FurnaceClosuresThatDiffer) {
  const FurnaceCase cases[] = {
      {"ward", 0.685419},
  };
  expect_furnace(cases, std::size(cases), "furnace_differ");
}

// What testrender accepts with a warning renders here too: an instance value for a parameter
// the shader lacks, an attribute nobody reads, an option Lobe does not use.
TEST(TestrenderScenes, WarningsDoNotStopTheRender) {
  fs::path d = temp_dir("warnings");
  fs::path scene = d / "w.xml";
  std::ofstream(scene) << R"(<World>
  <Option aa="int 2" texture_cache="int 1"/>
  <Camera eye="0 0 0" dir="0 0 1" fov="20" shutter="0 1"/>
  <ShaderGroup>color Cs 0.5 0.5 0.5; float shininess 3; shader tr_matte m;</ShaderGroup>
  <Sphere center="0 0 4" radius="1"/>
  <ShaderGroup>shader tr_constant_bg bg;</ShaderGroup>
  <Background resolution="1"/>
</World>)";
  std::string out;
  Means m = render_means(scene, "--res 16 16", d, &out);
  EXPECT_NEAR(m.r, 0.5, 0.02) << out; // a grey 0.5 sphere filling the view in a furnace
  EXPECT_NE(out.find(scene.string() + ":2: <Option> 'texture_cache' ignored"), std::string::npos)
      << out;
  EXPECT_NE(out.find(scene.string() + ":3: <Camera> attribute 'shutter' ignored"),
            std::string::npos)
      << out;
  EXPECT_NE(out.find("shininess"), std::string::npos) << out;
  EXPECT_NE(out.find("(ignored)"), std::string::npos) << out;
}

// Camera rays that escape run the background shader itself, as testrender's do, so the
// picture's background is exact at any table size. The background is 0 on one side of the
// plane x = 0.07344 (-z) through the eye (4.2 degrees off -Z) and 1 on the other; a 10-degree
// camera looking down -Z sees it as a vertical edge at x_ndc = 0.07344 / tan(5 deg) = 0.839,
// pixel column 58.9 of 64. Columns clear of it are exactly 0 or 1. The 128 x 64 table
// (resolution 64: texels of 2.8 degrees, the one holding the edge spans columns 50 to past the
// image's edge) reads about 0.5 there, which a lookup in the table would show.
TEST(BackgroundShader, CameraRaysSeeTheShaderNotItsTable) {
  fs::path d = lobe::testing::temp_dir("testrender", "bg_exact");
  std::ofstream(d / "edge_bg.osl")
      << "surface edge_bg() { vector d = normalize(I);\n"
         "  Ci = (d[0] > -0.07344 * d[2] ? color(1) : color(0)) * background(); }\n";
  std::ofstream(d / "s.json") << R"({"camera": {"eye": [0, 0, 0], "look_at": [0, 0, -1], "fov": 10},
             "settings": {"resolution": [64, 64], "spp": 4},
             "materials": {"bg": {"shader": "edge_bg"}},
             "environment": {"type": "shader", "material": "bg", "resolution": 64}})";
  fs::path out = d / "o.exr";
  CmdResult r = run_cmd(std::string(LOBE_EXE) + " render -q " + (d / "s.json").string() + " -o " +
                        out.string());
  ASSERT_EQ(r.status, 0) << r.out;
  lobe::image::Image img;
  ASSERT_EQ(lobe::image::read_image(out.string(), img), "");
  int c = img.channel("R");
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      float v = img.pixel(x, y)[c];
      if (x <= 57) {
        EXPECT_EQ(v, 0.0f) << x << " " << y;
      }
      if (x >= 60) {
        EXPECT_EQ(v, 1.0f) << x << " " << y;
      }
    }
}
