// The Embree 3 scene: triangle meshes (quads become two triangles), native point spheres,
// closest-hit and occlusion queries, and the surface data at a hit (position, geometric and
// shading normals, uv, tangents).
//
// Robust ray origins: a new ray starts at the hit point pushed off the surface along the
// geometric normal by a few float ulps of the position (Waechter and Binder, "A Fast and
// Robust Method for Avoiding Self-Intersection", Ray Tracing Gems ch. 6), on the side the
// ray leaves towards; no epsilon in t, so there is neither acne nor leaking through thin parts.
#pragma once

#include "camera.h"
#include "scene.h"

#include <embree3/rtcore.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace lobe::render {

struct SurfaceHit {
  float t = 0;
  int shape = -1; // index into SceneDesc::shapes
  int prim = -1;  // triangle index within the shape (meshes, quads)
  Vec3 P, Ng, N;  // Ng, N: unit, facing as the geometry says (outwards for spheres)
  float u = 0, v = 0;
  Vec3 dPdu, dPdv;
};

// Scenes with more mesh triangles than this build their BVH at Embree's MEDIUM quality.
constexpr size_t kMediumBuildTriangles = 200000;

// Inline: two calls a path vertex.
inline Vec3 offset_ray_origin(const Vec3& p, const Vec3& ng, const Vec3& dir) {
  constexpr float kOrigin = 1.0f / 32.0f, kFloatScale = 1.0f / 65536.0f, kIntScale = 256.0f;
  Vec3 n = dot(ng, dir) < 0 ? -ng : ng;
  Vec3 out;
  for (int i = 0; i < 3; ++i) {
    int32_t of = static_cast<int32_t>(kIntScale * n[i]);
    int32_t bits = std::bit_cast<int32_t>(p[i]);
    float pi = std::bit_cast<float>(bits + (p[i] < 0 ? -of : of));
    out[i] = std::abs(p[i]) < kOrigin ? p[i] + kFloatScale * n[i] : pi;
  }
  return out;
}

class Geometry {
public:
  Geometry() = default;
  ~Geometry();
  Geometry(const Geometry&) = delete;
  Geometry& operator=(const Geometry&) = delete;

  // Builds the Embree scene from world-space shapes; "" or an error.
  std::string build(const std::vector<scene::Shape>& shapes);

  bool intersect(const Ray& ray, SurfaceHit& hit) const;
  // intersect() in its two halves (timed apart by --stats): Embree's traversal, then the
  // surface data at the hit it found.
  struct RawHit {
    float t = 0, u = 0, v = 0;
    unsigned geom = RTC_INVALID_GEOMETRY_ID;
    int prim = -1;
  };
  bool traverse(const Ray& ray, RawHit& raw) const;
  // traverse() for up to kPacket rays at once (Embree's 8-wide packets where the processor
  // has them, else one by one): the same hits, found faster for rays that start together and
  // point alike (a pixel's camera rays). raw[i].geom is RTC_INVALID_GEOMETRY_ID for a miss.
  static constexpr int kPacket = 8;
  void traverse_packet(const Ray* rays, int n, RawHit* raw) const;
  void complete(const Ray& ray, const RawHit& raw, SurfaceHit& hit) const;
  bool occluded(const Vec3& org, const Vec3& dir, float tmax) const;
  // Raw traversal only (no surface data), for benchmarks: Embree's own speed.
  bool intersect_raw(const Ray& ray, float& t) const;

  // Per shape: whether surface() computes a mesh's dPdu/dPdv (0: left zero, for materials that
  // read neither tangents nor derivatives). Unset: always.
  void set_tangents_needed(std::vector<char> needed) { tangents_ = std::move(needed); }

  // Surface data at (shape, prim, barycentric u, v) as intersect() fills it.
  void surface(int shape, int prim, float bu, float bv, SurfaceHit& hit) const;

  const std::vector<scene::Shape>& shapes() const { return *shapes_; }
  // Bounding sphere of everything.
  Vec3 center() const { return center_; }
  float radius() const { return radius_; }
  // World-space triangles of a mesh or quad shape (3 vertex indices each).
  const scene::Mesh& mesh(int shape) const { return *mesh_of_[size_t(shape)]; }

private:
  RTCDevice device_ = nullptr;
  RTCScene scene_ = nullptr;
  const std::vector<scene::Shape>* shapes_ = nullptr;
  // Per shape: its own mesh (read in place: a mesh shape's triangles are not copied), a quad's
  // two triangles (in quads_), or an empty mesh for a sphere.
  std::vector<const scene::Mesh*> mesh_of_;
  std::vector<std::unique_ptr<scene::Mesh>> quads_;
  // The triangles' vertices and indices as Embree reads them (shared with it, in huge pages;
  // each padded by one element: Embree reads the last with a 16-byte load). Destroyed after
  // the scene that uses them.
  struct TriangleBuffers {
    LargeVector<float> vertices;
    LargeVector<uint32_t> indices;
  };
  std::vector<TriangleBuffers> triangle_buffers_;
  std::vector<int> geom_to_shape_;
  std::vector<char> tangents_;
  bool packets_ = false; // Embree traces 8-wide packets natively here
  Vec3 center_;
  float radius_ = 1;
};

} // namespace lobe::render
