// JSON scene loading: values land where the format says, and errors name file, JSON pointer
// and what was expected.
#include "light_kinds.h"
#include "scene.h"

#include <gtest/gtest.h>

#include <map>

using namespace lobe;
using namespace lobe::scene;

namespace {
SceneDesc ok(const std::string& text) {
  std::string err;
  auto s = parse_json_scene(text, "t.json", err);
  EXPECT_TRUE(s.has_value()) << err;
  return s ? *s : SceneDesc{};
}
std::string error_of(const std::string& text) {
  std::string err;
  auto s = parse_json_scene(text, "t.json", err);
  EXPECT_FALSE(s.has_value());
  return err;
}
} // namespace

TEST(SceneJson, FullSceneLoads) {
  SceneDesc s = ok(R"({
    "camera": {"eye": [0, 2, 6], "look_at": [0, 1, 0], "fov": 35, "aperture": 0.05},
    "settings": {"resolution": [320, 200], "spp": 8, "max_depth": 5, "seed": 7},
    "materials": {
      "red": {"shader": "matte", "params": {"Kd": 0.8, "Cs": [0.8, 0.1, 0.1],
                                            "n": {"type": "int", "value": 3}}},
      "glass": {"group": "param float ior 1.5 ; shader glass g1 ;"}
    },
    "shapes": [
      {"type": "sphere", "center": [0, 1, 0], "radius": 0.5, "material": "red",
       "transform": {"translate": [1, 0, 0], "scale": 2}},
      {"type": "quad", "corner": [-5, 0, -5], "edge_x": [10, 0, 0], "edge_y": [0, 0, 10],
       "material": "glass"}
    ],
    "lights": [{"type": "spot", "position": [0, 5, 0], "look_at": [0, 0, 0],
                "intensity": 10, "cone_angle": 20, "falloff_angle": 5}],
    "environment": {"type": "sky", "sun_direction": [0, 1, 1]}
  })");
  EXPECT_EQ(s.settings.width, 320);
  EXPECT_EQ(s.settings.spp, 8);
  EXPECT_EQ(s.settings.seed, 7u);
  EXPECT_EQ(s.settings.pixel_filter, PixelFilter::Box); // the default
  EXPECT_FLOAT_EQ(s.settings.light_paths, 0.1f);        // the default
  EXPECT_FLOAT_EQ(s.camera.aperture, 0.05f);
  ASSERT_EQ(s.materials.size(), 2u);
  const auto& layer = s.materials[0].group.layers.at(0);
  EXPECT_EQ(layer.shader, "matte");
  ASSERT_EQ(layer.values.size(), 3u);
  EXPECT_EQ(layer.values[0].type, "float"); // file order: Kd, Cs, n
  EXPECT_EQ(layer.values[1].type, "color");
  EXPECT_EQ(layer.values[1].value, "0.8 0.1 0.1");
  EXPECT_EQ(layer.values[2].type, "int");
  EXPECT_EQ(layer.values[2].value, "3");
  EXPECT_EQ(s.materials[1].group.layers.at(0).values.at(0).name, "ior");
  ASSERT_EQ(s.shapes.size(), 2u);
  // scale 2 first, then translate by 1: centre (0,1,0) -> (0,2,0) -> (1,2,0), radius 1.
  EXPECT_FLOAT_EQ(s.shapes[0].center.x, 1.0f);
  EXPECT_FLOAT_EQ(s.shapes[0].center.y, 2.0f);
  EXPECT_FLOAT_EQ(s.shapes[0].radius, 1.0f);
  EXPECT_EQ(s.shapes[1].material, 1);
  ASSERT_EQ(s.lights.size(), 1u);
  ASSERT_NE(s.lights[0].kind, nullptr);
  EXPECT_STREQ(s.lights[0].kind->name, "spot");
  EXPECT_FLOAT_EQ(s.lights[0].values[0].y, -1.0f); // the axis, towards look_at (light_kinds.cpp)
  EXPECT_EQ(s.environment.kind, Environment::Kind::Sky);
}

TEST(SceneJson, LayersAndConnections) {
  SceneDesc s = ok(R"({"materials": {"m": {
    "layers": [{"shader": "checker", "name": "tex", "params": {"scale": 4}},
               {"shader": "matte", "name": "surf"}],
    "connections": [["tex.Cout", "surf.Cs"]]}}})");
  const ShaderGroup& g = s.materials.at(0).group;
  ASSERT_EQ(g.layers.size(), 2u);
  ASSERT_EQ(g.connections.size(), 1u);
  EXPECT_EQ(g.connections[0].src_layer, "tex");
  EXPECT_EQ(g.connections[0].dst_param, "Cs");
}

TEST(SceneJson, RotationTransformsQuadEdges) {
  SceneDesc s = ok(R"({"shapes": [{"type": "quad", "corner": [1, 0, 0], "edge_x": [1, 0, 0],
    "edge_y": [0, 1, 0], "transform": {"rotate": [90, 0, 0, 1]}}]})");
  // 90 degrees about +Z maps +X to +Y and +Y to -X.
  EXPECT_NEAR(s.shapes[0].corner.y, 1.0f, 1e-6);
  EXPECT_NEAR(s.shapes[0].edge_x.y, 1.0f, 1e-6);
  EXPECT_NEAR(s.shapes[0].edge_y.x, -1.0f, 1e-6);
}

TEST(SceneJson, ErrorsNamePointerAndExpectation) {
  EXPECT_EQ(error_of(R"({"shapes": [{"type": "sphere", "radius": "big"}]})"),
            "t.json: /shapes/0/radius: expected a number, found string");
  EXPECT_EQ(error_of(R"({"shapes": [{"type": "sphere", "material": "nope"}]})"),
            "t.json: /shapes/0/material: no material named 'nope' in /materials");
  EXPECT_NE(
      error_of(R"({"settings": {"spp": 0}})").find("/settings/spp: expected an integer in [1,"),
      std::string::npos);
  EXPECT_EQ(error_of(R"({"settings": {"clamp": -1}})"),
            "t.json: /settings/clamp: expected a finite number >= 0 (0: no clamp)");
  EXPECT_EQ(error_of(R"({"settings": {"light_paths": -0.5}})"),
            "t.json: /settings/light_paths: expected a number in [0, 64] (0: none)");
  EXPECT_EQ(error_of(R"({"settings": {"light_paths": 1e9}})"),
            "t.json: /settings/light_paths: expected a number in [0, 64] (0: none)");
  EXPECT_EQ(error_of(R"({"settings": {"pixel_filter": "gauss"}})"),
            "t.json: /settings/pixel_filter: expected \"box\" or \"tent\" (testrender's)");
  EXPECT_NE(error_of(R"({"camera": {"fvo": 3}})").find("/camera/fvo: unknown key"),
            std::string::npos);
  EXPECT_NE(error_of(R"({"shapes": [{"type": "cone"}]})").find("/shapes/0/type: expected"),
            std::string::npos);
  EXPECT_NE(error_of(R"({"shapes": [{"type": "sphere", "transform": {"scale": [1, 2, 1]}}]})")
                .find("uniform"),
            std::string::npos);
}

TEST(SceneJson, SyntaxErrorsGiveLineAndColumn) {
  std::string err = error_of("{\n  \"camera\": {\n    \"fov\": ,\n  }\n}");
  EXPECT_EQ(err.rfind("t.json:3:", 0), 0u) << err;
  // The position once, then nlohmann's message without its own "[json.exception...] parse
  // error at line L, column C:" prefix.
  err = error_of("{\n  \"shapes\": [\n    {\"type\": \"sphere\", \"radius\": 1,}\n  ]}");
  EXPECT_EQ(err, "t.json:3:36: invalid JSON: syntax error while parsing object key - unexpected "
                 "'}'; expected string literal");
}

TEST(SceneJson, SeedTakesTheCommandLineRange) {
  std::string err;
  auto s = parse_json_scene(R"({"settings": {"seed": 1099511627776}})", "t.json", err);
  ASSERT_TRUE(s) << err;
  EXPECT_EQ(s->settings.seed, uint64_t(1) << 40);
  EXPECT_EQ(error_of(R"({"settings": {"seed": 1099511627777}})"),
            "t.json: /settings/seed: expected an integer in [0, 1099511627776]");
  auto x = parse_xml_scene(R"(<World><Settings seed="1099511627775"/></World>)", "t.xml", err);
  ASSERT_TRUE(x) << err;
  EXPECT_EQ(x->settings.seed, (uint64_t(1) << 40) - 1);
}

TEST(SceneJson, GroupTextErrorsAreLocated) {
  std::string err = error_of(R"({"materials": {"m": {"group": "shader ; param"}}})");
  EXPECT_NE(err.find("/materials/m/group"), std::string::npos) << err;
}

TEST(SceneJson, ShapeUserData) {
  SceneDesc s = ok(R"({"shapes": [
    {"type": "sphere", "userdata": {"tint": [1, 0.5, 0.25], "Kd": 0.75, "label": "left"}},
    {"type": "quad", "corner": [0, 0, 0], "edge_x": [1, 0, 0], "edge_y": [0, 1, 0],
     "userdata": {}}]})");
  ASSERT_EQ(s.shapes.size(), 2u);
  const auto& u = s.shapes[0].userdata;
  ASSERT_EQ(u.size(), 3u);
  std::map<std::string, const UserValue*> by;
  for (const UserValue& v : u) by[v.name] = &v;
  ASSERT_TRUE(by.count("tint") && by.count("Kd") && by.count("label"));
  EXPECT_EQ(by["tint"]->numbers, (std::vector<float>{1, 0.5f, 0.25f}));
  EXPECT_EQ(by["Kd"]->numbers, (std::vector<float>{0.75f}));
  EXPECT_TRUE(by["label"]->is_text);
  EXPECT_EQ(by["label"]->text, "left");
  EXPECT_TRUE(s.shapes[1].userdata.empty());
  EXPECT_EQ(error_of(R"({"shapes": [{"type": "sphere", "userdata": {"x": true}}]})"),
            "t.json: /shapes/0/userdata/x: expected a number, an array of numbers or a string");
  EXPECT_EQ(error_of(R"({"shapes": [{"type": "sphere", "userdata": {"x": [1, "a"]}}]})"),
            "t.json: /shapes/0/userdata/x/1: expected a number, found string");
  EXPECT_EQ(error_of(R"({"shapes": [{"type": "sphere", "userdata": [1]}]})"),
            "t.json: /shapes/0/userdata: expected an object, found array");
}

// Numbers no float (or no double) can hold are errors at their place, never an uncaught
// exception: nlohmann throws out_of_range for 1e999 while parsing.
TEST(SceneJson, NumbersOutOfRangeAreLocatedErrors) {
  EXPECT_EQ(error_of("{\n  \"settings\": {\"spp\": 1e999}}"),
            "t.json:2:23: number 1e999 is too large for a double");
  EXPECT_EQ(error_of(R"({"materials": {"m": {"shader": "matte", "params": {"Cs": -1e999}}}})"),
            "t.json:1:58: number -1e999 is too large for a double");
  EXPECT_EQ(error_of(R"({"camera": {"eye": [1e300, 0, 0]}})"),
            "t.json: /camera/eye/0: number 1e+300 is out of the range of a 32-bit float");
}

// Emitted light is never negative: a light's intensity or colour, an environment's colour or
// intensity below 0 is an error at its place; a product no float holds likewise. Shader
// parameters are the shader's to interpret (a negative offset is fine) and are not checked.
TEST(SceneJson, NegativeOrOverflowingLightIsAnError) {
  EXPECT_EQ(error_of(R"({"lights": [{"type": "point", "position": [0, 1, 0], "intensity": -5}]})"),
            "t.json: /lights/0/intensity: expected components >= 0 (emitted light cannot be "
            "negative)");
  EXPECT_EQ(error_of(R"({"lights": [{"type": "spot", "position": [0, 1, 0], "look_at": [0, 0, 0],
                       "color": [1, -0.5, 1]}]})"),
            "t.json: /lights/0/color: expected components >= 0 (emitted light cannot be "
            "negative)");
  EXPECT_EQ(error_of(R"({"lights": [{"type": "point", "position": [0, 1, 0], "intensity": 1e38,
                       "color": 100}]})"),
            "t.json: /lights/0: intensity x color overflows a 32-bit float");
  EXPECT_EQ(error_of(R"({"environment": {"type": "constant", "color": [-1, 1, 1]}})"),
            "t.json: /environment/color: expected components >= 0 (emitted light cannot be "
            "negative)");
  EXPECT_EQ(error_of(R"({"environment": {"type": "sky", "intensity": -2}})"),
            "t.json: /environment/intensity: expected a number >= 0 (emitted light cannot be "
            "negative)");
  std::string err;
  EXPECT_TRUE(
      parse_json_scene(R"({"materials": {"m": {"shader": "matte", "params": {"Cs": -0.5}}}})",
                       "t.json", err)
          .has_value())
      << err;
}
