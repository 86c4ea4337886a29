// SceneServices (services.h).
#include "services.h"

#include "camera.h"
#include "geometry.h"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace lobe::render {

bool SceneServices::write(const scene::UserValue& v, DataType type, void* val) {
  if (v.is_text) {
    if (type != DataType{DataType::Base::String, 0}) return false;
    *static_cast<const char**>(val) = v.text.c_str();
    return true;
  }
  if (type.base == DataType::Base::String) return false;
  size_t n = size_t(type.elements()) * size_t(type.components());
  if (v.numbers.size() == 1 && type.is_triple() && type.arraylen == 0) { // grey, as in scenes
    std::fill_n(static_cast<float*>(val), 3, v.numbers[0]);
    return true;
  }
  if (v.numbers.size() != n) return false;
  if (type.base == DataType::Base::Int) {
    for (float x : v.numbers)
      if (x != std::floor(x) || std::abs(x) > 2147483520.0f) return false;
    for (size_t k = 0; k < n; ++k) static_cast<int32_t*>(val)[k] = int32_t(v.numbers[k]);
    return true;
  }
  std::memcpy(val, v.numbers.data(), n * sizeof(float));
  return true;
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
  scene::UserValue v;
  if (name == "camera:resolution")
    v.numbers = {float(width_), float(height_)};
  else if (name == "camera:fov")
    v.numbers = {camera_.fov};
  else if (name == "camera:pixelaspect")
    v.numbers = {1.0f};
  else if (name == "camera:projection") {
    v.text = "perspective";
    v.is_text = true;
  } else
    return index < 0 && get_userdata(sg, name, type, derivatives, val);
  if (index >= 0) { // one element of an array attribute
    if (v.is_text || size_t(index) >= v.numbers.size() || type.arraylen != 0) return false;
    v.numbers = {v.numbers[size_t(index)]};
  }
  if (v.is_text) { // a literal: it outlives the call
    if (type != DataType{DataType::Base::String, 0}) return false;
    *static_cast<const char**>(val) = "perspective";
    return true;
  }
  return write(v, type, val);
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
