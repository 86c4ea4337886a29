// `lobe render` end to end (runs the built executable): where shaders are found, how scene
// and material errors are reported (exit status, located message), shader run-time messages
// after the render, and output checks before rendering.
#include "run_command.h"

#include "image.h"

#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

namespace fs = std::filesystem;

namespace {

using lobe::testing::CmdResult;
using lobe::testing::run_cmd;
using lobe::testing::write_file;

// A fresh folder for one test's files.
fs::path temp_dir(const std::string& name) { return lobe::testing::temp_dir("render_cli", name); }

// `lobe render -q ARGS`, run from `cwd`.
CmdResult render(const std::string& args, const fs::path& cwd = "/") {
  return run_cmd("cd '" + cwd.string() + "' && " + LOBE_EXE + " render -q " + args);
}

// A sphere filling a small image in a white furnace (radiance 1): a diffuse albedo renders to
// itself. `material` is the JSON of material "m".
std::string furnace_json(const std::string& material, const std::string& extra_materials = "") {
  return R"({"camera": {"eye": [0, 0, 4], "look_at": [0, 0, 0], "fov": 12},
  "settings": {"resolution": [8, 8], "spp": 4},
  "materials": {"m": )" +
         material + extra_materials + R"(},
  "shapes": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "m"}],
  "environment": {"type": "constant", "color": 1}})";
}

// Mean of channel `name` over the image at `path`.
double mean_channel(const fs::path& path, const std::string& name) {
  lobe::image::Image img;
  std::string e = lobe::image::read_image(path.string(), img);
  EXPECT_EQ(e, "");
  int c = img.channel(name);
  EXPECT_GE(c, 0) << name;
  if (!e.empty() || img.pixels.empty() || c < 0) return -1;
  double s = 0;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) s += img.pixel(x, y)[c];
  return s / (img.width * img.height);
}

const char* kTinted = "surface tinted(color c = color(0.25, 0.5, 0.75)) { Ci = c * diffuse(N); }\n";

} // namespace

TEST(RenderCli, ShadersNextToTheSceneFileAreFoundFromAnyFolder) {
  fs::path d = temp_dir("shader_dir");
  write_file(d / "tinted.osl", kTinted);
  write_file(d / "s.json", furnace_json(R"({"shader": "tinted"})"));
  CmdResult r =
      render("--materials jit " + (d / "s.json").string() + " -o " + (d / "o.exr").string());
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_EQ(r.out, "");
  // The albedo AOV is the shader's colour exactly (the beauty is its noisy MIS estimate).
  EXPECT_NEAR(mean_channel(d / "o.exr", "albedo.R"), 0.25, 1e-6);
  EXPECT_NEAR(mean_channel(d / "o.exr", "albedo.B"), 0.75, 1e-6);
  // The same through testrender XML.
  write_file(d / "s.xml", R"(<World>
  <Camera eye="0 0 4" look_at="0 0 0" fov="12"/>
  <Settings resolution="8 8" spp="4"/>
  <ShaderGroup>shader tinted m;</ShaderGroup>
  <Sphere center="0 0 0" radius="1"/>
  <ShaderGroup>color Cs 1 1 1; shader constant_background bg;</ShaderGroup>
  <Background resolution="16"/>
</World>)");
  r = render("--materials jit " + (d / "s.xml").string() + " -o " + (d / "x.exr").string());
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_NEAR(mean_channel(d / "x.exr", "albedo.G"), 0.5, 1e-6);
}

// A value the shader cannot take is an error (exit 1, file, material, parameter) in every
// backend: the native twins are no fallback for a material the JIT rejects.
TEST(RenderCli, BadInstanceValuesAreErrorsInEveryBackend) {
  fs::path d = temp_dir("bad_values");
  struct Case {
    const char* params;
    const char* message;
  } cases[] = {
      {R"({"Cs": "red"})", "value 'red' does not fit parameter 'Cs' of type color"},
      {R"({"Cs": [1, 0.5]})", "value '1 0.5' does not fit parameter 'Cs' of type color"},
      {R"({"roughness": [0.1, 0.2, 0.3]})",
       "value '0.1 0.2 0.3' does not fit parameter 'roughness' of type float"},
  };
  for (const Case& c : cases) {
    fs::path scene = d / "s.json";
    write_file(scene,
               furnace_json(std::string(R"({"shader": "matte", "params": )") + c.params + "}"));
    for (const char* mode : {"auto", "jit", "native"}) {
      CmdResult r = render(std::string("--materials ") + mode + " " + scene.string() + " -o " +
                           (d / "o.png").string());
      EXPECT_EQ(r.status, 1) << mode << " " << c.params;
      EXPECT_EQ(r.out, "lobe render: " + scene.string() +
                           ": /materials/m: material 'm': layer 'm': " + c.message + "\n")
          << mode;
    }
  }
}

// In auto mode the JIT's own error is reported, not the native twins' limitation.
TEST(RenderCli, JitErrorsAreReportedAsTheyAre) {
  fs::path d = temp_dir("jit_error");
  fs::path scene = d / "s.json";
  write_file(
      scene,
      furnace_json(R"({"group": "param float ior 1.45 ; shader glass g ; connect g.x h.y ;"})"));
  CmdResult r = render(scene.string() + " -o " + (d / "o.png").string());
  EXPECT_EQ(r.status, 1);
  EXPECT_EQ(
      r.out,
      "lobe render: " + scene.string() +
          ": /materials/m: material 'm': ConnectShaders: destination layer \"h\" not found\n");
  r = render("--materials native " + scene.string() + " -o " + (d / "o.png").string());
  EXPECT_EQ(r.status, 1);
  EXPECT_EQ(r.out, "lobe render: " + scene.string() +
                       ": /materials/m: material 'm': native materials take a single layer "
                       "without connections\n");
}

// --no-aovs: the .exr holds R, G, B only, and they are the same picture, bit for bit, as the
// beauty of the render with AOVs (the AOVs take no random numbers, so the paths are the same).
TEST(RenderCli, NoAovsWritesTheBeautyAlone) {
  fs::path d = temp_dir("no_aovs");
  write_file(d / "tinted.osl", kTinted);
  write_file(d / "s.json", furnace_json(R"({"shader": "tinted"})"));
  std::string scene = (d / "s.json").string();
  CmdResult with = render("--materials jit --seed 3 " + scene + " -o " + (d / "a.exr").string());
  ASSERT_EQ(with.status, 0) << with.out;
  CmdResult without =
      render("--materials jit --seed 3 --no-aovs " + scene + " -o " + (d / "b.exr").string());
  ASSERT_EQ(without.status, 0) << without.out;
  lobe::image::Image a, b;
  ASSERT_EQ(lobe::image::read_image((d / "a.exr").string(), a), "");
  ASSERT_EQ(lobe::image::read_image((d / "b.exr").string(), b), "");
  EXPECT_EQ(a.channels.size(), 10u); // R G B, albedo.R/G/B, N.X/Y/Z, Z
  EXPECT_EQ(b.channels, (std::vector<std::string>{"R", "G", "B"}));
  ASSERT_EQ(a.width * a.height, b.width * b.height);
  int differ = 0;
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x)
      for (int c = 0; c < 3; ++c) differ += a.pixel(x, y)[c] != b.pixel(x, y)[c];
  EXPECT_EQ(differ, 0);
  // Not all black: the furnace lights the sphere (tinted diffuse, albedo 0.25 in red).
  EXPECT_GT(mean_channel(d / "b.exr", "R"), 0.05);
}

// An instance value for a parameter the shader does not have is an error naming the file,
// the material, the parameter and the shader's parameters, in every backend.
TEST(RenderCli, UnknownParametersAreErrors) {
  fs::path d = temp_dir("unknown_param");
  fs::path scene = d / "s.json";
  write_file(scene, furnace_json(R"({"shader": "matte", "params": {"Cz": 1}})"));
  for (const char* mode : {"auto", "jit", "native"}) {
    CmdResult r = render(std::string("--materials ") + mode + " " + scene.string() + " -o " +
                         (d / "o.png").string());
    EXPECT_EQ(r.status, 1) << mode;
    EXPECT_EQ(r.out, "lobe render: " + scene.string() +
                         ": /materials/m: material 'm': layer 'm': shader 'matte' has no "
                         "parameter 'Cz' (its parameters: Cs, Kd, roughness)\n")
        << mode;
  }
  // A shader next to the scene: its own parameters are listed.
  write_file(d / "tinted.osl", kTinted);
  write_file(scene, furnace_json(R"({"shader": "tinted", "params": {"colour": [1, 0, 0]}})"));
  CmdResult r = render(scene.string() + " -o " + (d / "o.png").string());
  EXPECT_EQ(r.status, 1);
  EXPECT_EQ(r.out, "lobe render: " + scene.string() +
                       ": /materials/m: material 'm': layer 'm': shader 'tinted' has no "
                       "parameter 'colour' (its parameters: c)\n");
}

// A keyword argument a texture lookup or a closure does not take compiles (as oslc) and is
// dropped: the render goes on and says which (the furnace shows the albedo, 0.25 x the missing
// texture's 0.8 grey, untouched by the dropped arguments).
TEST(RenderCli, KeywordArgumentsNotTakenAreDroppedWithAWarning) {
  fs::path d = temp_dir("keywords");
  write_file(
      d / "kw.osl",
      "surface kw() {\n"
      "  color t = texture(\"nosuch_kw.tx\", u, v, \"foo\", 1, \"missingcolor\", color(0.8));\n"
      "  Ci = 0.25 * t * diffuse(N, \"bar\", 2);\n"
      "}\n");
  fs::path scene = d / "s.json";
  write_file(scene, furnace_json(R"({"shader": "kw"})"));
  CmdResult r = render(scene.string() + " -o " + (d / "o.exr").string());
  EXPECT_EQ(r.status, 0) << r.out;
  const std::string where = "warning: " + scene.string() + ": /materials/m: material 'm': ";
  const std::string shader = (d / "kw.osl").string();
  EXPECT_NE(r.out.find(where + "Unknown texture optional argument: \"foo\", <int> (" + shader +
                       ":2) (ignored)\n"),
            std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find(where + "Unsupported closure keyword arg \"bar\" for diffuse (" + shader +
                       ":3) (ignored)\n"),
            std::string::npos)
      << r.out;
  EXPECT_NEAR(mean_channel(d / "o.exr", "R"), 0.2, 0.01);
}

// The output is checked before rendering: a known extension and a writable folder. .hdr keeps
// RGB only (AOVs are written to EXR alone).
TEST(RenderCli, OutputIsCheckedBeforeRendering) {
  fs::path d = temp_dir("output");
  fs::path scene = d / "s.json";
  // 2^20 spp would take minutes: an error must come before any rendering.
  write_file(scene, furnace_json(R"({"shader": "matte"})"));
  struct Case {
    std::string out, message;
  } cases[] = {
      {(d / "x.pfm").string(),
       (d / "x.pfm").string() +
           ": cannot write .pfm images (expected .exr, .png, .jpg, .tif or .hdr)"},
      {(d / "x").string(),
       (d / "x").string() + ": no image extension (expected .exr, .png, .jpg, .tif or .hdr)"},
      {(d / "nope" / "x.png").string(),
       (d / "nope" / "x.png").string() + ": folder " + (d / "nope").string() + " does not exist"},
  };
  for (const Case& c : cases) {
    CmdResult r = render("--spp 1048576 " + scene.string() + " -o " + c.out);
    EXPECT_EQ(r.status, 1) << c.out;
    EXPECT_EQ(r.out, "lobe render: " + c.message + "\n");
  }
  CmdResult r = render(scene.string() + " -o " + (d / "x.hdr").string());
  ASSERT_EQ(r.status, 0) << r.out;
  lobe::image::Image img;
  ASSERT_EQ(lobe::image::read_image((d / "x.hdr").string(), img), "");
  EXPECT_EQ(img.nchannels(), 3);
  EXPECT_EQ(img.width, 8);
}

// A texture that cannot be read renders black but is reported after the render, once, with
// the material and a count; textures nobody reads are never opened, and shaders no shape uses
// are never compiled (here: a missing shader, a missing texture on an unused material and on
// a branch never taken).
TEST(RenderCli, ShaderRunTimeErrorsAreReportedOnceAfterTheRender) {
  fs::path d = temp_dir("texture");
  write_file(d / "textured.osl", R"(surface textured(string file = "none.exr", float branch = 0) {
    color c = color(0.5);
    if (branch > 0) c = texture(file, u, v);
    if (branch > 1) c = texture("never_taken.exr", u, v);
    Ci = c * diffuse(N);
})");
  std::string missing = (d / "missing.exr").string();
  write_file(
      d / "s.json",
      furnace_json(
          R"({"shader": "textured", "params": {"file": ")" + missing + R"(", "branch": 1}})",
          R"(, "unused": {"shader": "textured", "params": {"file": "also_missing.exr", "branch": 1}},
                           "unused_broken": {"shader": "doesnotexist"})"));
  CmdResult r = render((d / "s.json").string() + " -o " + (d / "o.exr").string(), d);
  ASSERT_EQ(r.status, 0) << r.out;
  // Told once, by the first lookup (as OSL tells it), not once per point.
  std::string line = "warning: " + (d / "s.json").string() +
                     ": /materials/m: material 'm': [RendererServices::texture] Could not open "
                     "file \"" +
                     missing + "\"\n";
  EXPECT_EQ(r.out, line);
  EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 1) << r.out; // one line in all
  EXPECT_EQ(r.out.find("also_missing"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("never_taken"), std::string::npos) << r.out;
  EXPECT_NEAR(mean_channel(d / "o.exr", "albedo.R"), 0, 1e-9); // black, as reported

  // The same shader on the branch without a texture: nothing to report.
  write_file(d / "s.json",
             furnace_json(R"({"shader": "textured", "params": {"file": ")" + missing + R"("}})",
                          R"(, "unused_broken": {"shader": "doesnotexist"})"));
  r = render((d / "s.json").string() + " -o " + (d / "o.exr").string(), d);
  EXPECT_EQ(r.status, 0);
  EXPECT_EQ(r.out, "");
  EXPECT_NEAR(mean_channel(d / "o.exr", "albedo.R"), 0.5, 1e-6);
}

// Ctrl-C: the finished samples are written and the summary says how many finished.
TEST(RenderCli, InterruptedSummarySaysHowManySamplesFinished) {
  fs::path d = temp_dir("interrupt");
  write_file(d / "s.json", furnace_json(R"({"shader": "matte"})"));
  CmdResult r =
      run_cmd("timeout --preserve-status -s INT 2 " + std::string(LOBE_EXE) +
              " render --spp 1000000 " + (d / "s.json").string() + " -o " + (d / "o.exr").string());
  EXPECT_EQ(r.status, 130) << r.out;
  std::string head =
      "interrupted: wrote the finished samples to " + (d / "o.exr").string() + ": 8x8, ";
  size_t at = r.out.find(head);
  ASSERT_NE(at, std::string::npos) << r.out;
  double done = std::atof(r.out.c_str() + at + head.size());
  EXPECT_GT(done, 0);
  EXPECT_LT(done, 1000000);
  EXPECT_EQ(r.out.compare(r.out.find(" ", at + head.size()), 20, " of 1000000 spp, jit"), 0)
      << r.out;
}

// --colorspace sets the JIT materials' colour space: luminance's weights here (the values are
// OSL 1.13.12's, as tests/shade/cli_test.cpp records); an unknown name is reported as testshade
// reports it and renders in Rec709.
TEST(RenderCli, ColorspaceOptionReachesTheMaterials) {
  fs::path d = temp_dir("colorspace");
  write_file(d / "lum.osl",
             "surface lum() { Ci = luminance(color(0.1, 0.7, 0.2)) * diffuse(N); }\n");
  write_file(d / "s.json", furnace_json(R"({"shader": "lum"})"));
  std::string args = "--materials jit " + (d / "s.json").string() + " -o " + (d / "o.exr").string();
  CmdResult r = render(args);
  EXPECT_EQ(r.status, 0) << r.out;
  EXPECT_NEAR(mean_channel(d / "o.exr", "albedo.R"), 0.536424339, 1e-6);
  r = render("--colorspace ACEScg " + args);
  EXPECT_EQ(r.status, 0) << r.out;
  EXPECT_NEAR(mean_channel(d / "o.exr", "albedo.R"), 0.509817958, 1e-6);
  r = render("--colorspace Rec2020 " + args);
  EXPECT_EQ(r.status, 0);
  EXPECT_EQ(r.out, "ERROR: Unknown color space \"Rec2020\"\n");
  EXPECT_NEAR(mean_channel(d / "o.exr", "albedo.R"), 0.536424339, 1e-6);
}

// An environment map with NaN and infinite values: a warning naming the file and how many, and
// those values read as 0 (the image is the one of the same map with zeros there, bit for bit).
TEST(RenderCli, NonFiniteEnvironmentTexelsAreWarnedOfAndReadAsZero) {
  fs::path d = temp_dir("nonfinite_env");
  auto write_env = [&](const std::string& name, bool bad) {
    lobe::image::Image img(16, 8, {"R", "G", "B"});
    for (int y = 0; y < 8; ++y)
      for (int x = 0; x < 16; ++x)
        for (int c = 0; c < 3; ++c) img.pixel(x, y)[c] = y < 4 ? 0.9f : 0.3f;
    float bad_values[3] = {NAN, INFINITY, -INFINITY};
    for (int k = 0; k < 3; ++k) img.pixel(2 + 3 * k, 1 + 2 * k)[k] = bad ? bad_values[k] : 0.0f;
    ASSERT_EQ(lobe::image::write_image((d / name).string(), img), "");
  };
  write_env("bad.exr", true);
  write_env("zero.exr", false);
  auto scene = [&](const std::string& map) {
    return R"({"camera": {"eye": [0, 1, 4], "look_at": [0, 0.5, 0], "fov": 40},
  "settings": {"resolution": [16, 12], "spp": 8},
  "environment": {"type": "map", "file": ")" +
           map + R"("},
  "materials": {"m": {"shader": "matte", "params": {"Cs": [0.5, 0.5, 0.5]}}},
  "shapes": [{"type": "sphere", "center": [0, 0.5, 0], "radius": 0.5, "material": "m"}]})";
  };
  write_file(d / "bad.json", scene("bad.exr"));
  write_file(d / "zero.json", scene("zero.exr"));
  CmdResult bad = render("--no-aovs bad.json -o bad_out.exr", d);
  ASSERT_EQ(bad.status, 0) << bad.out;
  EXPECT_EQ(bad.out, "warning: bad.json: /environment: environment map 'bad.exr': 3 values are "
                     "not finite numbers (NaN or infinite); read as 0\n");
  ASSERT_EQ(render("--no-aovs zero.json -o zero_out.exr", d).status, 0);
  lobe::image::Image a, b;
  ASSERT_EQ(lobe::image::read_image((d / "bad_out.exr").string(), a), "");
  ASSERT_EQ(lobe::image::read_image((d / "zero_out.exr").string(), b), "");
  EXPECT_EQ(a.pixels, b.pixels);
}

// --light-paths: light paths run for a glass sphere in an environment (the --stats line says
// how many: 0.5 a camera sample of 8 x 8 pixels at 4 samples), none with 0; a negative rate is
// refused.
TEST(RenderCli, LightPathsOptionSetsTheCausticPaths) {
  fs::path d = temp_dir("light_paths");
  const std::string json = R"({"camera": {"eye": [0, 2, 3], "look_at": [0, 0, 0], "fov": 40},
  "settings": {"resolution": [8, 8], "spp": 4},
  "materials": {"g": {"shader": "glass"}, "f": {"shader": "matte"}},
  "shapes": [{"type": "sphere", "center": [0, 0.6, 0], "radius": 0.5, "material": "g"},
             {"type": "quad", "corner": [-2, 0, 2], "edge_x": [4, 0, 0], "edge_y": [0, 0, -4],
              "material": "f"}],
  "environment": {"type": "sky", "resolution": 32}})";
  write_file(d / "s.json", json);
  std::string scene = (d / "s.json").string(), out = " -o " + (d / "a.exr").string();
  CmdResult on = render("--stats --light-paths 0.5 " + scene + out);
  ASSERT_EQ(on.status, 0) << on.out;
  EXPECT_NE(on.out.find("stats: 128 light paths for caustics of the environment"),
            std::string::npos)
      << on.out;
  CmdResult off = render("--stats --light-paths 0 " + scene + out);
  ASSERT_EQ(off.status, 0) << off.out;
  EXPECT_EQ(off.out.find("light paths"), std::string::npos) << off.out;
  // The scene's settings.light_paths when the flag is not given; the summary says the rate.
  std::string text = json;
  text.replace(text.find(R"("spp": 4)"), 8, R"("spp": 4, "light_paths": 0.25)");
  write_file(d / "t.json", text);
  CmdResult from_scene =
      run_cmd(std::string(LOBE_EXE) + " render --stats " + (d / "t.json").string() + out);
  ASSERT_EQ(from_scene.status, 0) << from_scene.out;
  EXPECT_NE(from_scene.out.find("stats: 64 light paths"), std::string::npos) << from_scene.out;
  EXPECT_NE(from_scene.out.find("4 spp, 0.25 light paths a sample for caustics"), std::string::npos)
      << from_scene.out;
  // Glass whose shader calls raytype() is no target (a light path shades it from the light's
  // side, with no ray type of the camera's path): no light paths.
  write_file(d / "rtglass.osl", "surface rtglass() { Ci = raytype(\"camera\") ? "
                                "refraction(N, 1.5) : reflection(N, 1.5); }\n");
  std::string rt = json;
  rt.replace(rt.find(R"("shader": "glass")"), 17, R"("shader": "rtglass")");
  write_file(d / "rt.json", rt);
  CmdResult by_raytype = render("--stats --materials jit " + (d / "rt.json").string() + out);
  ASSERT_EQ(by_raytype.status, 0) << by_raytype.out;
  EXPECT_EQ(by_raytype.out.find("light paths"), std::string::npos) << by_raytype.out;
  CmdResult bad = render("--light-paths -1 " + scene + out);
  EXPECT_NE(bad.status, 0);
  EXPECT_NE(bad.out.find("--light-paths"), std::string::npos) << bad.out;
}
