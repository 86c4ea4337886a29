// Camera: the pinhole's field of view, and the thin lens's geometry (rays from points spread
// over the lens disc of radius `aperture` all meet at the focus plane; a point off that plane
// is seen through a circle of confusion of the size similar triangles give).
#include "camera.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace lobe;
using namespace lobe::render;

namespace {

scene::Camera looking_down_minus_z(float aperture, float focus) {
  scene::Camera c;
  c.eye = {0, 0, 0};
  c.look_at = {0, 0, -1};
  c.up = {0, 1, 0};
  c.fov = 90;
  c.aperture = aperture;
  c.focus_distance = focus;
  return c;
}

// The point where a ray crosses the plane z = -depth.
Vec3 at_depth(const Ray& r, float depth) {
  float t = (-depth - r.org.z) / r.dir.z;
  return r.org + r.dir * t;
}

TEST(Camera, PinholeFieldOfView) {
  Camera cam(looking_down_minus_z(0, 0), 100, 100);
  // fov 90: the right edge of the film looks along (1, 0, -1), the top edge along (0, 1, -1).
  Ray r = cam.generate(100, 50, 0.3f, 0.7f);
  EXPECT_NEAR(r.dir.x, std::sqrt(0.5f), 1e-6f);
  EXPECT_NEAR(r.dir.z, -std::sqrt(0.5f), 1e-6f);
  Ray t = cam.generate(50, 0, 0.3f, 0.7f);
  EXPECT_NEAR(t.dir.y, std::sqrt(0.5f), 1e-6f);
  EXPECT_EQ(r.org, (Vec3{0, 0, 0})); // no lens: every ray starts at the eye
}

TEST(Camera, ThinLensRaysMeetOnTheFocusPlane) {
  const float aperture = 0.2f, focus = 4.0f;
  Camera cam(looking_down_minus_z(aperture, focus), 64, 64);
  Ray pin = Camera(looking_down_minus_z(0, 0), 64, 64).generate(40.5f, 20.5f, 0, 0);
  Vec3 sharp = at_depth(pin, focus); // where the pinhole ray for this pixel hits the plane
  float max_r = 0;
  for (int i = 0; i < 16; ++i)
    for (int j = 0; j < 16; ++j) {
      Ray r = cam.generate(40.5f, 20.5f, (i + 0.5f) / 16, (j + 0.5f) / 16);
      Vec3 hit = at_depth(r, focus);
      EXPECT_NEAR(hit.x, sharp.x, 1e-5f);
      EXPECT_NEAR(hit.y, sharp.y, 1e-5f);
      EXPECT_NEAR(r.org.z, 0.0f, 1e-7f); // origins on the lens plane
      max_r = std::fmax(max_r, std::hypot(r.org.x, r.org.y));
      EXPECT_LE(std::hypot(r.org.x, r.org.y), aperture * (1 + 1e-5f));
    }
  EXPECT_GT(max_r, 0.9f * aperture); // the samples cover the disc
}

TEST(Camera, CircleOfConfusionFollowsSimilarTriangles) {
  // On the axis, a plane at depth z != focus is crossed within a disc of radius
  // aperture * |z - focus| / focus (rays converge to the focus point, then diverge).
  const float aperture = 0.1f, focus = 2.0f, depth = 6.0f;
  Camera cam(looking_down_minus_z(aperture, focus), 65, 65);
  float max_r = 0;
  for (int i = 0; i < 32; ++i)
    for (int j = 0; j < 32; ++j) {
      Vec3 p = at_depth(cam.generate(32.5f, 32.5f, (i + 0.5f) / 32, (j + 0.5f) / 32), depth);
      max_r = std::fmax(max_r, std::hypot(p.x, p.y));
    }
  float expected = aperture * (depth - focus) / focus; // 0.2
  EXPECT_LE(max_r, expected * 1.001f);
  EXPECT_GT(max_r, expected * 0.95f);
}

} // namespace

// project() is generate()'s inverse for the pinhole: the film position of a point along the ray
// through (fx, fy) is (fx, fy), and the cosine is the ray's with the view axis; a point behind
// the camera has none.
TEST(Camera, ProjectFindsTheFilmPositionOfAPoint) {
  scene::Camera c = looking_down_minus_z(0, 0);
  c.fov = 40;
  c.eye = {1, 2, 3};
  c.look_at = {0.5f, 1, -4};
  Camera cam(c, 64, 48);
  const float spots[][2] = {{0.5f, 0.5f}, {32, 24}, {63.25f, 1.75f}, {10.5f, 47.5f}};
  for (const auto& s : spots) {
    Ray r = cam.generate(s[0], s[1], 0.5f, 0.5f);
    float fx = -1, fy = -1, cos_axis = -1;
    ASSERT_TRUE(cam.project(r.org + r.dir * 7.5f, fx, fy, cos_axis));
    EXPECT_NEAR(fx, s[0], 2e-3f);
    EXPECT_NEAR(fy, s[1], 2e-3f);
    Vec3 axis = normalize(c.look_at - c.eye);
    EXPECT_NEAR(cos_axis, dot(r.dir, axis), 1e-5f);
    EXPECT_FALSE(cam.project(r.org - r.dir * 2.0f, fx, fy, cos_axis));
  }
}
