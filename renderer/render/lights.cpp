// Light selection and sampling (see lights.h).
#include "lights.h"

#include "light_kinds.h"

#include "sampling.h"
#include "spherical_triangle.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace lobe::render {

void LightSet::build(const Geometry& geo, const std::vector<scene::Light>& lights,
                     const std::vector<Emitter>& emitters, const EnvironmentLight* env) {
  geo_ = &geo;
  env_ = env && env->valid() ? env : nullptr;
  points_ = lights;
  std::vector<float> power;
  for (const scene::Light& l : lights) {
    float solid = l.kind ? l.kind->solid_angle(l.values) : 4 * kPi; // no kind: a point light
    power.push_back(solid * luminance(l.intensity));
  }
  shape_to_area_.assign(geo.shapes().size(), -1);
  for (const Emitter& e : emitters) {
    Area a{e.shape, 0, {}};
    const scene::Shape& s = geo.shapes()[e.shape];
    if (s.kind == scene::Shape::Kind::Sphere) {
      a.total_area = 4 * kPi * s.radius * s.radius;
    } else {
      const scene::Mesh& m = geo.mesh(e.shape);
      std::vector<float> areas(m.indices.size() / 3);
      for (size_t t = 0; t < areas.size(); ++t) {
        const uint32_t* i = &m.indices[3 * t];
        areas[t] = 0.5f * length(cross(m.positions[i[1]] - m.positions[i[0]],
                                       m.positions[i[2]] - m.positions[i[0]]));
        a.total_area += areas[t];
      }
      a.triangles = Distribution1D(areas);
      float ex = length(s.edge_x), ey = length(s.edge_y);
      a.rectangle = s.kind == scene::Shape::Kind::Quad &&
                    std::abs(dot(s.edge_x, s.edge_y)) <= 1e-5f * ex * ey && ex * ey > 0;
      if (areas.size() <= size_t(kSolidAngleTriangles))
        for (size_t t = 0; t < areas.size(); ++t) {
          const uint32_t* i = &m.indices[3 * t];
          a.corners.push_back({m.positions[i[0]], m.positions[i[1]], m.positions[i[2]]});
        }
    }
    if (!(a.total_area > 0)) continue;
    shape_to_area_[e.shape] = static_cast<int>(areas_.size());
    areas_.push_back(std::move(a));
    power.push_back(e.power);
  }
  if (env_) {
    float r = geo.radius();
    power.push_back(kPi * kPi * r * r * env_->average_luminance());
  }
  count_ = static_cast<int>(power.size());
  // A light whose power estimate is zero keeps a small share so it is never unsampleable.
  float mx = 0;
  for (float p : power) mx = std::max(mx, p);
  for (float& p : power) p = std::max(p, 1e-3f * mx + 1e-12f);
  if (count_) select_ = Distribution1D(power);
}

bool LightSet::sample(const Vec3& p, const Vec3& n, float u_select, float u1, float u2,
                      LightSample& out) const {
  if (!count_) return false;
  float prob;
  int i = select_.sample_discrete(u_select, prob);
  if (i < int(points_.size())) {
    const scene::Light& l = points_[i];
    Vec3 d = l.position - p;
    float d2 = dot(d, d);
    if (!(d2 > 0)) return false;
    out.kind = LightSample::Kind::Point;
    out.dist = std::sqrt(d2);
    out.wi = d / out.dist;
    out.L = l.intensity / d2;
    if (l.kind) out.L *= l.kind->profile(l.values, -out.wi); // its emission profile
    out.pdf = prob;
    return !is_zero(out.L);
  }
  i -= int(points_.size());
  if (i < int(areas_.size())) {
    if (!sample_area(areas_[i], p, u1, u2, out)) return false;
    out.pdf *= prob;
    return out.pdf > 0;
  }
  float pdf;
  out.kind = LightSample::Kind::Environment;
  out.wi = env_->sample(n, u1, u2, pdf, out.L);
  out.dist = std::numeric_limits<float>::infinity();
  out.pdf = pdf * prob;
  return out.pdf > 0;
}

bool LightSet::sample_area(const Area& a, const Vec3& p, float u1, float u2,
                           LightSample& out) const {
  const scene::Shape& s = geo_->shapes()[a.shape];
  out.kind = LightSample::Kind::Area;
  SurfaceHit& h = out.surface;
  double solid_pdf = 0; // by solid angle: its density, known here
  if (s.kind == scene::Shape::Kind::Sphere) {
    Vec3 dc = s.center - p;
    float d2 = dot(dc, dc), r2 = s.radius * s.radius;
    if (d2 <= r2 * 1.0001f) { // inside (or on) the sphere: uniform area
      h.P = s.center + square_to_uniform_sphere(u1, u2) * s.radius;
    } else { // the cone of directions the sphere subtends
      float dist = std::sqrt(d2), cos_max = std::sqrt(std::max(0.0f, 1 - r2 / d2));
      Vec3 w = Frame(dc / dist).to_world(square_to_uniform_cone(u1, u2, cos_max));
      // Nearest intersection of p + t w with the sphere (clamped to the tangent point).
      float b = dot(w, dc), disc = std::max(0.0f, b * b - (d2 - r2));
      h.P = p + w * (b - std::sqrt(disc));
    }
    geo_->surface(a.shape, 0, 0, 0, h);
  } else if (SphericalRectangle r = rectangle(a, p); r.solid_angle > 0) {
    // A point uniform over the rectangle's solid angle, on the quad mesh's triangles
    // (geometry.cpp's quad_mesh: 0 is corner, +ex, +ex+ey; 1 is corner, +ex+ey, +ey).
    float sp, tp;
    r.sample(u1, u2, sp, tp);
    if (sp >= tp)
      geo_->surface(a.shape, 0, sp - tp, tp, h);
    else
      geo_->surface(a.shape, 1, sp, tp - sp, h);
    solid_pdf = 1 / double(r.solid_angle);
  } else if (double omega[kSolidAngleTriangles], total = solid_angles(a, p, omega); total > 0) {
    // A triangle by its share of the solid angle (u1 re-used within the chosen share), a
    // direction uniform in it, and the point where that direction meets its plane.
    int t = 0, n = int(a.corners.size());
    double x = double(u1) * total;
    while (t < n - 1 && (x >= omega[t] || omega[t] == 0)) x -= omega[t++];
    float ur = omega[t] > 0 ? float(std::clamp(x / omega[t], 0.0, 1.0)) : 0.5f;
    const std::array<Vec3, 3>& v = a.corners[size_t(t)];
    Vec3 w;
    if (!sample_spherical_triangle(v[0] - p, v[1] - p, v[2] - p, std::min(ur, 0x1.fffffep-1f), u2,
                                   w))
      return false;
    Vec3 e1 = v[1] - v[0], e2 = v[2] - v[0], ng = cross(e1, e2);
    float along = dot(ng, w);
    if (along == 0) return false;
    float dist = dot(ng, v[0] - p) / along;
    if (!(dist > 0)) return false;
    // Barycentric coordinates of the point, kept inside the triangle (rounding).
    Vec3 d = p + w * dist - v[0];
    float d00 = dot(e1, e1), d01 = dot(e1, e2), d11 = dot(e2, e2);
    float d20 = dot(d, e1), d21 = dot(d, e2), den = d00 * d11 - d01 * d01;
    if (!(den > 0)) return false;
    float b1 = std::max(0.0f, (d11 * d20 - d01 * d21) / den);
    float b2 = std::max(0.0f, (d00 * d21 - d01 * d20) / den);
    if (b1 + b2 > 1) {
      float scale = 1 / (b1 + b2);
      b1 *= scale, b2 *= scale;
    }
    geo_->surface(a.shape, t, b1, b2, h);
    solid_pdf = 1 / total;
  } else {
    // Triangle by area, then a uniform point in it (u1 re-used within the chosen cell).
    float prob, ur;
    int t = a.triangles.sample_discrete(u1, prob, ur);
    float su = std::sqrt(ur);
    geo_->surface(a.shape, t, su * (1 - u2), su * u2, h); // barycentric (b1, b2)
  }
  Vec3 d = h.P - p;
  float d2 = dot(d, d);
  if (!(d2 > 0)) return false;
  out.dist = std::sqrt(d2);
  out.wi = d / out.dist;
  out.pdf = solid_pdf > 0 ? float(solid_pdf) : area_density(a, p, h);
  return out.pdf > 0 && std::isfinite(out.pdf);
}

float LightSet::area_density(const Area& a, const Vec3& p, const SurfaceHit& h) const {
  const scene::Shape& s = geo_->shapes()[a.shape];
  Vec3 d = h.P - p;
  float d2 = dot(d, d);
  if (!(d2 > 0)) return 0;
  if (s.kind == scene::Shape::Kind::Sphere) {
    Vec3 dc = s.center - p;
    float c2 = dot(dc, dc), r2 = s.radius * s.radius;
    if (c2 > r2 * 1.0001f) {
      float cos_max = std::sqrt(std::max(0.0f, 1 - r2 / c2));
      return 1.0f / (2 * kPi * std::max(1 - cos_max, 1e-7f));
    }
  } else if (SphericalRectangle r = rectangle(a, p); r.solid_angle > 0) {
    return 1 / r.solid_angle;
  } else if (double omega[kSolidAngleTriangles], total = solid_angles(a, p, omega); total > 0) {
    return float(1 / total);
  }
  float cos_l = std::abs(dot(h.Ng, d)) / std::sqrt(d2);
  if (!(cos_l > 1e-7f)) return 0;
  return d2 / (cos_l * a.total_area);
}

SphericalRectangle LightSet::rectangle(const Area& a, const Vec3& p) const {
  if (!a.rectangle) return SphericalRectangle({}, {}, {}, {});
  const scene::Shape& s = geo_->shapes()[a.shape];
  SphericalRectangle r(p, s.corner, s.edge_x, s.edge_y);
  if (r.solid_angle < kMinRectangleSolidAngle) r.solid_angle = 0;
  return r;
}

double LightSet::solid_angles(const Area& a, const Vec3& p, double* omega) {
  if (a.corners.empty()) return 0;
  double total = 0;
  for (size_t t = 0; t < a.corners.size(); ++t) {
    const std::array<Vec3, 3>& v = a.corners[t];
    omega[t] = triangle_solid_angle(v[0] - p, v[1] - p, v[2] - p);
    total += omega[t];
  }
  return total >= kMinSolidAngle ? total : 0;
}

float LightSet::pdf_area(const Vec3& p, const SurfaceHit& hit) const {
  if (!is_emitter(hit.shape)) return 0;
  int i = shape_to_area_[hit.shape];
  return select_.discrete_prob(int(points_.size()) + i) * area_density(areas_[i], p, hit);
}

Color3 LightSet::environment_hit(const Vec3& dir, const Vec3& n, float& pdf) const {
  if (!env_) {
    pdf = 0;
    return {};
  }
  Color3 L = env_->eval_pdf(dir, n, pdf);
  pdf *= select_.discrete_prob(count_ - 1);
  return L;
}

} // namespace lobe::render
