// Every light of a scene behind one interface for next-event estimation and MIS:
// point and spot lights (delta positions), emissive shapes (area lights), and the environment.
// A sphere is sampled by the cone it subtends; a rectangle (a quad with edges at right angles)
// by its solid angle (SphericalRectangle) unless that is below kMinRectangleSolidAngle; below
// it, and any other shape of at most kSolidAngleTriangles triangles, by the solid angle its
// triangles subtend, each triangle picked by its share and a direction uniform in it
// (sample_spherical_triangle), unless that is below kMinSolidAngle. Far away or edge-on the
// two densities are alike and area is cheaper: there, and for larger meshes, a triangle is
// picked by area and a point uniform in it.
//
// One light is picked per shading point with probability proportional to an estimate of its
// power (point: 4 pi I, spot: its cone's solid angle times I, area: pi A L, environment:
// pi^2 R^2 L_avg, the irradiance pi L_avg through the cross-section pi R^2 of a scene of
// bounding radius R). pdf() returns the same
// selection-times-density that sample() reports, so a BSDF-sampled ray that hits an emitter can
// be weighted against light sampling.
#pragma once

#include "distribution.h"
#include "environment.h"
#include "geometry.h"
#include "spherical_triangle.h"

#include <array>
#include <memory>
#include <vector>

namespace lobe::render {

struct LightSample {
  enum class Kind { Point, Area, Environment } kind = Kind::Point;
  Vec3 wi;            // unit, from the shading point towards the light
  float dist = 0;     // distance to the light point (infinity for the environment)
  Color3 L;           // arriving radiance/intensity; for Area the caller shades the emitter
  float pdf = 0;      // selection probability x solid-angle density (delta: selection only)
  SurfaceHit surface; // Area: the point on the emitter
};

class LightSet {
public:
  struct Emitter {
    int shape = -1;
    float power = 0; // luminance power estimate (pi * area * radiance)
  };

  void build(const Geometry& geo, const std::vector<scene::Light>& lights,
             const std::vector<Emitter>& emitters, const EnvironmentLight* env);
  bool empty() const { return count_ == 0; }
  int count() const { return count_; }

  // Samples one light as seen from `p` on a surface of unit normal `n` (turned towards the
  // side being lit; the environment may sample its hemisphere); false if nothing can be sampled.
  bool sample(const Vec3& p, const Vec3& n, float u_select, float u1, float u2,
              LightSample& out) const;
  // Selection x solid-angle density of reaching emitter point `hit` from `p` by sample().
  float pdf_area(const Vec3& p, const SurfaceHit& hit) const;
  // The environment's radiance along `dir` and, in `pdf`, the selection x density of sample()
  // from a point of normal `n` reaching it along `dir` (EnvironmentLight::pdf), with one lookup.
  Color3 environment_hit(const Vec3& dir, const Vec3& n, float& pdf) const;
  bool is_emitter(int shape) const {
    return shape >= 0 && shape < int(shape_to_area_.size()) && shape_to_area_[shape] >= 0;
  }
  const EnvironmentLight* environment() const { return env_; }

private:
  static constexpr int kSolidAngleTriangles = 8;
  static constexpr double kMinSolidAngle = 1e-4;          // steradians
  static constexpr float kMinRectangleSolidAngle = 1e-3f; // float: a few 1e-7 sr of error

  struct Area {
    int shape;
    float total_area = 0;
    Distribution1D triangles;                 // by area (meshes and quads)
    std::vector<std::array<Vec3, 3>> corners; // small meshes: their triangles, for solid angles
    bool rectangle = false;                   // a quad with edges at right angles
  };
  // A rectangle's solid angle from `p` (SphericalRectangle), its solid_angle 0 when `a` is no
  // rectangle or subtends less than kMinRectangleSolidAngle from `p`.
  SphericalRectangle rectangle(const Area& a, const Vec3& p) const;
  // A small mesh's triangles' solid angles from `p` into `omega` (kSolidAngleTriangles of
  // them) and their sum; 0 when the shape is sampled by area from `p`.
  static double solid_angles(const Area& a, const Vec3& p, double* omega);
  bool sample_area(const Area& a, const Vec3& p, float u1, float u2, LightSample& out) const;
  float area_density(const Area& a, const Vec3& p, const SurfaceHit& hit) const;

  const Geometry* geo_ = nullptr;
  const EnvironmentLight* env_ = nullptr;
  std::vector<scene::Light> points_; // point and spot
  std::vector<Area> areas_;
  std::vector<int> shape_to_area_;
  Distribution1D select_; // over points_, then areas_, then the environment
  int count_ = 0;
};

} // namespace lobe::render
