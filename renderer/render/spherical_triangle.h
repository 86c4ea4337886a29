// Triangles as seen from a point: their solid angle, and directions spread uniformly over it.
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

} // namespace lobe::render
