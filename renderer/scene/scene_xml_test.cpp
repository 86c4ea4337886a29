// OSL testrender XML scenes: shader groups bind to the shapes after them, the group before
// <Background> is the background shader, and errors carry the line number.
#include "scene.h"
#include "scene_group.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace lobe;
using namespace lobe::scene;

TEST(SceneXml, TestrenderSceneLoads) {
  const char* xml = R"(<World>
  <Camera eye="0, 1, 5" look_at="0,0.5,0" fov="30" />
  <ShaderGroup>
    color Cs 0.7 0.2 0.2;
    shader matte layer1;
  </ShaderGroup>
  <Sphere center="0,0.5,0" radius="0.5" />
  <Quad corner="-3,0,-3" edge_x="6,0,0" edge_y="0,0,6" />
  <ShaderGroup>param float Kd 1; shader envmap bg;</ShaderGroup>
  <Background resolution="128" />
</World>)";
  std::string err;
  auto s = parse_xml_scene(xml, "t.xml", err);
  ASSERT_TRUE(s) << err;
  // testrender's fov 30 spans half of what Lobe's fov 30 does: tan(lobe/2) = tan(15 deg) / 2.
  EXPECT_NEAR(s->camera.fov, 2 * std::atan(0.5 * std::tan(15 * M_PI / 180)) * 180 / M_PI, 1e-4);
  EXPECT_FLOAT_EQ(s->camera.look_at.y, 0.5f);
  ASSERT_EQ(s->materials.size(), 2u);
  ASSERT_EQ(s->materials[0].group.layers.size(), 1u);
  const auto& v = s->materials[0].group.layers[0].values;
  ASSERT_EQ(v.size(), 1u);
  EXPECT_EQ(v[0].type, "color");
  EXPECT_EQ(v[0].value, "0.7 0.2 0.2");
  ASSERT_EQ(s->shapes.size(), 2u);
  EXPECT_EQ(s->shapes[0].material, 0);
  EXPECT_EQ(s->shapes[1].material, 0);
  EXPECT_FLOAT_EQ(s->shapes[1].edge_y.z, 6.0f);
  EXPECT_EQ(s->environment.kind, Environment::Kind::Shader);
  EXPECT_EQ(s->environment.material, 1);
  EXPECT_EQ(s->environment.resolution, 256); // Lobe's table keeps at least 256 rows
  EXPECT_TRUE(s->materials[0].unknown_params_warn);
}

// testrender 1.13's camera: eye/dir/up/fov with defaults eye 0, dir +Z, up +Y, fov 90;
// look_at overrides dir.
TEST(SceneXml, CameraAsTestrender) {
  std::string err;
  auto s = parse_xml_scene("<World><Camera eye=\"1 2 3\" dir=\"0 0 -2\"/></World>", "t.xml", err);
  ASSERT_TRUE(s) << err;
  EXPECT_FLOAT_EQ(s->camera.look_at.x, 1);
  EXPECT_FLOAT_EQ(s->camera.look_at.y, 2);
  EXPECT_FLOAT_EQ(s->camera.look_at.z, 1);
  EXPECT_NEAR(s->camera.fov, 2 * std::atan(0.5) * 180 / M_PI, 1e-4); // fov 90: tan(45) / 2
  s = parse_xml_scene("<World><Camera dir=\"1 0 0\" look_at=\"0 0 -5\"/></World>", "t.xml", err);
  ASSERT_TRUE(s) << err;
  EXPECT_FLOAT_EQ(s->camera.look_at.z, -5);
  s = parse_xml_scene("<World/>", "t.xml", err); // no camera: testrender's defaults
  ASSERT_TRUE(s) << err;
  EXPECT_FLOAT_EQ(s->camera.look_at.z, 1);
  EXPECT_FLOAT_EQ(s->camera.eye.z, 0);
  EXPECT_EQ(s->settings.width, 640);
  EXPECT_EQ(s->settings.height, 480);
  EXPECT_EQ(s->settings.spp, 1);
  EXPECT_EQ(s->settings.pixel_filter, PixelFilter::Tent); // testrender's
  EXPECT_FALSE(parse_xml_scene("<World><Camera dir=\"0 1 0\"/></World>", "t.xml", err));
  EXPECT_EQ(err, "t.xml:1: the view direction and up must not be parallel");
}

// <Option>: aa N is N x N samples, max_bounces the path depth; other names are warnings,
// the -albedo view an error naming it.
TEST(SceneXml, Options) {
  std::string err;
  auto s =
      parse_xml_scene("<World>\n<Option aa=\"int 3\" max_bounces=\"int 0\" rr_depth=\"int 2\"/>"
                      "\n<Option lockgeom=\"int 0\"/></World>",
                      "t.xml", err);
  ASSERT_TRUE(s) << err;
  EXPECT_EQ(s->settings.spp, 9);
  EXPECT_EQ(s->settings.max_depth, 0);
  ASSERT_EQ(s->warnings.size(), 1u);
  EXPECT_EQ(s->warnings[0], "t.xml:3: <Option> 'lockgeom' ignored");
  EXPECT_FALSE(parse_xml_scene("<World><Option aa=\"int x\"/></World>", "t.xml", err));
  EXPECT_EQ(err, "t.xml:1: <Option> aa expects an integer in [1, 1024], found \"int x\"");
  EXPECT_FALSE(
      parse_xml_scene("<World><Option show_albedo_scale=\"float 1\"/></World>", "t.xml", err));
  EXPECT_NE(err.find("show_albedo_scale"), std::string::npos) << err;
}

TEST(SceneXml, LightsGroupsAndBackground) {
  std::string err;
  auto s = parse_xml_scene(R"(<World>
  <ShaderGroup name="e" type="surface" commands="float power 2; shader emitter e;"/>
  <Quad corner="0 0 0" edge_x="1 0 0" edge_y="0 1 0" is_light="1"/>
  <Sphere center="0 0 0" radius="1" is_light="yes"/>
  <Sphere center="0 0 0" radius="1"/>
  <ShaderGroup>
    <Parameter Cs="color 1, 0.5, 0.25" Kd="float 0.5" name="tex.png"/>
    <Shader type="surface" name="tex" layer="t"/>
    <Shader name="matte" layer="m"/>
    <ConnectShaders srclayer="t" srcparam="Cout" dstlayer="m" dstparam="Cs"/>
  </ShaderGroup>
  <Background resolution="1"/>
</World>)",
                           "t.xml", err);
  ASSERT_TRUE(s) << err;
  EXPECT_TRUE(s->shapes[0].is_light);
  EXPECT_TRUE(s->shapes[1].is_light);
  EXPECT_FALSE(s->shapes[2].is_light);
  ASSERT_EQ(s->materials.size(), 2u);
  EXPECT_EQ(s->materials[0].name, "e");
  EXPECT_EQ(s->materials[0].group.layers[0].values[0].value, "2");
  const ShaderGroup& g = s->materials[1].group;
  ASSERT_EQ(g.layers.size(), 2u);
  EXPECT_EQ(g.layers[0].shader, "tex");
  ASSERT_EQ(g.layers[0].values.size(), 3u);
  EXPECT_EQ(g.layers[0].values[0].type, "color");
  EXPECT_EQ(g.layers[0].values[0].value, "1  0.5  0.25");
  EXPECT_EQ(g.layers[0].values[1].type, "float");
  EXPECT_EQ(g.layers[0].values[2].type, "string");
  EXPECT_EQ(g.layers[0].values[2].value, "tex.png");
  ASSERT_EQ(g.connections.size(), 1u);
  EXPECT_EQ(g.connections[0].dst_param, "Cs");
  EXPECT_EQ(s->environment.material, 1);
  EXPECT_EQ(s->environment.resolution, 256);
}

// testrender's <Background resolution="R"> tabulates R x R texels; Lobe's 2:1 table gets about
// as many (R / sqrt(2) rows: 1024 -> 724, 2 x 724 x 724 = 1.05 M texels), never under 256 rows.
TEST(SceneXml, BackgroundResolutionKeepsTestrendersTexelCount) {
  for (auto [r, rows] : {std::pair{1024, 724}, {2048, 1448}, {362, 256}, {1, 256}}) {
    std::string err;
    auto s =
        parse_xml_scene("<World><ShaderGroup>shader sky s;</ShaderGroup><Background resolution=\"" +
                            std::to_string(r) + "\"/></World>",
                        "t.xml", err);
    ASSERT_TRUE(s) << err;
    EXPECT_EQ(s->environment.resolution, rows) << r;
  }
}

TEST(SceneXml, ErrorsCarryLines) {
  std::string err;
  EXPECT_FALSE(
      parse_xml_scene("<World>\n<Sphere center=\"0 0\" radius=\"1\"/>\n</World>", "t.xml", err));
  EXPECT_EQ(err, "t.xml:2: attribute 'center' expects 3 number(s), found \"0 0\"");
  EXPECT_FALSE(parse_xml_scene("<World>\n\n<Cone/>\n</World>", "t.xml", err));
  EXPECT_EQ(err.rfind("t.xml:3: unknown element <Cone>", 0), 0u) << err;
  EXPECT_FALSE(parse_xml_scene("<World>\n<Background/>\n</World>", "t.xml", err));
  EXPECT_NE(err.find("needs a <ShaderGroup>"), std::string::npos);
  // A mistake inside a <ShaderGroup> is reported at its file line (5), not a line counted
  // inside the group.
  EXPECT_FALSE(parse_xml_scene("<World>\n<Camera fov=\"40\"/>\n<ShaderGroup>\ncolor Cs 0.5 0.5 "
                               "0.5;\nshadr matte m;\n</ShaderGroup>\n</World>",
                               "t.xml", err));
  EXPECT_EQ(err, "t.xml:5: error: expected `param`, `shader` or `connect`, found `shadr`");
  EXPECT_FALSE(parse_xml_scene("<World>\n<ShaderGroup>shader matte m;\nfloat Kd \"x;</ShaderGroup>"
                               "\n</World>",
                               "t.xml", err));
  EXPECT_EQ(err, "t.xml:3: error: unterminated string");
  EXPECT_FALSE(parse_xml_scene("<World>\n<PointLight position=\"0 1 0\" intensity=\"1 -1 1\"/>"
                               "\n</World>",
                               "t.xml", err));
  EXPECT_EQ(err, "t.xml:2: intensity expects components >= 0 (emitted light cannot be negative)");
  EXPECT_FALSE(parse_xml_scene("<World><Sphere", "t.xml", err));
  EXPECT_NE(err.find("invalid XML"), std::string::npos);
}

TEST(SceneXml, UnknownAttributesAreWarnings) {
  std::string err;
  auto s = parse_xml_scene("<World><Sphere center=\"0 0 0\" radius=\"1\" shiny=\"yes\"/></World>",
                           "t.xml", err);
  ASSERT_TRUE(s) << err;
  ASSERT_EQ(s->warnings.size(), 1u);
  EXPECT_NE(s->warnings[0].find("'shiny'"), std::string::npos);
}

TEST(GroupText, ParamsShadersAndConnections) {
  std::string err;
  auto g = parse_group_text(
      "param string name \"a b\" ; param float[2] w 1 2; shader tex t1;\n shader matte m;"
      " connect t1.Cout m.Cs ;",
      "x", false, err);
  ASSERT_TRUE(g) << err;
  ASSERT_EQ(g->layers.size(), 2u);
  ASSERT_EQ(g->layers[0].values.size(), 2u);
  EXPECT_EQ(g->layers[0].values[0].value, "a b");
  EXPECT_EQ(g->layers[0].values[1].type, "float[2]");
  EXPECT_EQ(g->layers[0].values[1].value, "1 2");
  EXPECT_TRUE(g->layers[1].values.empty());
  ASSERT_EQ(g->connections.size(), 1u);
  EXPECT_EQ(g->connections[0].src_param, "Cout");
  // Bare form only where allowed.
  EXPECT_FALSE(parse_group_text("float Kd 1; shader m l;", "x", false, err));
  EXPECT_EQ(err, "x:1: error: expected `param`, `shader` or `connect`, found `float`");
  EXPECT_TRUE(parse_group_text("float Kd 1; shader m l;", "x", true, err));
  EXPECT_FALSE(parse_group_text("shader m l;\nparam float Kd 1;", "x", false, err));
  EXPECT_EQ(err, "x:2: error: parameter values after the last `shader`");
}

// Found by fuzz_scene_xml: spp="3.7e36" passed the `>= 1` check and int(spp) was undefined.
TEST(SceneXml, HugeSettingsAreErrors) {
  std::string err;
  for (const char* a : {"spp=\"3666666666666666666666666666666666662\"", "spp=\"1048577\"",
                        "max_depth=\"1e30\"", "max_depth=\"1025\""}) {
    EXPECT_FALSE(
        parse_xml_scene(std::string("<World>\n<Settings ") + a + "/>\n</World>", "t.xml", err))
        << a;
    EXPECT_NE(err.find("t.xml:2: "), std::string::npos) << err;
    EXPECT_NE(err.find("spp expects [1, 1048576], max_depth [0, 1024], seed >= 0"),
              std::string::npos)
        << err;
  }
  auto s = parse_xml_scene("<World>\n<Settings spp=\"1048576\" max_depth=\"1024\" seed=\"7\"/>\n"
                           "</World>",
                           "t.xml", err);
  ASSERT_TRUE(s) << err;
  EXPECT_EQ(s->settings.spp, 1 << 20);
  EXPECT_EQ(s->settings.max_depth, 1024);
  EXPECT_EQ(s->settings.seed, 7u);
}
