// The shape kinds made of triangles (shape_kinds.h): a row of the table is a JSON type and an
// XML element, read, checked and built as the row says; docs/scene-format.md lists the table.
// Expected meshes are computed here from geometry (areas of a regular polygon and of a box's
// faces), not taken from the builders.
#include "shape_kinds.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>

using namespace lobe;
using namespace lobe::scene;

namespace {

SceneDesc json_ok(const std::string& text) {
  std::string err;
  auto s = parse_json_scene(text, "t.json", err);
  EXPECT_TRUE(s.has_value()) << err;
  return s ? *s : SceneDesc{};
}
std::string json_error(const std::string& text) {
  std::string err;
  EXPECT_FALSE(parse_json_scene(text, "t.json", err).has_value());
  return err;
}

Vec3 tri_normal(const Mesh& m, size_t t) {
  const uint32_t* i = &m.indices[3 * t];
  return cross(m.positions[i[1]] - m.positions[i[0]], m.positions[i[2]] - m.positions[i[0]]);
}
float area(const Mesh& m) {
  float a = 0;
  for (size_t t = 0; t < m.indices.size() / 3; ++t) a += 0.5f * length(tri_normal(m, t));
  return a;
}

TEST(ShapeKinds, CommittedDocsAreTheGeneratedOnes) {
  std::ifstream in(LOBE_SOURCE_DIR "/docs/scene-format.md", std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  std::string doc = ss.str(), regenerated = doc;
  ASSERT_TRUE(replace_scene_sections(regenerated)) << "docs/scene-format.md lost its markers";
  EXPECT_EQ(doc, regenerated)
      << "docs/scene-format.md is out of date: run scene_docs --update docs/scene-format.md";
  EXPECT_NE(shape_reference_markdown().find("| `disk` | `center` (point, 0 0 0): its centre; "),
            std::string::npos);
}

TEST(ShapeKinds, DiskIsARegularPolygonFacingItsNormal) {
  SceneDesc s = json_ok(R"({"shapes": [{"type": "disk", "center": [1, 2, 3], "normal": [0, 0, 2],
                                        "radius": 2, "segments": 8}]})");
  ASSERT_EQ(s.shapes.size(), 1u);
  const Shape& sh = s.shapes[0];
  EXPECT_EQ(sh.kind, Shape::Kind::Mesh);
  ASSERT_EQ(sh.mesh.positions.size(), 9u);
  ASSERT_EQ(sh.mesh.indices.size(), 24u);
  EXPECT_EQ(sh.mesh.uvs.size(), 18u);
  for (size_t i = 1; i < 9; ++i) {
    EXPECT_NEAR(length(sh.mesh.positions[i] - Vec3{1, 2, 3}), 2.0f, 1e-5f);
    EXPECT_NEAR(sh.mesh.positions[i].z, 3.0f, 1e-5f);
  }
  for (size_t t = 0; t < 8; ++t) EXPECT_GT(tri_normal(sh.mesh, t).z, 0.0f) << t;
  // A regular octagon of circumradius 2: (n / 2) r^2 sin(2 pi / n) = 16 sin(pi / 4).
  EXPECT_NEAR(area(sh.mesh), 16.0f * std::sqrt(0.5f), 1e-4f);
}

TEST(ShapeKinds, BoxFacesOutAndTakesItsTransform) {
  SceneDesc s = json_ok(R"({"shapes": [{"type": "box", "min": [0, 0, 0], "max": [1, 2, 3],
                                        "transform": {"translate": [10, 0, 0]}}]})");
  ASSERT_EQ(s.shapes.size(), 1u);
  const Mesh& m = s.shapes[0].mesh;
  ASSERT_EQ(m.positions.size(), 24u);
  ASSERT_EQ(m.indices.size(), 36u);
  EXPECT_NEAR(area(m), 2 * (1 * 2 + 2 * 3 + 1 * 3), 1e-4f); // 22
  Vec3 centre{10.5f, 1, 1.5f};
  for (size_t t = 0; t < 12; ++t) {
    const uint32_t* i = &m.indices[3 * t];
    Vec3 mid = (m.positions[i[0]] + m.positions[i[1]] + m.positions[i[2]]) * (1.0f / 3);
    EXPECT_GT(dot(tri_normal(m, t), mid - centre), 0.0f) << t;
  }
  for (const Vec3& p : m.positions) {
    EXPECT_GE(p.x, 10.0f);
    EXPECT_LE(p.x, 11.0f);
  }
}

TEST(ShapeKinds, DefaultsFillWhatIsLeftOut) {
  SceneDesc s = json_ok(R"({"shapes": [{"type": "disk"}, {"type": "box"}]})");
  ASSERT_EQ(s.shapes.size(), 2u);
  EXPECT_EQ(s.shapes[0].mesh.positions.size(), 65u); // 64 segments around the centre
  EXPECT_NEAR(area(s.shapes[0].mesh), 32.0f * std::sin(2 * 3.14159265f / 64), 1e-4f);
  EXPECT_NEAR(area(s.shapes[1].mesh), 24.0f, 1e-4f); // the cube [-1, 1]^3
}

TEST(ShapeKinds, BadValuesAreLocatedErrors) {
  EXPECT_EQ(json_error(R"({"shapes": [{"type": "disk", "radius": 0}]})"),
            "t.json: /shapes/0: disk: radius expects a number > 0");
  EXPECT_EQ(json_error(R"({"shapes": [{"type": "disk", "normal": [0, 0, 0]}]})"),
            "t.json: /shapes/0: disk: normal expects a non-zero vector");
  EXPECT_EQ(json_error(R"({"shapes": [{"type": "box", "min": [0, 0, 0], "max": [1, 0, 1]}]})"),
            "t.json: /shapes/0: box: max must exceed min in every coordinate");
  EXPECT_NE(json_error(R"({"shapes": [{"type": "disk", "radiuss": 1}]})")
                .find("t.json: /shapes/0/radiuss: unknown key (expected one of: type, material, "
                      "transform, userdata, center, normal, radius, segments)"),
            std::string::npos);
  EXPECT_NE(json_error(R"({"shapes": [{"type": "disk", "segments": 2.5}]})")
                .find("t.json: /shapes/0/segments: expected an integer"),
            std::string::npos);
  EXPECT_EQ(json_error(R"({"shapes": [{"type": "cone"}]})"),
            "t.json: /shapes/0/type: expected \"sphere\", \"quad\", \"mesh\", \"disk\" or \"box\", "
            "found \"cone\"");
}

TEST(ShapeKinds, XmlElementsFollowTheTable) {
  std::string err;
  auto s = parse_xml_scene("<World>\n<Disk center=\"0, 1, 0\" normal=\"0 -1 0\" radius=\"0.5\" "
                           "segments=\"4\" is_light=\"1\" glow=\"2\"/>\n<Box/>\n</World>",
                           "t.xml", err);
  ASSERT_TRUE(s.has_value()) << err;
  ASSERT_EQ(s->shapes.size(), 2u);
  const Shape& d = s->shapes[0];
  EXPECT_EQ(d.kind, Shape::Kind::Mesh);
  EXPECT_TRUE(d.is_light);
  ASSERT_EQ(d.mesh.positions.size(), 5u);
  EXPECT_NEAR(area(d.mesh), 2 * 0.25f, 1e-5f); // a square of circumradius 0.5
  EXPECT_LT(tri_normal(d.mesh, 0).y, 0.0f);    // facing -y
  ASSERT_EQ(s->warnings.size(), 1u);
  EXPECT_EQ(s->warnings[0], "t.xml:2: <Disk> attribute 'glow' ignored");
  EXPECT_NEAR(area(s->shapes[1].mesh), 24.0f, 1e-4f);

  EXPECT_FALSE(parse_xml_scene("<World>\n<Disk radius=\"x\"/></World>", "t.xml", err));
  EXPECT_EQ(err, "t.xml:2: attribute 'radius' expects a number, found \"x\"");
  EXPECT_FALSE(parse_xml_scene("<World>\n<Disk radius=\"-1\"/></World>", "t.xml", err));
  EXPECT_EQ(err, "t.xml:2: radius expects a number > 0");
  EXPECT_FALSE(parse_xml_scene("<World><disk/></World>", "t.xml", err)); // elements keep case
  EXPECT_NE(err.find("unknown element <disk>"), std::string::npos);
  EXPECT_NE(err.find("Sphere, Quad, Disk, Box, Background"), std::string::npos);
}

// A row named as a loader's own kind would never be reached: none is, and names are unique.
TEST(ShapeKinds, NamesAreTheirOwn) {
  std::span<const ShapeKind> kinds = shape_kinds();
  for (size_t i = 0; i < kinds.size(); ++i) {
    for (const char* own : {"sphere", "quad", "mesh"})
      EXPECT_EQ(find_shape_kind(own) == &kinds[i], false) << kinds[i].name;
    EXPECT_EQ(find_shape_kind(kinds[i].name), &kinds[i]) << kinds[i].name;
  }
}

TEST(ShapeKinds, ValuesParseAsTheirType) {
  const ShapeParam point{ShapeParam::Type::Point, "p", "0 0 0", ""};
  const ShapeParam count{ShapeParam::Type::Count, "n", "1", ""};
  Vec3 v;
  EXPECT_EQ(parse_shape_value(point, "1, 2,3", v), "");
  EXPECT_EQ(v.y, 2.0f);
  EXPECT_EQ(parse_shape_value(point, "1 2", v), "expects 3 numbers");
  EXPECT_EQ(parse_shape_value(point, "1 2 3 4", v), "expects 3 numbers");
  EXPECT_EQ(parse_shape_value(point, "1 nan 3", v), "expects 3 numbers");
  EXPECT_EQ(parse_shape_value(count, "12", v), "");
  EXPECT_EQ(v.x, 12.0f);
  EXPECT_NE(parse_shape_value(count, "2.5", v), "");
  EXPECT_NE(parse_shape_value(count, "0", v), "");
}

} // namespace
