// Triangles and rectangles as seen from a point: their solid angle, and directions spread
// uniformly over it.
//
// An area light close to the point it lights, sampled by area, gives a few samples enormous
// weights (d^2 / (cos A) at the nearest points): the ceiling a centimetre above a light
// panel, a wall beside a light strip. Sampling the solid angle the triangle subtends instead
// keeps every weight below the light's radiance times that solid angle.
//
// The solid angle is Van Oosterom and Strackee's ("The Solid Angle of a Plane Triangle", IEEE
// Trans. Biomed. Eng. 30(2), 1983): tan(omega / 2) = |a.(b x c)| / (|a||b||c| + (a.b)|c| +
// (a.c)|b| + (b.c)|a|). The sampling is Arvo's ("Stratified Sampling of Spherical
// Triangles", SIGGRAPH 1995): the first number picks the area of the sub-triangle (A, B, C')
// with C' on the arc AC, the second a point on the arc from B to C' with its cosine uniform.
// Both work in double: the angles' sum minus pi loses the digits of a small triangle in float.
#pragma once

#include "lobe/vec.h"

namespace lobe::render {

// Solid angle (steradians, in [0, 2 pi]) of the triangle with corners a, b, c relative to the
// viewer; 0 for a triangle seen edge-on or degenerate.
double triangle_solid_angle(const Vec3& a, const Vec3& b, const Vec3& c);

// A unit direction from the viewer into the triangle with corners a, b, c (relative to the
// viewer), uniform over its solid angle for (u1, u2) uniform on the unit square. False when
// the triangle subtends no solid angle (edge-on, degenerate, or a corner at the viewer).
bool sample_spherical_triangle(const Vec3& a, const Vec3& b, const Vec3& c, float u1, float u2,
                               Vec3& dir);

// A rectangle as seen from a point, for points on it uniform over its solid angle: Urena,
// Fajardo and King, "An Area-Preserving Parametrization for Spherical Rectangles" (EGSR
// 2013). One set-up per viewer (four angles between the planes through its edges), then a
// point per (u, v): the first number picks the solid angle left of a line x = const, the
// second the height along that line. In float, with the corner angles summed in pairs as
// arguments of complex products (two fast_atan2, sampling.h: within 3e-7 rad): the solid angle's
// absolute error is a few 1e-7 sr (callers use it above 1e-3 sr). Cheaper than the quad's two
// triangles by Arvo's method in double, though not by much: light sampling took ~26% of the
// Cornell box's profile that way, ~21% this way.
struct SphericalRectangle {
  // From viewer `o`, the rectangle corner + s ex + t ey (s, t in [0, 1]), ex and ey at right
  // angles. solid_angle 0 when the viewer is in its plane or an edge is degenerate.
  SphericalRectangle(const Vec3& o, const Vec3& corner, const Vec3& ex, const Vec3& ey);
  // The point of the rectangle for (u, v) in [0, 1)^2, as (s, t) along ex and ey.
  void sample(float u, float v, float& s, float& t) const;

  float solid_angle = 0;

private:
  float z0 = 0, x0 = 0, y0 = 0, x1 = 0, y1 = 0, ex_len = 1, ey_len = 1;
  float b0 = 0, b1 = 0, k = 0;
};

} // namespace lobe::render
