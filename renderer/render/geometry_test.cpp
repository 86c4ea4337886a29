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

// A packet finds what single rays find, for every packet size and with rays that miss, start
// inside the sphere or stop short (tmax): the sphere hit from (0, 1, 5) towards -z at t = 4,
// the quad's at |y| / dy, nothing upwards.
TEST(Geometry, PacketsFindTheHitsOfSingleRays) {
  auto shapes = two_shapes();
  Geometry g;
  ASSERT_EQ(g.build(shapes), "");
  RandomStream rng(11, 0, 0);
  std::vector<Ray> rays;
  rays.push_back({{0, 1, 5}, {0, 0, -1}});               // the sphere at t = 4
  rays.push_back({{3, 2, 0}, {0, -1, 0}});               // the quad at t = 2
  rays.push_back({{0, 3, 0}, {0, 1, 0}});                // nothing
  rays.push_back({{0, 1, 5}, {0, 0, -1}, 3.5f});         // stops short of the sphere
  rays.push_back({{0, 1, 0}, normalize(Vec3{1, 1, 0})}); // from inside the sphere
  for (int i = 0; i < 43; ++i) {
    Vec3 org{rng.next() * 6 - 3, rng.next() * 3 + 0.5f, 6};
    Vec3 dir = normalize(Vec3{rng.next() - 0.5f, rng.next() - 0.8f, -1});
    rays.push_back({org, dir});
  }
  int hits = 0, misses = 0;
  for (int n = 1; n <= Geometry::kPacket; ++n)
    for (size_t first = 0; first + size_t(n) <= rays.size(); first += size_t(n)) {
      Geometry::RawHit packet[Geometry::kPacket];
      g.traverse_packet(&rays[first], n, packet);
      for (int i = 0; i < n; ++i) {
        Geometry::RawHit single;
        bool found = g.traverse(rays[first + size_t(i)], single);
        ASSERT_EQ(packet[i].geom != RTC_INVALID_GEOMETRY_ID, found) << first + size_t(i);
        (found ? hits : misses)++;
        if (!found) continue;
        EXPECT_EQ(packet[i].geom, single.geom);
        EXPECT_EQ(packet[i].prim, single.prim);
        EXPECT_NEAR(packet[i].t, single.t, 1e-5f * single.t);
        EXPECT_NEAR(packet[i].u, single.u, 1e-5f);
        EXPECT_NEAR(packet[i].v, single.v, 1e-5f);
      }
    }
  EXPECT_GT(hits, 100);
  EXPECT_GT(misses, 50);
  Geometry::RawHit four[4];
  g.traverse_packet(rays.data(), 4, four);
  EXPECT_NEAR(four[0].t, 4.0f, 1e-5f);
  EXPECT_NEAR(four[1].t, 2.0f, 1e-5f);
  EXPECT_EQ(four[2].geom, RTC_INVALID_GEOMETRY_ID);
  EXPECT_EQ(four[3].geom, RTC_INVALID_GEOMETRY_ID);
}
