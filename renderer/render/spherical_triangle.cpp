// Solid angles of triangles and uniform directions over them (see spherical_triangle.h).
#include "spherical_triangle.h"

#include "sampling.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace lobe::render {
namespace {

struct D3 {
  double x, y, z;
};
D3 d3(const Vec3& v) { return {v.x, v.y, v.z}; }
D3 operator-(const D3& a, const D3& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
D3 operator+(const D3& a, const D3& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
D3 operator*(const D3& a, double s) { return {a.x * s, a.y * s, a.z * s}; }
double dot(const D3& a, const D3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
D3 cross(const D3& a, const D3& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
double length(const D3& a) { return std::sqrt(dot(a, a)); }
// Unit copy; zero for a zero vector.
D3 unit(const D3& a) {
  double l = length(a);
  return l > 0 ? a * (1 / l) : D3{0, 0, 0};
}
// The angle between two vectors of any length, accurate near 0 and pi alike.
double angle(const D3& a, const D3& b) { return std::atan2(length(cross(a, b)), dot(a, b)); }

} // namespace

double triangle_solid_angle(const Vec3& a, const Vec3& b, const Vec3& c) {
  D3 A = d3(a), B = d3(b), C = d3(c);
  double la = length(A), lb = length(B), lc = length(C);
  double num = std::abs(dot(A, cross(B, C)));
  double den = la * lb * lc + dot(A, B) * lc + dot(A, C) * lb + dot(B, C) * la;
  if (!(num > 0)) return 0; // edge-on, degenerate, or NaN
  double omega = 2 * std::atan2(num, den);
  return std::isfinite(omega) ? omega : 0;
}

bool sample_spherical_triangle(const Vec3& a, const Vec3& b, const Vec3& c, float u1, float u2,
                               Vec3& dir) {
  D3 A = unit(d3(a)), B = unit(d3(b)), C = unit(d3(c));
  // The interior angles at the three corners: between the great circles through them.
  double alpha = angle(cross(A, B), cross(A, C));
  double beta = angle(cross(B, C), cross(B, A));
  double gamma = angle(cross(C, A), cross(C, B));
  double area = alpha + beta + gamma - std::numbers::pi;
  if (!(area > 0) || !std::isfinite(area)) return false;
  // The sub-triangle (A, B, C') of area u1 * area: C' on the arc from A to C, at the cosine q
  // from A that Arvo's equation gives.
  double area_sub = double(u1) * area;
  double s = std::sin(area_sub - alpha), t = std::cos(area_sub - alpha);
  double ca = std::cos(alpha), sa = std::sin(alpha);
  double u = t - ca, v = s + sa * dot(A, B);
  double den = (v * s + u * t) * sa;
  double q = den != 0 ? ((v * t - u * s) * ca - v) / den : 1.0;
  q = std::clamp(std::isfinite(q) ? q : 1.0, -1.0, 1.0);
  D3 c_perp = unit(C - A * dot(C, A));
  D3 c2 = A * q + c_perp * std::sqrt(std::max(0.0, 1 - q * q));
  // A point on the arc from B to C' with its cosine from B uniform.
  double z = 1 - double(u2) * (1 - dot(c2, B));
  D3 b_perp = unit(c2 - B * dot(c2, B));
  D3 w = B * z + b_perp * std::sqrt(std::max(0.0, 1 - z * z));
  dir = Vec3{float(w.x), float(w.y), float(w.z)};
  dir = normalize(dir);
  return !is_zero(dir);
}

SphericalRectangle::SphericalRectangle(const Vec3& o, const Vec3& corner, const Vec3& ex,
                                       const Vec3& ey) {
  ex_len = length(ex), ey_len = length(ey);
  if (!(ex_len > 0) || !(ey_len > 0)) return;
  // The rectangle's frame: x, y along its edges, z towards the viewer's side (z0 < 0).
  Vec3 x = ex / ex_len, y = ey / ey_len, z = cross(x, y), d = corner - o;
  z0 = dot(d, z);
  if (z0 > 0) z0 = -z0;
  if (!(z0 < 0)) return;
  x0 = dot(d, x), y0 = dot(d, y), x1 = x0 + ex_len, y1 = y0 + ey_len;
  // The interior angles g0..g3 at the corners (x1, y0), (x1, y1), (x0, y1), (x0, y0): each
  // between the planes through the viewer and the two edges meeting there, whose normals in
  // this frame are (0, z0, -y0), (-z0, 0, x1), (0, -z0, y1), (z0, 0, -x0) (the cross products
  // of consecutive corners, lengths dropped). The angle between -n_i and n_i+1 is the
  // argument of (-n_i . n_i+1) + i |n_i x n_i+1|, which works out to the corner's two
  // coordinates' product and |z0| times its distance; only the sums g0 + g1 and g2 + g3 are
  // needed, so each is the argument of a product of two such numbers (in double, against
  // overflow; arguments are unchanged by the factors' lengths): two atan2 instead of four.
  const double az = std::abs(z0);
  auto dist = [&](float a, float b) { return std::sqrt(double(a) * a + double(b) * b + az * az); };
  auto pair_angle = [](double re1, double im1, double re2, double im2) {
    double re = re1 * re2 - im1 * im2, im = re1 * im2 + im1 * re2;
    double m = std::max(std::abs(re), std::abs(im));
    if (!(m > 0)) return 0.0f;
    // Each angle is in (0, pi), so the sum is in (0, 2 pi): unwrap a negative argument.
    float a = fast_atan2(float(im / m), float(re / m));
    return a < 0 ? a + 2 * std::numbers::pi_v<float> : a;
  };
  float g01 = pair_angle(double(y0) * x1, az * dist(x1, y0), -double(x1) * y1, az * dist(x1, y1));
  float g23 = pair_angle(double(x0) * y1, az * dist(x0, y1), -double(x0) * y0, az * dist(x0, y0));
  b0 = -y0 / std::sqrt(z0 * z0 + y0 * y0), b1 = y1 / std::sqrt(z0 * z0 + y1 * y1);
  k = 2 * std::numbers::pi_v<float> - g23;
  float omega = g01 - k;
  solid_angle = omega > 0 && std::isfinite(omega) ? omega : 0;
}

void SphericalRectangle::sample(float u, float v, float& s, float& t) const {
  // x: where the solid angle to its left is u of the whole.
  float au = u * solid_angle + k;
  float fu = (std::cos(au) * b0 - b1) / std::sin(au);
  float cu = std::clamp(std::copysign(1.0f, fu) / std::sqrt(fu * fu + b0 * b0), -1.0f, 1.0f);
  float xu = -(cu * z0) / std::max(std::sqrt(1 - cu * cu), 1e-12f);
  xu = std::clamp(std::isfinite(xu) ? xu : x1, x0, x1);
  // y: the height along that line with the cosine-like h uniform between its ends.
  float dd = std::sqrt(xu * xu + z0 * z0);
  float h0 = y0 / std::sqrt(dd * dd + y0 * y0), h1 = y1 / std::sqrt(dd * dd + y1 * y1);
  float hv = h0 + v * (h1 - h0), hv2 = hv * hv;
  float yv = hv2 < 1 - 1e-6f ? hv * dd / std::sqrt(1 - hv2) : y1;
  yv = std::clamp(yv, y0, y1);
  s = std::clamp((xu - x0) / ex_len, 0.0f, 1.0f);
  t = std::clamp((yv - y0) / ey_len, 0.0f, 1.0f);
}

} // namespace lobe::render
