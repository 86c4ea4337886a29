// Embree geometry: hits land where analytic ray/shape intersection says, surface data is
// consistent, occlusion works, and offset origins never re-hit their own surface.
#include "geometry.h"
#include "sampling.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>

using namespace lobe;
using namespace lobe::render;

namespace {
std::vector<scene::Shape> two_shapes() {
  scene::Shape sphere;
  sphere.kind = scene::Shape::Kind::Sphere;
  sphere.center = {0, 1, 0};
  sphere.radius = 1;
  scene::Shape quad;
  quad.kind = scene::Shape::Kind::Quad;
  quad.corner = {-5, 0, 5};
  quad.edge_x = {10, 0, 0};
  quad.edge_y = {0, 0, -10}; // cross(x, -z) = +y: faces up
  return {sphere, quad};
}
} // namespace

TEST(Geometry, SphereAndQuadHits) {
  auto shapes = two_shapes();
  Geometry g;
  ASSERT_EQ(g.build(shapes), "");
  SurfaceHit h;
  ASSERT_TRUE(g.intersect({{0, 1, 5}, {0, 0, -1}}, h));
  EXPECT_EQ(h.shape, 0);
  EXPECT_NEAR(h.t, 4.0f, 1e-5);
  EXPECT_NEAR(h.Ng.z, 1.0f, 1e-5);
  ASSERT_TRUE(g.intersect({{3, 2, 0}, {0, -1, 0}}, h));
  EXPECT_EQ(h.shape, 1);
  EXPECT_NEAR(h.t, 2.0f, 1e-5);
  EXPECT_NEAR(h.Ng.y, 1.0f, 1e-6);
  // uv over the quad: corner (-5, 0, 5) + 0.8 * edge_x + 0.5 * edge_y.
  EXPECT_NEAR(h.u, 0.8f, 1e-5);
  EXPECT_NEAR(h.v, 0.5f, 1e-5);
  EXPECT_NEAR(h.dPdu.x, 10.0f, 1e-4);
  EXPECT_FALSE(g.intersect({{0, 3, 0}, {0, 1, 0}}, h));
  EXPECT_TRUE(g.occluded({0, 1, 5}, {0, 0, -1}, 10));
  EXPECT_FALSE(g.occluded({0, 1, 5}, {0, 0, -1}, 3.9f));
}

TEST(Geometry, SphereTangentsAreDerivatives) {
  auto shapes = two_shapes();
  Geometry g;
  ASSERT_EQ(g.build(shapes), "");
  SurfaceHit h;
  ASSERT_TRUE(g.intersect({{2, 1.3f, 3}, normalize(Vec3{-2, 0.1f, -3})}, h));
  // Central differences of the documented parametrisation, in double precision:
  // phi = 2 pi (u - 0.5), theta = pi v, P = c + r (sin t sin p, cos t, sin t cos p).
  auto P = [](double u, double v) {
    double ph = 2 * M_PI * (u - 0.5), th = M_PI * v;
    return std::array<double, 3>{std::sin(th) * std::sin(ph), 1 + std::cos(th),
                                 std::sin(th) * std::cos(ph)};
  };
  auto p0 = P(h.u, h.v);
  EXPECT_NEAR(p0[0], h.P.x, 1e-5);
  EXPECT_NEAR(p0[1], h.P.y, 1e-5);
  const double e = 1e-5;
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR((P(h.u + e, h.v)[k] - P(h.u - e, h.v)[k]) / (2 * e), h.dPdu[k], 1e-3);
    EXPECT_NEAR((P(h.u, h.v + e)[k] - P(h.u, h.v - e)[k]) / (2 * e), h.dPdv[k], 1e-3);
  }
}

TEST(Geometry, OffsetOriginsAvoidSelfIntersection) {
  auto shapes = two_shapes();
  Geometry g;
  ASSERT_EQ(g.build(shapes), "");
  RandomStream s(3, 0, 0);
  int self_hits = 0, leaks = 0;
  for (int i = 0; i < 2000; ++i) {
    // Random points on the sphere far from the origin's float grid, rays leaving outwards.
    Vec3 d = square_to_uniform_sphere(s.next(), s.next());
    SurfaceHit h;
    if (!g.intersect({Vec3{0, 1, 0} + d * 50.0f, -d}, h) || h.shape != 0) continue;
    Vec3 out = normalize(h.Ng + square_to_uniform_sphere(s.next(), s.next()) * 0.9f);
    if (dot(out, h.Ng) <= 0.01f) continue;
    SurfaceHit h2;
    if (g.intersect({offset_ray_origin(h.P, h.Ng, out), out}, h2) && h2.shape == 0) ++self_hits;
    // Going inwards must hit the sphere's far side, not escape (no leak through the surface).
    Vec3 in = -out;
    if (!g.intersect({offset_ray_origin(h.P, h.Ng, in), in}, h2) || h2.shape != 0 || h2.t < 1e-3f)
      ++leaks;
  }
  EXPECT_EQ(self_hits, 0);
  EXPECT_EQ(leaks, 0);
}
