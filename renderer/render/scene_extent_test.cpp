// check_scene_extent: positions single-precision ray tracing cannot resolve (Embree asserts on
// ray origins beyond about 1.8e18) are errors naming their place, before anything is built.
#include "scene_setup.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace lobe;

TEST(SceneExtent, OrdinaryScenesPass) {
  scene::SceneDesc d;
  d.path = "s.json";
  scene::Shape s;
  s.center = {1e6f, 0, 0};
  s.radius = 1e3f;
  d.shapes.push_back(s);
  EXPECT_EQ(render::check_scene_extent(d), "");
}

TEST(SceneExtent, FarOrNonFinitePositionsAreNamed) {
  scene::SceneDesc d;
  d.path = "s.json";
  d.camera.eye = {1e17f, 0, 0};
  EXPECT_EQ(render::check_scene_extent(d),
            "s.json: camera: eye (1e+17, 0, 0) is not finite or lies farther than 1e+15 from the "
            "origin");
  d.camera.eye = {0, 1, 5};
  scene::Shape m;
  m.kind = scene::Shape::Kind::Mesh;
  m.where = "s.json: /shapes/2";
  m.mesh.positions = {{0, 0, 0}, {1, 0, 0}, {0, NAN, 0}};
  d.shapes.push_back(m);
  EXPECT_EQ(render::check_scene_extent(d),
            "s.json: /shapes/2: vertex 2 (0, nan, 0) is not finite or lies farther than 1e+15 "
            "from the origin");
  d.shapes[0].mesh.positions[2].y = 0;
  scene::Light l;
  l.position = {0, -INFINITY, 0};
  l.where = "s.json: /lights/0";
  d.lights.push_back(l);
  EXPECT_NE(render::check_scene_extent(d).find("s.json: /lights/0: position"), std::string::npos);
}

// geometry_bytes: the figure set-up checks against the memory before building. Two meshes of 2
// and 1 triangles (4 and 3 vertices) and a sphere (no mesh): 3 x 256 + 7 x 64 = 1216 bytes.
TEST(SceneMemory, GeometryBytesCountTrianglesAndVertices) {
  scene::SceneDesc d;
  scene::Shape a, b, sphere;
  a.kind = b.kind = scene::Shape::Kind::Mesh;
  a.mesh.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}};
  a.mesh.indices = {0, 1, 2, 1, 3, 2};
  b.mesh.positions = {{0, 0, 1}, {1, 0, 1}, {0, 1, 1}};
  b.mesh.indices = {0, 1, 2};
  sphere.radius = 1;
  d.shapes = {a, b, sphere};
  EXPECT_EQ(render::geometry_bytes(d), 3 * 256.0 + 7 * 64.0);
}
