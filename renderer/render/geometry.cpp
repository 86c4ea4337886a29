// Embree scene construction and ray queries (see geometry.h).
#include "geometry.h"

#include "sampling.h"

#include <bit>
#include <cmath>
#include <cstring>

namespace lobe::render {

Geometry::~Geometry() {
  if (scene_) rtcReleaseScene(scene_);
  if (device_) rtcReleaseDevice(device_);
}

// LightSet::sample_area (lights.cpp) maps a point (s, t) of a rectangle onto these two
// triangles: keep their order and corners.
static scene::Mesh quad_mesh(const scene::Shape& s) {
  scene::Mesh m;
  m.positions = {s.corner, s.corner + s.edge_x, s.corner + s.edge_x + s.edge_y,
                 s.corner + s.edge_y};
  m.uvs = {0, 0, 1, 0, 1, 1, 0, 1};
  m.indices = {0, 1, 2, 0, 2, 3};
  return m;
}

std::string Geometry::build(const std::vector<scene::Shape>& shapes) {
  shapes_ = &shapes;
  device_ = rtcNewDevice(nullptr);
  if (!device_) return "cannot create the Embree device";
  scene_ = rtcNewScene(device_);
  packets_ = rtcGetDeviceProperty(device_, RTC_DEVICE_PROPERTY_NATIVE_RAY8_SUPPORTED) != 0;
  // BVH quality: HIGH (spatial splits) traces a little faster but builds two to three times
  // slower; past kMediumBuildTriangles triangles the build dominates set-up and MEDIUM is used
  // (on the 524k-triangle bench scene: build 0.55 s -> 0.2 s, render time unchanged within
  // noise; bench/embree_compare).
  size_t triangles = 0;
  for (const scene::Shape& s : shapes)
    if (s.kind == scene::Shape::Kind::Mesh) triangles += s.mesh.indices.size() / 3;
  rtcSetSceneBuildQuality(scene_, triangles > kMediumBuildTriangles ? RTC_BUILD_QUALITY_MEDIUM
                                                                    : RTC_BUILD_QUALITY_HIGH);
  static const scene::Mesh kNoMesh;
  mesh_of_.assign(shapes.size(), &kNoMesh);
  quads_.clear();
  triangle_buffers_.clear();
  triangle_buffers_.reserve(shapes.size());
  for (size_t i = 0; i < shapes.size(); ++i) {
    const scene::Shape& s = shapes[i];
    RTCGeometry g;
    if (s.kind == scene::Shape::Kind::Sphere) {
      g = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_SPHERE_POINT);
      auto* v = static_cast<float*>(
          rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4, 16, 1));
      v[0] = s.center.x, v[1] = s.center.y, v[2] = s.center.z, v[3] = s.radius;
    } else {
      if (s.kind == scene::Shape::Kind::Quad) {
        quads_.push_back(std::make_unique<scene::Mesh>(quad_mesh(s)));
        mesh_of_[i] = quads_.back().get();
      } else {
        mesh_of_[i] = &s.mesh;
      }
      const scene::Mesh& m = *mesh_of_[i];
      g = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
      TriangleBuffers& b = triangle_buffers_.emplace_back();
      b.vertices.resize(m.positions.size() * 3 + 1);
      std::memcpy(b.vertices.data(), m.positions.data(), m.positions.size() * 12);
      b.indices.resize(m.indices.size() + 1);
      std::memcpy(b.indices.data(), m.indices.data(), m.indices.size() * 4);
      rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, b.vertices.data(),
                                 0, 12, m.positions.size());
      rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, b.indices.data(), 0,
                                 12, m.indices.size() / 3);
    }
    rtcCommitGeometry(g);
    unsigned id = rtcAttachGeometry(scene_, g);
    rtcReleaseGeometry(g);
    if (geom_to_shape_.size() <= id) geom_to_shape_.resize(id + 1, -1);
    geom_to_shape_[id] = static_cast<int>(i);
  }
  rtcCommitScene(scene_);
  if (rtcGetDeviceError(device_) != RTC_ERROR_NONE) return "Embree failed to build the scene";
  RTCBounds b;
  rtcGetSceneBounds(scene_, &b);
  if (shapes.empty() || !(b.upper_x >= b.lower_x)) {
    center_ = {0, 0, 0}, radius_ = 1;
  } else {
    Vec3 lo{b.lower_x, b.lower_y, b.lower_z}, hi{b.upper_x, b.upper_y, b.upper_z};
    center_ = (lo + hi) * 0.5f;
    radius_ = std::max(1e-3f, length(hi - lo) * 0.5f);
  }
  return "";
}

bool Geometry::intersect_raw(const Ray& ray, float& t) const {
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  RTCRayHit rh;
  rh.ray.org_x = ray.org.x, rh.ray.org_y = ray.org.y, rh.ray.org_z = ray.org.z;
  rh.ray.dir_x = ray.dir.x, rh.ray.dir_y = ray.dir.y, rh.ray.dir_z = ray.dir.z;
  rh.ray.tnear = 0, rh.ray.tfar = ray.tmax, rh.ray.time = 0, rh.ray.mask = ~0u, rh.ray.flags = 0;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(scene_, &ctx, &rh);
  t = rh.ray.tfar;
  return rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
}

bool Geometry::traverse(const Ray& ray, RawHit& raw) const {
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  RTCRayHit rh;
  rh.ray.org_x = ray.org.x, rh.ray.org_y = ray.org.y, rh.ray.org_z = ray.org.z;
  rh.ray.dir_x = ray.dir.x, rh.ray.dir_y = ray.dir.y, rh.ray.dir_z = ray.dir.z;
  rh.ray.tnear = 0, rh.ray.tfar = ray.tmax, rh.ray.time = 0, rh.ray.mask = ~0u, rh.ray.flags = 0;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(scene_, &ctx, &rh);
  raw.geom = rh.hit.geomID;
  if (raw.geom == RTC_INVALID_GEOMETRY_ID) return false;
  raw.t = rh.ray.tfar, raw.u = rh.hit.u, raw.v = rh.hit.v, raw.prim = int(rh.hit.primID);
  return true;
}

void Geometry::traverse_packet(const Ray* rays, int n, RawHit* raw) const {
  if (!packets_ || n < 2) {
    for (int i = 0; i < n; ++i)
      if (!traverse(rays[i], raw[i])) raw[i].geom = RTC_INVALID_GEOMETRY_ID;
    return;
  }
  static_assert(kPacket == 8);
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  ctx.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
  alignas(32) int valid[8];
  alignas(32) RTCRayHit8 rh;
  for (int i = 0; i < 8; ++i) {
    const bool on = i < n;
    const Ray& r = rays[on ? i : 0];
    valid[i] = on ? -1 : 0;
    rh.ray.org_x[i] = r.org.x, rh.ray.org_y[i] = r.org.y, rh.ray.org_z[i] = r.org.z;
    rh.ray.dir_x[i] = r.dir.x, rh.ray.dir_y[i] = r.dir.y, rh.ray.dir_z[i] = r.dir.z;
    rh.ray.tnear[i] = 0, rh.ray.tfar[i] = r.tmax, rh.ray.time[i] = 0;
    rh.ray.mask[i] = ~0u, rh.ray.flags[i] = 0, rh.ray.id[i] = unsigned(i);
    rh.hit.geomID[i] = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0][i] = RTC_INVALID_GEOMETRY_ID;
  }
  rtcIntersect8(valid, scene_, &ctx, &rh);
  for (int i = 0; i < n; ++i) {
    RawHit& h = raw[i];
    h.geom = rh.hit.geomID[i];
    if (h.geom == RTC_INVALID_GEOMETRY_ID) continue;
    h.t = rh.ray.tfar[i], h.u = rh.hit.u[i], h.v = rh.hit.v[i], h.prim = int(rh.hit.primID[i]);
  }
}

void Geometry::complete(const Ray& ray, const RawHit& raw, SurfaceHit& hit) const {
  hit.t = raw.t;
  hit.P = ray.org + ray.dir * hit.t;
  surface(geom_to_shape_[raw.geom], raw.prim, raw.u, raw.v, hit);
}

bool Geometry::intersect(const Ray& ray, SurfaceHit& hit) const {
  RawHit raw;
  if (!traverse(ray, raw)) return false;
  complete(ray, raw, hit);
  return true;
}

bool Geometry::occluded(const Vec3& org, const Vec3& dir, float tmax) const {
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  RTCRay r;
  r.org_x = org.x, r.org_y = org.y, r.org_z = org.z;
  r.dir_x = dir.x, r.dir_y = dir.y, r.dir_z = dir.z;
  r.tnear = 0, r.tfar = tmax, r.time = 0, r.mask = ~0u, r.flags = 0;
  rtcOccluded1(scene_, &ctx, &r);
  return r.tfar < 0; // Embree sets tfar to -inf on a hit
}

// Tangents from the uv parametrisation of a triangle, or any frame when it is degenerate.
static void triangle_tangents(const Vec3 p[3], const float uv[6], const Vec3& ng, Vec3& dpdu,
                              Vec3& dpdv) {
  float du1 = uv[2] - uv[0], dv1 = uv[3] - uv[1], du2 = uv[4] - uv[0], dv2 = uv[5] - uv[1];
  float det = du1 * dv2 - dv1 * du2;
  Vec3 e1 = p[1] - p[0], e2 = p[2] - p[0];
  if (std::abs(det) > 1e-12f) {
    float inv = 1.0f / det;
    dpdu = (e1 * dv2 - e2 * dv1) * inv;
    dpdv = (e2 * du1 - e1 * du2) * inv;
    if (is_finite(dpdu) && is_finite(dpdv) && !is_zero(cross(dpdu, dpdv))) return;
  }
  Frame f(ng);
  dpdu = f.t, dpdv = f.b;
}

void Geometry::surface(int shape, int prim, float bu, float bv, SurfaceHit& hit) const {
  const scene::Shape& s = (*shapes_)[shape];
  hit.shape = shape;
  hit.prim = prim;
  if (s.kind == scene::Shape::Kind::Sphere) {
    Vec3 d = normalize(hit.P - s.center);
    if (is_zero(d)) d = {0, 1, 0};
    hit.P = s.center + d * s.radius; // re-project: the hit point is exactly on the sphere
    hit.Ng = hit.N = d;
    hit.u = 0.5f + std::atan2(d.x, d.z) / (2 * kPi);
    hit.v = std::acos(std::clamp(d.y, -1.0f, 1.0f)) / kPi;
    float st = std::sqrt(std::max(0.0f, 1 - d.y * d.y));
    hit.dPdu = Vec3{d.z, 0, -d.x} * (2 * kPi * s.radius);
    // dP/dv = pi r (cos(theta) sin(phi), -sin(theta), cos(theta) cos(phi)), with
    // sin(phi) = x / sin(theta), cos(phi) = z / sin(theta) (no second atan2).
    float inv = st > 1e-7f ? 1.0f / st : 0.0f;
    hit.dPdv = Vec3{d.y * d.x * inv, -st, d.y * d.z * inv} * (kPi * s.radius);
    return;
  }
  const scene::Mesh& m = *mesh_of_[size_t(shape)];
  const uint32_t* tri = &m.indices[3 * size_t(prim)];
  Vec3 p[3] = {m.positions[tri[0]], m.positions[tri[1]], m.positions[tri[2]]};
  float b0 = 1 - bu - bv;
  hit.Ng = normalize(cross(p[1] - p[0], p[2] - p[0]));
  hit.P = p[0] * b0 + p[1] * bu + p[2] * bv;
  float uv[6] = {0, 0, 1, 0, 0, 1};
  if (!m.uvs.empty())
    for (int k = 0; k < 3; ++k)
      uv[2 * k] = m.uvs[2 * tri[k]], uv[2 * k + 1] = m.uvs[2 * tri[k] + 1];
  hit.u = uv[0] * b0 + uv[2] * bu + uv[4] * bv;
  hit.v = uv[1] * b0 + uv[3] * bu + uv[5] * bv;
  if (tangents_.empty() || tangents_[size_t(shape)])
    triangle_tangents(p, uv, hit.Ng, hit.dPdu, hit.dPdv);
  else
    hit.dPdu = hit.dPdv = Vec3{};
  hit.N = hit.Ng;
  if (!m.normals.empty()) {
    Vec3 n = normalize(m.normals[tri[0]] * b0 + m.normals[tri[1]] * bu + m.normals[tri[2]] * bv);
    // Keep the shading normal on the geometric normal's side (bad normals otherwise leak).
    if (!is_zero(n)) hit.N = dot(n, hit.Ng) < 0 ? -n : n;
  }
}

} // namespace lobe::render
