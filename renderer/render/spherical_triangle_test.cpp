// Solid angles of triangles against closed forms, and directions uniform over them (counted
// in sub-triangles whose solid angles are the closed forms'). Area lights sampled this way:
// tests/render/analytic_test.cpp.
#include "sampling.h"
#include "spherical_triangle.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <numbers>

using namespace lobe;
using namespace lobe::render;

namespace {

constexpr double kPiD = std::numbers::pi;

// Solid angle of the rectangle [0, a] x [0, b] at height h above a corner (the viewer on the
// corner's normal): Omega = arctan(ab / (h sqrt(a^2 + b^2 + h^2))).
double corner_rectangle_solid_angle(double a, double b, double h) {
  return std::atan(a * b / (h * std::sqrt(a * a + b * b + h * h)));
}

// Where the direction w from the origin meets the plane of (a, b, c), in barycentric
// coordinates (b1, b2) of b and c; false if it does not meet it ahead.
bool barycentric_hit(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& w, double& b1,
                     double& b2) {
  Vec3 e1 = b - a, e2 = c - a, n = cross(e1, e2);
  double t = dot(n, a) / double(dot(n, w));
  if (!(t > 0)) return false;
  Vec3 d = w * float(t) - a;
  double d00 = dot(e1, e1), d01 = dot(e1, e2), d11 = dot(e2, e2);
  double d20 = dot(d, e1), d21 = dot(d, e2), den = d00 * d11 - d01 * d01;
  b1 = (d11 * d20 - d01 * d21) / den;
  b2 = (d00 * d21 - d01 * d20) / den;
  return true;
}

} // namespace

TEST(SphericalTriangle, SolidAnglesAreTheClosedForms) {
  // An octant: one eighth of the sphere.
  EXPECT_NEAR(triangle_solid_angle({1, 0, 0}, {0, 1, 0}, {0, 0, 1}), 4 * kPiD / 8, 1e-12);
  // Half of a rectangle above its corner, split by the diagonal through the corner: the two
  // halves of a square are mirror images, so each is half the rectangle's closed form.
  for (double h : {0.01, 0.3, 1.0, 50.0}) {
    double full = corner_rectangle_solid_angle(1, 1, h);
    Vec3 o{0, float(-h), 0};
    EXPECT_NEAR(triangle_solid_angle(Vec3{0, 0, 0} - o, Vec3{1, 0, 0} - o, Vec3{1, 0, 1} - o),
                full / 2, 1e-6 * full)
        << h;
  }
  // Far away: area x cos / d^2 to the centroid, to second order in size / distance. The
  // triangle of area 1/2 about 1000 away, tilted by 60 degrees from the line of sight.
  float c = std::cos(kPi / 3), s = std::sin(kPi / 3);
  Vec3 o{0, 0, -1000};
  Vec3 centroid = Vec3{1, c, s} / 3 - o;
  double d2 = dot(centroid, centroid), cos_view = dot(Vec3{0, -s, c}, centroid) / std::sqrt(d2);
  EXPECT_NEAR(triangle_solid_angle(Vec3{0, 0, 0} - o, Vec3{1, 0, 0} - o, Vec3{0, c, s} - o),
              0.5 * std::abs(cos_view) / d2, 1e-5 * 0.25e-6);
  // A viewer a millimetre above a large triangle sees nearly a hemisphere.
  EXPECT_NEAR(
      triangle_solid_angle({-1000, -1000, -0.001f}, {1000, -1000, -0.001f}, {0, 1000, -0.001f}),
      2 * kPiD, 1e-4);
  // Edge-on, degenerate: nothing.
  EXPECT_EQ(triangle_solid_angle({1, 0, 0}, {2, 0, 0}, {0, 1, 0}), 0);
  EXPECT_EQ(triangle_solid_angle({1, 0, 1}, {1, 0, 1}, {0, 1, 1}), 0);
}

TEST(SphericalTriangle, DirectionsAreUniformOverTheSolidAngle) {
  // Triangles seen close, far, and nearly edge-on. Each is cut into four by its edges'
  // midpoints; the samples that land in each of the four match the share of its solid
  // angle (binomial, within 4.5 standard deviations), and every direction hits the triangle.
  const std::array<std::array<Vec3, 3>, 4> tris = {{
      {{{-1, -1, 0.05f}, {2, -0.5f, 0.05f}, {0, 3, 0.05f}}}, // close: a wide cone
      {{{0, 0, 1}, {1, 0, 1}, {0, 1, 1}}},
      {{{-0.5f, 0.2f, 20}, {0.5f, 0.1f, 20}, {0, 0.9f, 21}}}, // far
      {{{1, -1, 0.02f}, {3, 0, 0.01f}, {1, 2, 0.1f}}},        // grazing
  }};
  RandomStream rng(17, 0, 5);
  for (const auto& t : tris) {
    Vec3 m01 = (t[0] + t[1]) * 0.5f, m12 = (t[1] + t[2]) * 0.5f, m20 = (t[2] + t[0]) * 0.5f;
    const std::array<std::array<Vec3, 3>, 4> parts = {
        {{{t[0], m01, m20}}, {{m01, t[1], m12}}, {{m20, m12, t[2]}}, {{m01, m12, m20}}}};
    double total = triangle_solid_angle(t[0], t[1], t[2]);
    ASSERT_GT(total, 0);
    const int n = 40000;
    int count[4] = {0, 0, 0, 0};
    for (int i = 0; i < n; ++i) {
      Vec3 w;
      ASSERT_TRUE(sample_spherical_triangle(t[0], t[1], t[2], rng.next(), rng.next(), w));
      double b1, b2;
      ASSERT_TRUE(barycentric_hit(t[0], t[1], t[2], w, b1, b2));
      ASSERT_GE(b1, -1e-4);
      ASSERT_GE(b2, -1e-4);
      ASSERT_LE(b1 + b2, 1 + 1e-4);
      // The part it falls in: corners 0, 1, 2 by their barycentric coordinate above 1/2.
      double b0 = 1 - b1 - b2;
      ++count[b0 > 0.5 ? 0 : b1 > 0.5 ? 1 : b2 > 0.5 ? 2 : 3];
    }
    double sum = 0;
    for (int k = 0; k < 4; ++k) {
      double share = triangle_solid_angle(parts[k][0], parts[k][1], parts[k][2]) / total;
      sum += share;
      double sd = std::sqrt(n * share * (1 - share));
      EXPECT_NEAR(count[k], n * share, 4.5 * sd + 1) << "part " << k << " of " << total;
    }
    EXPECT_NEAR(sum, 1, 1e-5);
  }
}

TEST(SphericalTriangle, DegenerateTrianglesGiveNoDirection) {
  Vec3 w;
  EXPECT_FALSE(sample_spherical_triangle({1, 0, 0}, {2, 0, 0}, {0, 1, 0}, 0.3f, 0.6f, w));
  EXPECT_FALSE(sample_spherical_triangle({0, 0, 0}, {1, 0, 1}, {0, 1, 1}, 0.3f, 0.6f, w));
  // The square's corners of the unit square: u = 0 and u -> 1 stay inside.
  for (float u1 : {0.0f, 0x1.fffffep-1f})
    for (float u2 : {0.0f, 0x1.fffffep-1f}) {
      ASSERT_TRUE(sample_spherical_triangle({0, 0, 1}, {1, 0, 1}, {0, 1, 1}, u1, u2, w));
      EXPECT_GE(w.z, 0.5f);
      EXPECT_GE(w.x, -1e-6f);
      EXPECT_GE(w.y, -1e-6f);
    }
}

namespace {

// Solid angle of the part [s0, s1] x [t0, t1] of the rectangle corner + s ex + t ey from o,
// as two triangles in double (triangle_solid_angle, tested above against closed forms).
double part_solid_angle(const Vec3& o, const Vec3& c, const Vec3& ex, const Vec3& ey, float s0,
                        float s1, float t0, float t1) {
  Vec3 p00 = c + ex * s0 + ey * t0 - o, p10 = c + ex * s1 + ey * t0 - o;
  Vec3 p11 = c + ex * s1 + ey * t1 - o, p01 = c + ex * s0 + ey * t1 - o;
  return triangle_solid_angle(p00, p10, p11) + triangle_solid_angle(p00, p11, p01);
}

} // namespace

TEST(SphericalRectangle, SolidAngleIsTheClosedForm) {
  // Above a corner: the closed form; elsewhere (beside, behind, grazing, far): two triangles.
  for (double h : {0.01, 0.3, 1.0, 20.0}) {
    SphericalRectangle r({0, 0, float(-h)}, {0, 0, 0}, {2, 0, 0}, {0, 1, 0});
    double expected = corner_rectangle_solid_angle(2, 1, h);
    EXPECT_NEAR(r.solid_angle, expected, 2e-6 + 1e-5 * expected) << h;
  }
  const Vec3 c{-0.25f, 0.99f, -0.25f}, ex{0.5f, 0, 0}, ey{0, 0, 0.5f};
  for (Vec3 o : {Vec3{0, 1, 0}, Vec3{0.6f, 1, 0.1f}, Vec3{0.3f, 0.9f, -0.4f}, Vec3{0, -1, 0},
                 Vec3{-2, 0.98f, 1}, Vec3{0.1f, 0.991f, 0.05f}}) {
    SphericalRectangle r(o, c, ex, ey);
    double expected = part_solid_angle(o, c, ex, ey, 0, 1, 0, 1);
    EXPECT_NEAR(r.solid_angle, expected, 2e-6 + 1e-5 * expected) << o.x << "," << o.y;
  }
  // In its plane: nothing.
  EXPECT_EQ(SphericalRectangle({1, 0.99f, 0}, c, ex, ey).solid_angle, 0);
}

TEST(SphericalRectangle, PointsAreUniformOverTheSolidAngle) {
  // Seen from close above, from the side at a grazing angle, and from far: the samples in
  // each quarter of the rectangle match its share of the solid angle (4.5 standard
  // deviations), and (s, t) stay inside.
  const Vec3 c{-0.25f, 0.99f, -0.25f}, ex{0.5f, 0, 0}, ey{0, 0, 0.7f};
  RandomStream rng(23, 0, 2);
  for (Vec3 o : {Vec3{0.05f, 1.0f, 0.1f}, Vec3{0.6f, 1.002f, 0}, Vec3{0.1f, -3, 0.4f}}) {
    SphericalRectangle r(o, c, ex, ey);
    ASSERT_GT(r.solid_angle, 1e-3f);
    const int n = 40000;
    int count[4] = {0, 0, 0, 0};
    for (int i = 0; i < n; ++i) {
      float s, t;
      r.sample(rng.next(), rng.next(), s, t);
      ASSERT_GE(s, 0);
      ASSERT_LE(s, 1);
      ASSERT_GE(t, 0);
      ASSERT_LE(t, 1);
      ++count[(s >= 0.5f) + 2 * (t >= 0.5f)];
    }
    double total = part_solid_angle(o, c, ex, ey, 0, 1, 0, 1);
    for (int k = 0; k < 4; ++k) {
      float s0 = k & 1 ? 0.5f : 0, t0 = k & 2 ? 0.5f : 0;
      double share = part_solid_angle(o, c, ex, ey, s0, s0 + 0.5f, t0, t0 + 0.5f) / total;
      double sd = std::sqrt(n * share * (1 - share));
      EXPECT_NEAR(count[k], n * share, 4.5 * sd + 1) << "quarter " << k << " from " << o.x;
    }
  }
}
