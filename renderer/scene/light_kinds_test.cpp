// The light kinds (light_kinds.h): a row of the table is a JSON type and an XML element, read
// and checked as the row says, with the emission profile and solid angle its functions give.
// Expected values are closed forms (a cone's solid angle, the smoothstep edge), written here.
#include "light_kinds.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace lobe;
using namespace lobe::scene;

namespace {

constexpr double kPi = 3.14159265358979323846;

std::string json_error(const std::string& text) {
  std::string err;
  EXPECT_FALSE(parse_json_scene(text, "t.json", err).has_value());
  return err;
}

TEST(LightKinds, PointShinesEveryWay) {
  const LightKind* k = find_light_kind("point");
  ASSERT_NE(k, nullptr);
  EXPECT_NEAR(k->solid_angle({}), 4 * kPi, 1e-5);
  EXPECT_EQ(k->profile({}, Vec3{0, 0, 1}), 1.0f);
  EXPECT_EQ(light_element(*k), "PointLight");
}

TEST(LightKinds, SpotIsAConeWithASmoothEdge) {
  std::string err;
  auto s = parse_json_scene(R"({"lights": [{"type": "spot", "position": [0, 4, 0],
      "look_at": [0, 0, 0], "cone_angle": 30, "falloff_angle": 10}]})",
                            "t.json", err);
  ASSERT_TRUE(s) << err;
  const Light& l = s->lights[0];
  ASSERT_NE(l.kind, nullptr);
  EXPECT_STREQ(l.kind->name, "spot");
  EXPECT_FLOAT_EQ(l.values[0].y, -1.0f); // the axis, towards look_at, unit
  // 2 pi (1 - cos 30 deg)
  EXPECT_NEAR(l.kind->solid_angle(l.values), 2 * kPi * (1 - std::cos(kPi / 6)), 1e-5);
  auto at = [&](double deg) {
    double r = deg * kPi / 180;
    return l.kind->profile(l.values, Vec3{float(std::sin(r)), float(-std::cos(r)), 0});
  };
  EXPECT_FLOAT_EQ(at(0), 1.0f);
  EXPECT_FLOAT_EQ(at(19), 1.0f); // inside cone - falloff
  EXPECT_EQ(at(31), 0.0f);       // outside the cone
  // Halfway across the edge in cosine, the smoothstep is 1/2.
  double c_mid = 0.5 * (std::cos(kPi / 6) + std::cos(kPi / 9));
  EXPECT_NEAR(at(std::acos(c_mid) * 180 / kPi), 0.5, 1e-4);
  // `direction` wins over look_at; left out, both: straight down.
  s = parse_json_scene(R"({"lights": [{"type": "spot", "position": [0, 4, 0],
      "look_at": [0, 0, 0], "direction": [2, 0, 0]}, {"type": "spot", "position": [0, 1, 0]}]})",
                       "t.json", err);
  ASSERT_TRUE(s) << err;
  EXPECT_FLOAT_EQ(s->lights[0].values[0].x, 1.0f);
  EXPECT_FLOAT_EQ(s->lights[1].values[0].y, -1.0f);
  EXPECT_FLOAT_EQ(s->lights[1].values[2].x, 30.0f); // the defaults
  EXPECT_FLOAT_EQ(s->lights[1].values[3].x, 5.0f);
}

TEST(LightKinds, BadValuesAreLocatedErrors) {
  EXPECT_EQ(json_error(R"({"lights": [{"type": "spot", "position": [0, 1, 0],
      "cone_angle": 95}]})"),
            "t.json: /lights/0/cone_angle: expected degrees in (0, 90]");
  EXPECT_EQ(json_error(R"({"lights": [{"type": "spot", "position": [0, 1, 0],
      "cone_angle": 20, "falloff_angle": 25}]})"),
            "t.json: /lights/0/falloff_angle: expected degrees in [0, cone_angle]");
  EXPECT_EQ(json_error(R"({"lights": [{"type": "spot", "position": [0, 1, 0],
      "look_at": [0, 1, 0]}]})"),
            "t.json: /lights/0: spot direction is zero");
  EXPECT_EQ(json_error(R"({"lights": [{"type": "laser", "position": [0, 1, 0]}]})"),
            "t.json: /lights/0/type: expected \"point\" or \"spot\", found \"laser\"");
  EXPECT_NE(json_error(R"({"lights": [{"type": "point", "position": [0, 1, 0], "cone_angle": 9}]})")
                .find("/lights/0/cone_angle: unknown key (expected one of: type, position, "
                      "intensity, color)"),
            std::string::npos);
}

TEST(LightKinds, XmlElementsFollowTheTable) {
  std::string err;
  auto s = parse_xml_scene("<World>\n<SpotLight position=\"0 3 0\" intensity=\"5 5 5\" "
                           "cone_angle=\"20\" beam=\"1\"/>\n<PointLight position=\"1 1 1\" "
                           "intensity=\"1 1 1\"/>\n</World>",
                           "t.xml", err);
  ASSERT_TRUE(s.has_value()) << err;
  ASSERT_EQ(s->lights.size(), 2u);
  EXPECT_STREQ(s->lights[0].kind->name, "spot");
  EXPECT_FLOAT_EQ(s->lights[0].values[2].x, 20.0f);
  EXPECT_FLOAT_EQ(s->lights[0].intensity.x, 5.0f);
  EXPECT_STREQ(s->lights[1].kind->name, "point");
  ASSERT_EQ(s->warnings.size(), 1u);
  EXPECT_EQ(s->warnings[0], "t.xml:2: <SpotLight> attribute 'beam' ignored");
  EXPECT_FALSE(parse_xml_scene("<World>\n<SpotLight position=\"0 3 0\" intensity=\"1 1 1\" "
                               "cone_angle=\"120\"/></World>",
                               "t.xml", err));
  EXPECT_EQ(err, "t.xml:2: cone_angle: expected degrees in (0, 90]");
}

TEST(LightKinds, CommittedDocsListTheTable) {
  std::string md = light_reference_markdown();
  EXPECT_NE(md.find("| `spot` | `<SpotLight>` | `direction` (vector, 0 -1 0): "), std::string::npos)
      << md;
  EXPECT_NE(md.find("| `point` | `<PointLight>` | - | "), std::string::npos) << md;
}

} // namespace
