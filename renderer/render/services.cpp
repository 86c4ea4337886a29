// SceneServices (services.h).
#include "services.h"

#include "camera.h"
#include "geometry.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <span>

namespace lobe::render {

namespace {

// A string answers a string request; `text` must outlive the call.
bool write_text(const char* text, DataType type, void* val) {
  if (type != DataType{DataType::Base::String, 0}) return false;
  *static_cast<const char**>(val) = text;
  return true;
}

// Numbers answer int (whole numbers only), float, triple, matrix or array requests of their
// count; one number is also a grey triple.
bool write_numbers(std::span<const float> v, DataType type, void* val) {
  if (type.base == DataType::Base::String) return false;
  size_t n = size_t(type.elements()) * size_t(type.components());
  if (v.size() == 1 && type.is_triple() && type.arraylen == 0) { // grey, as in scenes
    std::fill_n(static_cast<float*>(val), 3, v[0]);
    return true;
  }
  if (v.size() != n) return false;
  if (type.base == DataType::Base::Int) {
    for (float x : v)
      if (x != std::floor(x) || std::abs(x) > 2147483520.0f) return false;
    for (size_t k = 0; k < n; ++k) static_cast<int32_t*>(val)[k] = int32_t(v[k]);
    return true;
  }
  std::memcpy(val, v.data(), n * sizeof(float));
  return true;
}

} // namespace

bool SceneServices::write(const scene::UserValue& v, DataType type, void* val) {
  return v.is_text ? write_text(v.text.c_str(), type, val) : write_numbers(v.numbers, type, val);
}

bool SceneServices::get_userdata(const ShaderGlobals& sg, std::string_view name, DataType type,
                                 bool derivatives, void* val) const {
  (void)derivatives; // constant over the shape: zero derivatives (Lobe zeroed them)
  const auto* shape = static_cast<const scene::Shape*>(sg.renderstate);
  if (!shape) return false;
  for (const scene::UserValue& v : shape->userdata)
    if (v.name == name) return write(v, type, val);
  return false;
}

bool SceneServices::get_attribute(const ShaderGlobals& sg, std::string_view object,
                                  std::string_view name, int index, DataType type, bool derivatives,
                                  void* val) const {
  if (!object.empty()) return false;
  if (name == "camera:projection") return index < 0 && write_text("perspective", type, val);
  float v[2];
  size_t n = 1;
  if (name == "camera:resolution") {
    v[0] = float(width_), v[1] = float(height_);
    n = 2;
  } else if (name == "camera:fov") {
    v[0] = camera_.fov;
  } else if (name == "camera:pixelaspect") {
    v[0] = 1.0f;
  } else {
    return index < 0 && get_userdata(sg, name, type, derivatives, val);
  }
  if (index < 0) return write_numbers({v, n}, type, val);
  // One element of an array attribute.
  return size_t(index) < n && type.arraylen == 0 && write_numbers({v + index, 1}, type, val);
}

bool SceneServices::trace(const ShaderGlobals& sg, const TraceOptions& opt, const Vec3& P,
                          const Vec3& dPdx, const Vec3& dPdy, const Vec3& R, const Vec3& dRdx,
                          const Vec3& dRdy, TraceHit& hit) const {
  (void)dPdx, (void)dPdy, (void)dRdx, (void)dRdy;
  float len = length(R);
  if (!geometry_ || !(len > 0) || !std::isfinite(len) || !(opt.maxdist > opt.mindist)) return false;
  Vec3 dir = R / len;
  Vec3 start = P + dir * std::max(0.0f, opt.mindist);
  Ray ray;
  // Off the surface the ray leaves (a point away from any surface has Ng = 0: no offset).
  ray.org = is_zero(sg.Ng) ? start : offset_ray_origin(start, normalize(sg.Ng), dir);
  ray.dir = dir;
  ray.tmax = opt.maxdist - std::max(0.0f, opt.mindist);
  SurfaceHit h;
  if (!geometry_->intersect(ray, h)) return false;
  hit.hitdist = length(h.P - P);
  hit.P = h.P;
  hit.N = h.N;
  hit.Ng = h.Ng;
  hit.u = h.u;
  hit.v = h.v;
  return true;
}

} // namespace lobe::render
